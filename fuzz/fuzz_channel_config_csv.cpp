// libFuzzer harness: parse_channel_config_csv.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz_common.h"
#include "hesai/calibration.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const hesai_fuzz::ExactCopy in(data, size);
  using hesai_fuzz::check;
  static hesai::ChannelConfig a, b;
  const hesai::ParseResult r = hesai::parse_channel_config_csv(in.view(), a);
  const hesai::ParseResult r2 = hesai::parse_channel_config_csv(in.view(), b);
  hesai_fuzz::check_named(r.error);
  check(r.error == r2.error && r.line == r2.line);
  if (r.error != hesai::Error::ok) {
    check(a.laser_num == 0 && r.line >= 1);
    return 0;
  }
  check(r.line == 0 && a.laser_num >= 1 && a.laser_num <= hesai::kMaxChannels && a.block_num >= 1);
  check((a.loops == 1 || a.loops == 2) && a.hash_length <= a.hash.size());
  check(a.laser_num == b.laser_num && a.block_num == b.block_num && a.loops == b.loops &&
        a.hash_length == b.hash_length && std::memcmp(a.hash.data(), b.hash.data(), a.hash_length) == 0);
  for (std::size_t loop = 0; loop < a.loops; ++loop) {
    bool seen[hesai::kMaxChannels + 1] = {};
    for (std::size_t i = 0; i < a.laser_num; ++i) {
      const std::uint8_t ch = a.channel[loop][i];
      check(ch >= 1 && ch <= hesai::kMaxChannels && !seen[ch]);  // 1..128, no channel twice in a loop
      seen[ch] = true;
      check(b.channel[loop][i] == ch);
    }
  }
  return 0;
}
