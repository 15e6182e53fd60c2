// libFuzzer harness: QT128C2X packets under a fixed session key (bytes 0x00..0x1F), unsigned
// packets refused and, in a second decoder, accepted.
#include <cstddef>
#include <cstdint>

#include "fuzz_common.h"
#include "hesai/detail/qt128_packet.h"

namespace {

struct Keyed {
  hesai::Decoder strict{hesai::Model::qt128c2x};
  hesai::Decoder lenient{hesai::Model::qt128c2x};
  Keyed() {
    std::uint8_t key[32];
    for (std::size_t i = 0; i < sizeof key; ++i) key[i] = static_cast<std::uint8_t>(i);
    hesai_fuzz::check(strict.set_session_key(key) == hesai::Error::ok);
    hesai_fuzz::check(lenient.set_session_key(key) == hesai::Error::ok);
    lenient.set_allow_unsigned(true);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using hesai_fuzz::check;
  const hesai_fuzz::ExactCopy in(data, size);
  static Keyed k;
  hesai::PacketInfo info;
  const hesai::Error e = hesai_fuzz::decode_checked(k.strict, in.view());
  if (e == hesai::Error::ok) {
    check(k.strict.validate(in.view(), info) == hesai::Error::ok);
    check(info.signature == hesai::SignatureStatus::valid && (info.flags & hesai::qt128::kFlagSignature) != 0);
  }
  const hesai::Error l = hesai_fuzz::decode_checked(k.lenient, in.view());
  if (l == hesai::Error::ok) {
    check(k.lenient.validate(in.view(), info) == hesai::Error::ok);
    check(info.signature == hesai::SignatureStatus::valid || info.signature == hesai::SignatureStatus::accepted_unsigned);
  }
  // The two differ only on unsigned packets (the lenient decoder goes on to check the fields).
  check(e == l || e == hesai::Error::signature_missing);
  check(l != hesai::Error::signature_missing);
  return 0;
}
