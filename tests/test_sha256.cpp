// SHA-256 known answers from FIPS 180-4's examples (also in RFC 6234 section 8.5) and NIST's
// CAVP byte-oriented test vectors, on every compression path this machine can run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "crypto_test_util.h"
#include "hesai/sha256.h"
#include "vector_paths.h"

namespace {

using hesai::Sha256;
using hesai::Sha256Path;
using hesai_test::Bytes;
using hesai_test::from_hex;
using hesai_test::from_text;
using hesai_test::to_hex;
using hesai_test::view;

struct Vector {
  const char* name;
  Bytes message;
  std::string digest;  // hex
};

std::vector<Vector> short_vectors() {
  return {
      {"empty", {}, "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"},
      {"abc", from_text("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"},
      {"448 bits", from_text("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
       "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1"},
      {"896 bits",
       from_text("abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmno"
                 "ijklmnopjklmnopqklmnopqrlmnopqrsmnopqrstnopqrstu"),
       "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1"},
      // NIST CAVP SHAVS byte-oriented vectors (SHA256ShortMsg.rsp) at the padding edges: 55 bytes
      // leave exactly room for 0x80 and the length; 63 and 64 bytes need a second block.
      {"CAVP Len=440",
       from_hex("3ebfb06db8c38d5ba037f1363e118550aad94606e26835a01af05078533cc25f"
                "2f39573c04b632f62f68c294ab31f2a3e2a1a0d8c2be51"),
       "6595a2ef537a69ba8583dfbf7f5bec0ab1f93ce4c8ee1916eff44a93af5749c4"},
      {"CAVP Len=504",
       from_hex("e2f76e97606a872e317439f1a03fcd92e632e5bd4e7cbc4e97f1afc19a16fde9"
                "2d77cbe546416b51640cddb92af996534dfd81edb17c4424cf1ac4d75aceeb"),
       "18041bd4665083001fba8c5411d2d748e8abbfdcdfd9218cb02b68a78e7d4c23"},
      {"CAVP Len=512",
       from_hex("5a86b737eaea8ee976a0a24da63e7ed7eefad18a101c1211e2b3650c5187c2a8"
                "a650547208251f6d4237e661c7bf4c77f335390394c37fa1a9f9be836ac28509"),
       "42e61e174fbb3897d6dd6cef3dd2802fe67b331953b06114a65c772859dfc1aa"},
  };
}

const char* const kMillionADigest = "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0";

std::string finish_hex(Sha256& h) {
  std::uint8_t out[hesai::kSha256Size];
  h.finish(out);
  return to_hex(out, sizeof out);
}

std::string hash_whole(Sha256Path path, const Bytes& m) {
  Sha256 h(path);
  h.update(view(m));
  return finish_hex(h);
}

std::string hash_split(Sha256Path path, const Bytes& m, std::size_t at) {
  Sha256 h(path);
  h.update(view(m, 0, at));
  h.update(view(m, at, m.size() - at));
  return finish_hex(h);
}

std::string hash_in_pieces(Sha256Path path, const Bytes& m, std::size_t piece) {
  Sha256 h(path);
  for (std::size_t off = 0; off < m.size(); off += piece)
    h.update(view(m, off, std::min(piece, m.size() - off)));
  return finish_hex(h);
}

std::string path_name(const ::testing::TestParamInfo<Sha256Path>& info) {
  return info.param == Sha256Path::portable ? "portable" : "hardware";
}

class Sha256Kat : public ::testing::TestWithParam<Sha256Path> {
 protected:
  void SetUp() override {
    if (GetParam() == Sha256Path::hardware && !hesai::sha256_hardware_available())
      GTEST_SKIP() << "no SHA instructions on this CPU";
  }
};

TEST_P(Sha256Kat, ContextRunsOnTheRequestedPath) { EXPECT_EQ(Sha256(GetParam()).path(), GetParam()); }

TEST_P(Sha256Kat, Whole) {
  for (const auto& v : short_vectors()) EXPECT_EQ(hash_whole(GetParam(), v.message), v.digest) << v.name;
}

TEST_P(Sha256Kat, ByteByByte) {
  for (const auto& v : short_vectors()) EXPECT_EQ(hash_in_pieces(GetParam(), v.message, 1), v.digest) << v.name;
}

TEST_P(Sha256Kat, SplitInTwoAtEveryOffset) {
  for (const auto& v : short_vectors())
    for (std::size_t at = 0; at <= v.message.size(); ++at)
      EXPECT_EQ(hash_split(GetParam(), v.message, at), v.digest) << v.name << " split at " << at;
}

TEST_P(Sha256Kat, OneMillionA) {
  const Bytes m(1000000, 'a');
  EXPECT_EQ(hash_whole(GetParam(), m), kMillionADigest);
  for (std::size_t piece : {1u, 3u, 63u, 64u, 65u, 1000u, 4096u, 99999u})
    EXPECT_EQ(hash_in_pieces(GetParam(), m, piece), kMillionADigest) << "pieces of " << piece;
  // Splitting a megabyte at every offset is 10^12 bytes of hashing: take every offset in the
  // first and last two blocks (all buffer fill levels, both ends) and a few in the middle.
  std::vector<std::size_t> splits;
  for (std::size_t at = 0; at <= 128; ++at) {
    splits.push_back(at);
    splits.push_back(m.size() - at);
  }
  for (std::size_t at : {500000u, 500001u, 500031u, 500063u}) splits.push_back(at);
  for (std::size_t at : splits) EXPECT_EQ(hash_split(GetParam(), m, at), kMillionADigest) << "split at " << at;
}

TEST_P(Sha256Kat, FinishStartsANewMessage) {
  Sha256 h(GetParam());
  h.update(view(from_text("garbage")));
  h.reset();
  h.update(view(from_text("abc")));
  EXPECT_EQ(finish_hex(h), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(finish_hex(h), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

INSTANTIATE_TEST_SUITE_P(Paths, Sha256Kat, ::testing::Values(Sha256Path::portable, Sha256Path::hardware),
                         path_name);

TEST(Sha256, OneShot) {
  for (const auto& v : short_vectors()) {
    std::uint8_t out[hesai::kSha256Size];
    hesai::sha256(view(v.message), out);
    EXPECT_EQ(to_hex(out, sizeof out), v.digest) << v.name;
  }
}

TEST(Sha256, ForcedHardwareFallsBackWhenUnavailable) {
  const Sha256Path expected =
      hesai::sha256_hardware_available() ? Sha256Path::hardware : Sha256Path::portable;
  EXPECT_EQ(Sha256(Sha256Path::hardware).path(), expected);
  EXPECT_EQ(hesai::sha256_best_path(), expected);
  EXPECT_EQ(Sha256().path(), expected);
  ::testing::Test::RecordProperty("sha256_hardware", hesai::sha256_hardware_available() ? "yes" : "no");
  std::printf("SHA-256 hardware path available: %s\n", hesai::sha256_hardware_available() ? "yes" : "no");
}

// ARMv8 with the SHA-2 instructions (-march=armv8-a+crypto, the aarch64 cross preset): the
// hardware compression function is compiled in and chosen by default.
#if defined(__aarch64__) && (defined(__ARM_FEATURE_SHA2) || defined(__ARM_FEATURE_CRYPTO)) && \
    !defined(__ARM_BIG_ENDIAN)
TEST(Sha256, Armv8ShaPathIsAvailableOnArmv8Crypto) {
  EXPECT_TRUE(hesai::sha256_hardware_available());
  EXPECT_EQ(hesai::sha256_best_path(), Sha256Path::hardware);
}
#endif

// The two compression functions on the same inputs: every length 0..1000, pseudo-random bytes.
TEST(Sha256, PathsAgreeOnEveryLengthUpTo1000) {
  if (const std::string why = hesai_test::sha256_portable_reason(Sha256Path::hardware); !why.empty()) GTEST_SKIP() << why;
  for (std::size_t len = 0; len <= 1000; ++len) {
    const Bytes m = hesai_test::pseudo_random_bytes(len, static_cast<std::uint32_t>(len) + 1);
    ASSERT_EQ(hash_whole(Sha256Path::hardware, m), hash_whole(Sha256Path::portable, m)) << "length " << len;
  }
}

// 16 blocks in one call through `path` equal 16 portable calls of one block.
void expect_many_blocks_equal_one_at_a_time(Sha256Path path) {
  const Bytes blocks = hesai_test::pseudo_random_bytes(16 * hesai::kSha256BlockSize, 7);
  std::uint32_t all[8] = {1, 2, 3, 4, 5, 6, 7, 8}, one[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  hesai::sha256_compress(path, all, blocks.data(), 16);
  for (std::size_t i = 0; i < 16; ++i)
    hesai::sha256_compress(Sha256Path::portable, one, blocks.data() + i * hesai::kSha256BlockSize, 1);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_EQ(all[i], one[i]) << "word " << i;
}

TEST(Sha256, CompressManyBlocksEqualsOneAtATime) { expect_many_blocks_equal_one_at_a_time(Sha256Path::portable); }

TEST(Sha256, CompressManyBlocksHardwareEqualsPortableOneAtATime) {
  if (const std::string why = hesai_test::sha256_portable_reason(Sha256Path::hardware); !why.empty()) GTEST_SKIP() << why;
  expect_many_blocks_equal_one_at_a_time(Sha256Path::hardware);
}

}  // namespace
