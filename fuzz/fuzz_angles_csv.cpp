// libFuzzer harness: parse_angle_csv for each model's channel count; a parsed file goes to a Decoder.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_common.h"
#include "hesai/calibration.h"
#include "seed_packets.h"

using hesai_fuzz::seed_packet;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const hesai_fuzz::ExactCopy in(data, size);
  using hesai_fuzz::check;
  static hesai::AngleCorrection a, b;
  for (const hesai::Model model : {hesai::Model::pandar40p, hesai::Model::pandar64, hesai::Model::qt128c2x,
                                    hesai::Model::pandar_xt16, hesai::Model::pandar_xt32m2x}) {
    const std::size_t n = hesai::channel_count(model);
    const hesai::ParseResult r = hesai::parse_angle_csv(in.view(), n, a);
    const hesai::ParseResult r2 = hesai::parse_angle_csv(in.view(), n, b);
    hesai_fuzz::check_named(r.error);
    check(r.error == r2.error && r.line == r2.line);
    if (r.error != hesai::Error::ok) {
      check(a.channels == 0 && r.line >= 1);
      continue;
    }
    check(r.line == 0 && a.channels == n && b.channels == n);
    for (std::size_t i = 0; i < n; ++i) {
      check(std::isfinite(a.elevation_deg[i]) && std::isfinite(a.azimuth_deg[i]));
      check(hesai_fuzz::same_bits(a.elevation_deg[i], b.elevation_deg[i]) &&
            hesai_fuzz::same_bits(a.azimuth_deg[i], b.azimuth_deg[i]));
    }
    hesai::Decoder d(model);
    bool in_range = true;
    for (std::size_t i = 0; i < n; ++i)
      in_range = in_range && std::fabs(a.elevation_deg[i]) <= 90 && std::fabs(a.azimuth_deg[i]) <= 360;
    const hesai::Error e = d.set_angles(a);
    check(e == (in_range ? hesai::Error::ok : hesai::Error::invalid_argument));
    if (!in_range) continue;
    // Any parsed geometry gives finite points in range.
    check(hesai_fuzz::decode_checked(d, seed_packet(model)) == hesai::Error::ok);
  }
  // A channel count no model has is refused without reading the text.
  check(hesai::parse_angle_csv(in.view(), 0, a).error == hesai::Error::invalid_argument && a.channels == 0);
  check(hesai::parse_angle_csv(in.view(), hesai::kMaxChannels + 1, a).error == hesai::Error::invalid_argument);
  return 0;
}
