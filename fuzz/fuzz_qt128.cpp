// libFuzzer harness: one UDP payload through a QT128C2X decoder (firing-time correction on and off).
#include <cstddef>
#include <cstdint>

#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const hesai_fuzz::ExactCopy in(data, size);
  static hesai::Decoder decoder(hesai::Model::qt128c2x);
  static hesai::Decoder plain(hesai::Model::qt128c2x);
  plain.set_firetime_correction(false);
  const hesai::Error e = hesai_fuzz::decode_checked(decoder, in.view());
  hesai_fuzz::check(hesai_fuzz::decode_checked(plain, in.view()) == e);
  return 0;
}
