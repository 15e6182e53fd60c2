// libFuzzer harness: one UDP payload through QT128C2X decoders (firing-time correction on and
// off). Both unit sizes (flags bit 4) come from the input. For customised packets (flags bit 6)
// the decoders hold a channel configuration for the header's laser num N (Loop1: channels 1..N,
// Loop2: 128 down to 129 - N); a decoder without one must refuse what they decode
// (channel_config_required), and one configured for another N must too (channel_config_mismatch).
#include <cstddef>
#include <cstdint>

#include "fuzz_common.h"
#include "hesai/calibration.h"
#include "hesai/detail/qt128_packet.h"

namespace {

hesai::ChannelConfig config_for(std::size_t lasers) {
  hesai::ChannelConfig c;
  c.laser_num = static_cast<std::uint16_t>(lasers);
  c.block_num = 2;
  c.loops = 2;
  for (std::size_t j = 0; j < lasers; ++j) {
    c.channel[0][j] = static_cast<std::uint8_t>(j + 1);
    c.channel[1][j] = static_cast<std::uint8_t>(128 - j);
  }
  return c;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hesai;
  const hesai_fuzz::ExactCopy in(data, size);
  static Decoder decoder(Model::qt128c2x);
  static Decoder plain(Model::qt128c2x);
  static Decoder unconfigured(Model::qt128c2x);
  static Decoder mismatched(Model::qt128c2x);
  plain.set_firetime_correction(false);
  const bool custom = size > qt128::kFlags && (data[qt128::kFlags] & qt128::kFlagChannelCustom) != 0;
  const std::size_t lasers = size > qt128::kLaserNum ? data[qt128::kLaserNum] : 0;
  if (custom && lasers >= 1 && lasers <= qt128::kChannels) {
    const ChannelConfig c = config_for(lasers);
    hesai_fuzz::check(decoder.set_channel_config(c) == Error::ok && plain.set_channel_config(c) == Error::ok);
    hesai_fuzz::check(mismatched.set_channel_config(config_for(lasers == 128 ? 1 : lasers + 1)) == Error::ok);
  }
  const Error e = hesai_fuzz::decode_checked(decoder, in.view());
  hesai_fuzz::check(hesai_fuzz::decode_checked(plain, in.view()) == e);
  const Error u = hesai_fuzz::decode_checked(unconfigured, in.view());
  const Error m = hesai_fuzz::decode_checked(mismatched, in.view());
  if (!custom) {
    hesai_fuzz::check(u == e && m == e);
  } else if (e == Error::ok) {
    hesai_fuzz::check(u == Error::channel_config_required && m == Error::channel_config_mismatch);
  } else {
    hesai_fuzz::check((u == e || u == Error::channel_config_required) && (m == e || m == Error::channel_config_mismatch));
  }
  return 0;
}
