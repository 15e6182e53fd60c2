// PTC settings: set payloads, read-back, allowed values, names (hesai/ptc_settings.h has the
// source of each).
#include "hesai/ptc_settings.h"

#include "model_facts.h"

namespace hesai::ptc {
namespace {

constexpr const char* kSettingNames[kSettingCount] = {"rpm", "return_mode", "standby", "sync_angle", "destination", "fov"};
constexpr Command kSetCommands[kSettingCount] = {Command::set_spin_rate,  Command::set_return_mode, Command::set_standby,
                                                 Command::set_sync_angle, Command::set_destination, Command::set_fov};
constexpr std::size_t kSetPayloadBytes[kSettingCount] = {2, 1, 1, 3, 8, 5};

// Return-mode names by code 0..5 (nebula's XT and QT128 table).
constexpr const char* kReturnModes[kReturnModeNames] = {"last",       "strongest",      "last_strongest",
                                                        "first",      "last_first",     "first_strongest"};

bool same_text(const char* a, std::size_t size, const char* b) noexcept {
  std::size_t i = 0;
  for (; i < size; ++i)
    if (b[i] == '\0' || a[i] != b[i]) return false;
  return b[i] == '\0';
}

void put_be16(std::uint8_t* p, std::uint16_t v) noexcept {
  p[0] = static_cast<std::uint8_t>(v >> 8);
  p[1] = static_cast<std::uint8_t>(v);
}

const char* listed(const char* const* names, std::size_t count, std::uint8_t code) noexcept {
  return code < count ? names[code] : "unknown";
}

}  // namespace

const char* setting_name(Setting setting) noexcept {
  const auto i = static_cast<std::size_t>(setting);
  return i < kSettingCount ? kSettingNames[i] : "unknown";
}

bool setting_from_name(const char* name, std::size_t size, Setting& out) noexcept {
  for (std::size_t i = 0; i < kSettingCount; ++i)
    if (same_text(name, size, kSettingNames[i])) {
      out = static_cast<Setting>(i);
      return true;
    }
  return false;
}

Command set_command(Setting setting) noexcept { return kSetCommands[static_cast<std::size_t>(setting) % kSettingCount]; }

void settings_from_config(const Config& c, Settings& out) noexcept {
  Settings s;
  s.rpm = c.spin_rate_rpm;
  s.return_mode = c.return_mode;
  s.standby = c.standby_mode;
  s.sync = c.sync;
  s.sync_angle = static_cast<std::uint16_t>((c.sync_angle + 50u) / 100u);
  for (std::size_t i = 0; i < 4; ++i) s.destination_ip[i] = c.destination_ip[i];
  s.destination_port = c.destination_port;
  s.gps_port = c.gps_port;
  s.fov_start = c.start_angle;
  s.fov_end = c.stop_angle;
  out = s;
}

bool same_setting(Setting setting, const Settings& a, const Settings& b) noexcept {
  switch (setting) {
    case Setting::rpm: return a.rpm == b.rpm;
    case Setting::return_mode: return a.return_mode == b.return_mode;
    case Setting::standby: return a.standby == b.standby;
    case Setting::sync_angle: return a.sync == b.sync && (a.sync == 0 || a.sync_angle == b.sync_angle);
    case Setting::destination:
      return a.destination_ip[0] == b.destination_ip[0] && a.destination_ip[1] == b.destination_ip[1] &&
             a.destination_ip[2] == b.destination_ip[2] && a.destination_ip[3] == b.destination_ip[3] &&
             a.destination_port == b.destination_port && a.gps_port == b.gps_port;
    case Setting::fov: return a.fov_start == b.fov_start && a.fov_end == b.fov_end;
  }
  return false;
}

void encode_setting(Setting setting, const Settings& v, std::uint8_t out[kMaxSetPayloadBytes], std::size_t& size) noexcept {
  switch (setting) {
    case Setting::rpm: put_be16(out, v.rpm); break;
    case Setting::return_mode: out[0] = v.return_mode; break;
    case Setting::standby: out[0] = v.standby; break;
    case Setting::sync_angle:
      out[0] = v.sync;
      put_be16(out + 1, v.sync_angle);
      break;
    case Setting::destination:
      for (std::size_t i = 0; i < 4; ++i) out[i] = v.destination_ip[i];
      put_be16(out + 4, v.destination_port);
      put_be16(out + 6, v.gps_port);
      break;
    case Setting::fov:
      out[0] = 0;  // one range for all channels
      put_be16(out + 1, v.fov_start);
      put_be16(out + 3, v.fov_end);
      break;
  }
  size = kSetPayloadBytes[static_cast<std::size_t>(setting) % kSettingCount];
}

Error parse_setting(std::uint8_t command, ByteView payload, Setting& setting, Settings& out) noexcept {
  std::size_t i = 0;
  while (i < kSettingCount && static_cast<std::uint8_t>(kSetCommands[i]) != command) ++i;
  if (i == kSettingCount) return Error::ptc_command_mismatch;
  if (payload.size != kSetPayloadBytes[i]) return Error::ptc_payload_length;
  const std::uint8_t* p = payload.data;
  setting = static_cast<Setting>(i);
  switch (setting) {
    case Setting::rpm: out.rpm = load_be16(p); break;
    case Setting::return_mode: out.return_mode = p[0]; break;
    case Setting::standby: out.standby = p[0]; break;
    case Setting::sync_angle:
      out.sync = p[0];
      out.sync_angle = load_be16(p + 1);
      break;
    case Setting::destination:
      for (std::size_t k = 0; k < 4; ++k) out.destination_ip[k] = p[k];
      out.destination_port = load_be16(p + 4);
      out.gps_port = load_be16(p + 6);
      break;
    case Setting::fov:
      if (p[0] != 0) return Error::invalid_argument;  // only the one-range method is read here
      out.fov_start = load_be16(p + 1);
      out.fov_end = load_be16(p + 3);
      break;
  }
  return Error::ok;
}

// ---- What each model allows ----

std::size_t allowed_spin_rates(Model model, std::uint16_t rates[kMaxSpinRates]) noexcept {
  static constexpr std::uint16_t kRates[kMaxSpinRates] = {300, 600, 1200};
  std::size_t n = 0;
  for (std::size_t bit = 0; bit < kMaxSpinRates; ++bit)
    if ((static_cast<unsigned>(detail::facts(model).spin_rates) >> bit) & 1u) rates[n++] = kRates[bit];
  return n;
}

bool spin_rate_over_http(Model model) noexcept { return detail::facts(model).spin_over_http; }

bool fov_supported(Model model) noexcept { return detail::facts(model).fov; }

const char* return_mode_name(Model model, std::uint8_t code) noexcept {
  const char* codes = detail::facts(model).return_codes;
  for (std::size_t c = 0; codes[c] != '\0'; ++c)
    if (c == code) return codes[c] == '-' ? nullptr : kReturnModes[codes[c] - '0'];
  return nullptr;
}

bool return_mode_code(Model model, const char* name, std::size_t size, std::uint8_t& code) noexcept {
  for (std::uint8_t c = 0; c < kReturnModeNames; ++c) {
    const char* n = return_mode_name(model, c);
    if (n != nullptr && same_text(name, size, n)) {
      code = c;
      return true;
    }
  }
  return false;
}

// ---- Names ----

const char* clock_source_name(std::uint8_t code) noexcept {
  static constexpr const char* kNames[] = {"GPS", "PTP"};
  return listed(kNames, 2, code);
}
const char* trigger_method_name(std::uint8_t code) noexcept {
  static constexpr const char* kNames[] = {"time-based", "angle-based"};
  return listed(kNames, 2, code);
}
const char* standby_name(std::uint8_t code) noexcept {
  static constexpr const char* kNames[] = {"in operation", "standby"};
  return listed(kNames, 2, code);
}
const char* motor_direction_name(std::uint8_t code) noexcept {
  static constexpr const char* kNames[] = {"clockwise", "counter-clockwise"};
  return listed(kNames, 2, code);
}
const char* on_off_name(std::uint8_t code) noexcept {
  static constexpr const char* kNames[] = {"off", "on"};
  return listed(kNames, 2, code);
}
const char* reflectivity_mapping_name(std::uint8_t code) noexcept {
  static constexpr const char* kNames[] = {"linear", "nonlinear"};
  return listed(kNames, 2, code);
}

// ---- FOV ----

Error parse_fov(ByteView payload, Fov& out) noexcept {
  if (payload.size < 5) return Error::ptc_payload_length;
  out.method = payload.data[0];
  out.start = load_be16(payload.data + 1);
  out.end = load_be16(payload.data + 3);
  return Error::ok;
}

// ---- PTP diagnostics ----

Error parse_ptp_diag_status(ByteView payload, PtpDiagStatus& out) noexcept {
  if (payload.size < kPtpDiagStatusBytes) return Error::ptc_payload_length;
  const std::uint8_t* p = payload.data;
  const std::uint64_t offset = static_cast<std::uint64_t>(load_be32(p)) << 32 | load_be32(p + 4);
  out.master_offset = static_cast<std::int64_t>(offset);
  out.ptp_state = static_cast<std::int32_t>(load_be32(p + 8));
  out.elapsed_ms = static_cast<std::int32_t>(load_be32(p + 12));
  return Error::ok;
}

// ---- Time source ----

const char* time_source_name(TimeSource source) noexcept {
  switch (source) {
    case TimeSource::ptp: return "ptp";
    case TimeSource::gps: return "gps";
    case TimeSource::free_run: break;
  }
  return "free_run";
}

TimeSource time_source(std::uint8_t clock_source, const Status& status) noexcept {
  if (clock_source == 1) return status.ptp_status == 1 || status.ptp_status == 2 ? TimeSource::ptp : TimeSource::free_run;
  if (clock_source == 0) return status.gps_pps_lock == 1 && status.gprmc_status == 1 ? TimeSource::gps : TimeSource::free_run;
  return TimeSource::free_run;
}

}  // namespace hesai::ptc
