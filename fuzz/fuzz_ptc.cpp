// libFuzzer harness: a PTC response as a sensor might send it. The first byte picks the command
// the client asked for; the rest is the response (header, then payload). The harness checks the
// header as the client does (with the command's bound and with a tight one), then runs every
// payload parser on what follows, and checks what each promises: texts NUL-ended within their
// arrays, at most nine temperatures, outputs untouched on error.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz_common.h"
#include "hesai/ptc.h"
#include "hesai/ptc_settings.h"

namespace {

constexpr hesai::ptc::Command kCommands[] = {
    hesai::ptc::Command::calibration,     hesai::ptc::Command::inventory,       hesai::ptc::Command::config,
    hesai::ptc::Command::status,          hesai::ptc::Command::signature_state, hesai::ptc::Command::signature_start,
    hesai::ptc::Command::signature_stop,  hesai::ptc::Command::channel_config,  hesai::ptc::Command::firetimes,
};

template <std::size_t N>
void check_text(const char (&s)[N]) {
  hesai_fuzz::check(std::memchr(s, '\0', N) != nullptr);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using hesai::ByteView;
  using hesai::Error;
  using hesai_fuzz::check;
  namespace ptc = hesai::ptc;
  if (size == 0) return 0;
  const ptc::Command command = kCommands[data[0] % (sizeof kCommands / sizeof kCommands[0])];
  const hesai_fuzz::ExactCopy in(data + 1, size - 1);
  const ByteView response = in.view();

  ptc::Header h;
  const Error e = ptc::check_response(response, command, ptc::max_response_bytes(command), h);
  hesai_fuzz::check_named(e);
  check(e == Error::ok || e == Error::truncated || e == Error::ptc_bad_magic || e == Error::ptc_command_mismatch ||
        e == Error::ptc_length_exceeds_bound || e == Error::ptc_sensor_error);
  check((e == Error::truncated) == (response.size < ptc::kHeaderBytes));
  if (e != Error::truncated && e != Error::ptc_bad_magic) {
    check(h.command == response[2] && h.return_code == response[3] && h.length == hesai::load_be32(response.data + 4));
    check(e != Error::ok || (h.length <= ptc::max_response_bytes(command) && h.return_code == 0));
    // A tighter bound never accepts more.
    ptc::Header tight;
    const Error t = ptc::check_response(response, command, h.length == 0 ? 0 : h.length - 1, tight);
    check(h.length == 0 ? t == e : (t == e || t == Error::ptc_length_exceeds_bound));
  }
  if (response.size < ptc::kHeaderBytes) return 0;
  const ByteView payload{response.data + ptc::kHeaderBytes, response.size - ptc::kHeaderBytes};

  ptc::Inventory inv;
  if (ptc::parse_inventory(payload, inv) == Error::ok) {
    check(payload.size >= ptc::kInvCommonBytes);
    check_text(inv.serial);
    check_text(inv.manufacture_date);
    check_text(inv.software_version);
    check_text(inv.hardware_version);
    check_text(inv.control_firmware);
    check_text(inv.sensor_firmware);
    check(inv.has_model == (payload.size >= ptc::kInvBytes));
    check(inv.has_model || inv.model == hesai::Model::unknown);
  } else {
    check(payload.size < ptc::kInvCommonBytes && inv.serial[0] == '\0' && !inv.has_model);
  }
  ptc::Config cfg;
  check((ptc::parse_config(payload, cfg) == Error::ok) == (payload.size >= ptc::kConfigBaseBytes));
  check(cfg.has_extra == (payload.size >= ptc::kConfigBaseBytes + 3));
  for (std::size_t m = 0; m < hesai::kModelCount; ++m) {
    const auto model = static_cast<hesai::Model>(m);
    ptc::Status s;
    const Error se = ptc::parse_status(payload, model, s);
    const std::size_t temps = ptc::status_temperature_count(model);
    check(temps <= ptc::kMaxTemperatures);
    check((se == Error::ok) == (payload.size >= ptc::status_bytes(temps)));
    check(se == Error::ok ? s.temperature_count == temps : s.temperature_count == 0);
  }
  std::uint8_t random[ptc::kRandomBytes] = {};
  const Error re = ptc::parse_session_start(payload, random);
  check((re == Error::ok) == (payload.size == ptc::kRandomBytes));
  if (re == Error::ok) check(std::memcmp(random, payload.data, sizeof random) == 0);
  bool on = false;
  check((ptc::parse_signature_state(payload, on) == Error::ok) == (payload.size == 1));
  // The settings (hesai/ptc_settings.h): a set request as the stand-in reads it, with the
  // response's command byte; what parses encodes back to the same bytes.
  ptc::Setting setting;
  ptc::Settings settings;
  const Error pe = ptc::parse_setting(response[2], payload, setting, settings);
  hesai_fuzz::check_named(pe);
  if (pe == Error::ok) {
    std::uint8_t again[ptc::kMaxSetPayloadBytes];
    std::size_t n = 0;
    ptc::encode_setting(setting, settings, again, n);
    check(n == payload.size && std::memcmp(again, payload.data, n) == 0);
    check(static_cast<std::uint8_t>(ptc::set_command(setting)) == response[2]);
  }
  ptc::Fov fov;
  check((ptc::parse_fov(payload, fov) == Error::ok) == (payload.size >= 5));
  ptc::PtpDiagStatus diag;
  check((ptc::parse_ptp_diag_status(payload, diag) == Error::ok) == (payload.size >= ptc::kPtpDiagStatusBytes));
  return 0;
}
