// The core in its smallest configuration (tests/config/minimal_config.h): what HESAI_SIGNATURE 0
// and an armed HESAI_ASSERT do. The CRC (HESAI_CRC_SLICING 1) and crypto tests run beside these.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../packet_builder.h"
#include "../test_support.h"
#include "hesai/crc32.h"
#include "hesai/decoder.h"

static_assert(HESAI_SIGNATURE == 0 && hesai::kCrc32Mpeg2Slices == 1, "minimal_config.h reached the core");

namespace {
int g_broken = 0;
std::string g_condition;
}  // namespace

void hesai_test_contract_broken(const char* condition) noexcept {
  ++g_broken;
  g_condition = condition;
}

namespace {

using namespace hesai;
using hesai_test::qt128_packet;
using hesai_test::qt128_seal;

ByteView view(const std::vector<std::uint8_t>& v) { return {v.data(), v.size()}; }

// A QT128 packet (flags 0x0D: sequence, functional safety, signature) with its CRCs, signed or not.
// Mode flag 0: block 1 fires sequence 2, in which channel 1 (bank A) fires (manual App. II).
std::vector<std::uint8_t> qt128(const std::uint8_t* key) {
  auto p = qt128_packet(0x0D, 0x37, 0, hesai_test::Stamp{});
  hesai_test::qt128_point(p, 1, 1, 1000, 50);
  qt128_seal(p, key);
  return p;
}

TEST(MinimalConfig, SessionKeyIsUnsupported) {
  Decoder dec(Model::qt128c2x);
  const std::uint8_t key[32] = {7};
  EXPECT_EQ(dec.set_session_key(key), Error::unsupported_feature);
  EXPECT_STREQ(error_name(Error::unsupported_feature), "unsupported_feature");
  // Still no key: an unsigned packet is accepted as unsigned, not refused as signature_missing.
  PacketInfo info;
  static PacketPoints pts;
  ASSERT_EQ(dec.decode(view(qt128(nullptr)), info, pts), Error::ok);
  EXPECT_EQ(info.signature, SignatureStatus::not_signed);
}

TEST(MinimalConfig, SignedPacketDecodesUnverified) {
  const std::uint8_t key[32] = {7};
  const auto signed_packet = qt128(key);
  ASSERT_NE(signed_packet.back(), 0u);  // HMAC bytes, not the all-zero "not signed" value (odds 2^-8)
  Decoder dec(Model::qt128c2x);
  PacketInfo info;
  static PacketPoints pts;
  ASSERT_EQ(dec.decode(view(signed_packet), info, pts), Error::ok);
  EXPECT_EQ(info.signature, SignatureStatus::unverified);
  ASSERT_EQ(pts.count, 1u);  // the one point set above, channel 1 of block 1
  EXPECT_EQ(pts.points[0].channel, 1);
  EXPECT_FLOAT_EQ(pts.points[0].distance_m, 4.0f);  // 1000 x 4 mm
  // A corrupted signature is not detected without signature support: still unverified.
  auto tampered = signed_packet;
  tampered.back() ^= 0xFF;
  ASSERT_EQ(dec.decode(view(tampered), info, pts), Error::ok);
  EXPECT_EQ(info.signature, SignatureStatus::unverified);
}

TEST(MinimalConfig, ContractChecksReachTheAssertHook) {
  g_broken = 0;
  const std::uint8_t bytes[4] = {};
  const ByteView v{bytes, 4};
  (void)v.sub(1, 3);  // within the view: no report
  EXPECT_EQ(g_broken, 0);
  (void)v.sub(2, 3);  // one byte past the end: a broken contract, reported
  EXPECT_EQ(g_broken, 1);
  EXPECT_EQ(g_condition, "offset <= size && count <= size - offset");
}

TEST(MinimalConfig, RealCaptureBreaksNoContract) {
  const auto packets = hesai_test::pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_EQ(packets.size(), 1800u);
  g_broken = 0;
  Decoder dec(Model::qt128c2x);
  PacketInfo info;
  static PacketPoints pts;
  std::size_t decoded = 0;
  for (const auto& p : packets) decoded += dec.decode(view(p), info, pts) == Error::ok;
  EXPECT_EQ(decoded, packets.size());
  EXPECT_EQ(g_broken, 0) << g_condition;
}

}  // namespace
