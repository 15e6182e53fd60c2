// libFuzzer harness: one UDP payload through PandarQT64 decoders (point cloud protocol 3.1;
// firing-time correction on and off, and a decoder under the unit's angle file values set by hand
// to the extremes the decoder accepts, so that any accepted geometry gives points in range).
#include <cstddef>
#include <cstdint>

#include "fuzz_common.h"

namespace {

hesai::AngleCorrection extreme_angles() {
  hesai::AngleCorrection a;
  a.channels = 64;
  for (std::size_t i = 0; i < 64; ++i) {
    a.elevation_deg[i] = (i % 2 != 0) ? 90.0 : -90.0;
    a.azimuth_deg[i] = (i % 3 == 0) ? 360.0 : -360.0 + static_cast<double>(i);
  }
  return a;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const hesai_fuzz::ExactCopy in(data, size);
  static hesai::Decoder decoder(hesai::Model::pandar_qt64);
  static hesai::Decoder plain(hesai::Model::pandar_qt64);
  static hesai::Decoder extreme(hesai::Model::pandar_qt64);
  plain.set_firetime_correction(false);
  hesai_fuzz::check(extreme.set_angles(extreme_angles()) == hesai::Error::ok);
  const hesai::Error e = hesai_fuzz::decode_checked(decoder, in.view());
  hesai_fuzz::check(hesai_fuzz::decode_checked(plain, in.view()) == e);
  hesai_fuzz::check(hesai_fuzz::decode_checked(extreme, in.view()) == e);
  return 0;
}
