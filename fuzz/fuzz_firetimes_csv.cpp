// libFuzzer harness: parse_firetime_csv for each model's channel count; a parsed file goes to a Decoder.
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
  static hesai::FiretimeCorrection a, b;
  for (const hesai::Model model : {hesai::Model::pandar40p, hesai::Model::pandar64, hesai::Model::qt128c2x,
                                    hesai::Model::pandar_xt16, hesai::Model::pandar_xt32m2x}) {
    const std::size_t n = hesai::channel_count(model);
    const hesai::ParseResult r = hesai::parse_firetime_csv(in.view(), n, a);
    const hesai::ParseResult r2 = hesai::parse_firetime_csv(in.view(), n, b);
    hesai_fuzz::check_named(r.error);
    check(r.error == r2.error && r.line == r2.line);
    if (r.error != hesai::Error::ok) {
      check(a.channels == 0 && r.line >= 1);
      continue;
    }
    check(r.line == 0 && a.channels == n && (a.loops == 1 || a.loops == 2) && a.loops == b.loops);
    for (std::size_t ch = 0; ch < n; ++ch) {
      bool fires = false;
      for (std::size_t loop = 0; loop < a.loops; ++loop) {
        check(std::isfinite(a.firetime_us[loop][ch]));
        check(hesai_fuzz::same_bits(a.firetime_us[loop][ch], b.firetime_us[loop][ch]));
        check(a.fires[loop][ch] == b.fires[loop][ch]);
        fires = fires || a.fires[loop][ch];
      }
      check(fires);  // every channel fires in some loop
    }
    hesai::Decoder d(model);
    bool in_range = true;
    for (std::size_t loop = 0; loop < a.loops; ++loop)
      for (std::size_t ch = 0; ch < n; ++ch)
        in_range = in_range && (!a.fires[loop][ch] || std::fabs(a.firetime_us[loop][ch]) <= 1000);
    const hesai::Error e = d.set_firetimes(a);
    // The seed packet decodes under any accepted file, except where the file rests a QT128 channel
    // that holds data in the packet (QT128C2X manual 3.1.2: a resting channel's bytes are 0).
    if (e == hesai::Error::ok) {
      const hesai::Error de = hesai_fuzz::decode_checked(d, seed_packet(model));
      check(de == hesai::Error::ok || (model == hesai::Model::qt128c2x && de == hesai::Error::resting_channel_data));
    }
    // A QT128 decoder refuses a one-loop file; every decoder refuses times beyond 1 ms.
    if (model == hesai::Model::qt128c2x && a.loops == 1)
      check(e == hesai::Error::calib_channel_count);
    else
      check(e == (in_range ? hesai::Error::ok : hesai::Error::invalid_argument));
  }
  return 0;
}
