// The platform hooks (hesai/config.h HESAI_CRC32_ALT, HESAI_SHA256_ALT) on the host: this program
// provides hesai_crc32_mpeg2_alt and hesai_sha256_compress_alt as a platform would, each counting
// its calls and computing with the core's own software path (CrcPath::table, Sha256Path::portable),
// and checks that every CRC and SHA-256 the core computes by default goes through them, with the
// results of the definitions: the check values, RFC 4231, and the real QT128 capture validated and
// signature-checked packet by packet.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "hesai/crc32.h"
#include "hesai/decoder.h"
#include "hesai/hkdf.h"
#include "hesai/hmac.h"
#include "hesai/detail/qt128_packet.h"
#include "hesai/sha256.h"
#include "../test_support.h"

namespace {
std::size_t g_crc_calls = 0, g_crc_bytes = 0, g_sha_calls = 0, g_sha_blocks = 0;
}  // namespace

extern "C" std::uint32_t hesai_crc32_mpeg2_alt(std::uint32_t crc, const std::uint8_t* data, std::size_t size) noexcept {
  ++g_crc_calls;
  g_crc_bytes += size;
  return hesai::crc32_mpeg2_update(hesai::CrcPath::table, crc, hesai::ByteView{data, size});
}

extern "C" void hesai_sha256_compress_alt(std::uint32_t state[8], const std::uint8_t* blocks, std::size_t nblocks) noexcept {
  ++g_sha_calls;
  g_sha_blocks += nblocks;
  hesai::sha256_compress(hesai::Sha256Path::portable, state, blocks, nblocks);
}

namespace {

using hesai::ByteView;
using hesai::Error;

ByteView text(const char* s) { return {reinterpret_cast<const std::uint8_t*>(s), std::strlen(s)}; }

TEST(AltHooks, PathsNameThePlatform) {
  EXPECT_STREQ(hesai::crc32_path_name(), "alt");
  EXPECT_TRUE(hesai::crc32_hardware_available());
  EXPECT_STREQ(hesai::sha256_path_name(), "alt");
  EXPECT_EQ(hesai::sha256_best_path(), hesai::Sha256Path::hardware);
}

TEST(AltHooks, CrcCheckValueThroughTheHook) {
  g_crc_calls = 0;
  EXPECT_EQ(hesai::crc32_mpeg2(text("123456789")), 0x0376E6E7u);  // the catalogue's check value
  EXPECT_EQ(g_crc_calls, 1u);
  // Split input, each piece one call, the same register.
  std::uint32_t crc = hesai::kCrc32Mpeg2Init;
  crc = hesai::crc32_mpeg2_update(crc, text("1234"));
  crc = hesai::crc32_mpeg2_update(crc, text("56789"));
  EXPECT_EQ(crc, 0x0376E6E7u);
  EXPECT_EQ(g_crc_calls, 3u);
  // The core's own paths stay its own.
  EXPECT_EQ(hesai::crc32_mpeg2_update(hesai::CrcPath::slicing, hesai::kCrc32Mpeg2Init, text("123456789")), 0x0376E6E7u);
  EXPECT_EQ(g_crc_calls, 3u);
}

TEST(AltHooks, Sha256AndHmacThroughTheHook) {
  g_sha_blocks = 0;
  // FIPS 180-2 B.1: SHA-256("abc"), one block.
  std::uint8_t digest[32];
  hesai::Sha256 h;
  h.update(text("abc"));
  h.finish(digest);
  const std::uint8_t abc[32] = {0xba, 0x78, 0x16, 0xbf, 0x8f, 0x01, 0xcf, 0xea, 0x41, 0x41, 0x40, 0xde, 0x5d, 0xae, 0x22, 0x23,
                                0xb0, 0x03, 0x61, 0xa3, 0x96, 0x17, 0x7a, 0x9c, 0xb4, 0x10, 0xff, 0x61, 0xf2, 0x00, 0x15, 0xad};
  EXPECT_EQ(std::memcmp(digest, abc, 32), 0);
  EXPECT_EQ(g_sha_blocks, 1u);
  // RFC 4231 test case 2: key "Jefe", "what do ya want for nothing?".
  hesai::hmac_sha256(text("Jefe"), text("what do ya want for nothing?"), digest);
  const std::uint8_t tc2[32] = {0x5b, 0xdc, 0xc1, 0x46, 0xbf, 0x60, 0x75, 0x4e, 0x6a, 0x04, 0x24, 0x26, 0x08, 0x95, 0x75, 0xc7,
                                0x5a, 0x00, 0x3f, 0x08, 0x9d, 0x27, 0x39, 0x83, 0x9d, 0xec, 0x58, 0xb9, 0x64, 0xec, 0x38, 0x43};
  EXPECT_EQ(std::memcmp(digest, tc2, 32), 0);
  // Inner: key block + 28 bytes (1 + 1 blocks); outer: key block + 32 bytes (1 + 1).
  EXPECT_EQ(g_sha_blocks, 1u + 4u);
}

// Every QT128 packet of the capture, signed under a session key and validated: three CRCs per
// packet through the CRC hook, and the signature's compressions through the SHA hook: the inner
// hash covers the precomputed key block and the 1 095 signed bytes (64 + 1 095 + 9 bytes of padding
// and length round up to 19 blocks, 18 after the key block), the outer one the key block and the
// 32-byte inner digest (2 blocks, 1 after it): 19 a packet.
TEST(AltHooks, Qt128CaptureValidatesThroughBothHooks) {
  const auto packets = hesai_test::pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_EQ(packets.size(), 1800u);
  std::uint8_t key[32];
  const std::uint8_t lidar[32] = {7}, client[32] = {9};
  ASSERT_EQ(hesai::hesai_session_key(text("12345678"), lidar, client, key), Error::ok);
  std::vector<std::vector<std::uint8_t>> signed_packets = packets;
  for (auto& p : signed_packets) ASSERT_EQ(hesai::qt128::sign(p.data(), p.size(), key), Error::ok);
  ASSERT_EQ(signed_packets[0].size(), 1127u);  // flags 0x1D: the signature covers bytes 0..1094

  hesai::Decoder d(hesai::Model::qt128c2x);
  ASSERT_EQ(d.set_session_key(key), Error::ok);
  g_crc_calls = g_sha_blocks = 0;
  std::size_t valid = 0;
  for (const auto& p : signed_packets) {
    hesai::PacketInfo info;
    ASSERT_EQ(d.validate(ByteView{p.data(), p.size()}, info), Error::ok);
    valid += info.signature == hesai::SignatureStatus::valid;
  }
  EXPECT_EQ(valid, 1800u);
  EXPECT_EQ(g_crc_calls, 3u * 1800u);
  EXPECT_EQ(g_sha_blocks, 19u * 1800u);
  // A flipped body byte: CRC1 through the hook catches it.
  auto bad = signed_packets[5];
  bad[100] ^= 1;
  hesai::PacketInfo info;
  EXPECT_EQ(d.validate(ByteView{bad.data(), bad.size()}, info), Error::crc_body);
}

}  // namespace
