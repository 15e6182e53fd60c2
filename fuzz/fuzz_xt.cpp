// libFuzzer harness: one UDP payload through the three decoders of point cloud protocol 6.1
// (PandarXT16, XT32, XT32M2X), with the firing-time correction on and off; at most one of them
// accepts a payload (identify() names one model by laser and block numbers).
#include <cstddef>
#include <cstdint>

#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const hesai_fuzz::ExactCopy in(data, size);
  static hesai::Decoder decoders[] = {hesai::Decoder(hesai::Model::pandar_xt16), hesai::Decoder(hesai::Model::pandar_xt32),
                                      hesai::Decoder(hesai::Model::pandar_xt32m2x)};
  static hesai::Decoder plain[] = {hesai::Decoder(hesai::Model::pandar_xt16), hesai::Decoder(hesai::Model::pandar_xt32),
                                   hesai::Decoder(hesai::Model::pandar_xt32m2x)};
  int accepted = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    plain[i].set_firetime_correction(false);
    const hesai::Error e = hesai_fuzz::decode_checked(decoders[i], in.view());
    hesai_fuzz::check(hesai_fuzz::decode_checked(plain[i], in.view()) == e);
    accepted += e == hesai::Error::ok;
  }
  hesai_fuzz::check(accepted <= 1);
  return 0;
}
