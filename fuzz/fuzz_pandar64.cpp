// libFuzzer harness: one UDP payload through a Pandar64 decoder (firing-time correction on and
// off, and the nonlinear reflectivity mapping, which changes nothing but the intensities).
#include <cstddef>
#include <cstdint>

#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const hesai_fuzz::ExactCopy in(data, size);
  static hesai::Decoder decoder(hesai::Model::pandar64);
  static hesai::Decoder plain(hesai::Model::pandar64);
  static hesai::Decoder nonlinear(hesai::Model::pandar64);
  plain.set_firetime_correction(false);
  hesai_fuzz::check(nonlinear.set_reflectivity(hesai::Reflectivity::nonlinear) == hesai::Error::ok);
  const hesai::Error e = hesai_fuzz::decode_checked(decoder, in.view());
  hesai_fuzz::check(hesai_fuzz::decode_checked(plain, in.view()) == e);
  hesai_fuzz::check(hesai_fuzz::decode_checked(nonlinear, in.view()) == e);
  return 0;
}
