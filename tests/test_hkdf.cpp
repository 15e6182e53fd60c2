// HKDF-SHA256 known answers from RFC 5869 appendix A (cases 1-3), its length limit, and the
// Hesai session-key derivation.
#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <string>
#include <vector>

#include "crypto_test_util.h"
#include "hesai/hkdf.h"
#include "hesai/hmac.h"

namespace {

using hesai::Error;
using hesai_test::Bytes;
using hesai_test::from_hex;
using hesai_test::from_text;
using hesai_test::to_hex;
using hesai_test::view;

Bytes counting(std::uint8_t first, std::size_t n) {
  Bytes b(n);
  for (std::size_t i = 0; i < n; ++i) b[i] = static_cast<std::uint8_t>(first + i);
  return b;
}

struct Case {
  int number;
  Bytes ikm, salt, info;
  std::string prk, okm;  // hex
};

std::vector<Case> rfc5869_cases() {
  return {
      {1, Bytes(22, 0x0b), counting(0x00, 13), counting(0xf0, 10),
       "077709362c2e32df0ddc3f0dc47bba6390b6c73bb50f9c3122ec844ad7c2b3e5",
       "3cb25f25faacd57a90434f64d0362f2a2d2d0a90cf1a5a4c5db02d56ecc4c5bf34007208d5b887185865"},
      {2, counting(0x00, 80), counting(0x60, 80), counting(0xb0, 80),
       "06a6b88c5853361a06104c9ceb35b45cef760014904671014a193f40c15fc244",
       "b11e398dc80327a1c8e7f78c596a49344f012eda2d4efad8a050cc4c19afa97c"
       "59045a99cac7827271cb41c65e590e09da3275600c2f09b8367793a9aca3db71"
       "cc30c58179ec3e87c14c01d5c1f3434f1d87"},
      {3, Bytes(22, 0x0b), {}, {}, "19ef24a32c717b167f33a91d6f648bdf96596776afdb6377ac434c1c293ccb04",
       "8da4e775a563c18f715f802a063c5a31b8a11f5c5ee1879ec3454e5f3c738d2d9d201395faa4b61a96c8"},
  };
}

TEST(Hkdf, Rfc5869ExtractThenExpand) {
  for (const Case& c : rfc5869_cases()) {
    std::uint8_t prk[hesai::kSha256Size];
    hesai::hkdf_sha256_extract(view(c.salt), view(c.ikm), prk);
    EXPECT_EQ(to_hex(prk, sizeof prk), c.prk) << "case " << c.number;

    Bytes okm(c.okm.size() / 2);
    ASSERT_EQ(hesai::hkdf_sha256_expand({prk, sizeof prk}, view(c.info), okm.data(), okm.size()), Error::ok);
    EXPECT_EQ(to_hex(okm), c.okm) << "case " << c.number;
  }
}

TEST(Hkdf, Rfc5869OneCall) {
  for (const Case& c : rfc5869_cases()) {
    Bytes okm(c.okm.size() / 2);
    ASSERT_EQ(hesai::hkdf_sha256(view(c.salt), view(c.ikm), view(c.info), okm.data(), okm.size()), Error::ok);
    EXPECT_EQ(to_hex(okm), c.okm) << "case " << c.number;
  }
}

TEST(Hkdf, LengthLimits) {
  const Case c = rfc5869_cases()[1];
  const Bytes prk = from_hex(c.prk);

  // Every length up to the case's own is a prefix of its OKM (T(i) does not depend on L).
  for (std::size_t len = 0; len <= c.okm.size() / 2; ++len) {
    Bytes okm(len);
    ASSERT_EQ(hesai::hkdf_sha256_expand(view(prk), view(c.info), okm.data(), len), Error::ok);
    EXPECT_EQ(to_hex(okm), c.okm.substr(0, 2 * len)) << "length " << len;
  }

  // The longest output, 255 * 32 bytes, is accepted and starts with the same bytes.
  Bytes longest(hesai::kHkdfSha256MaxLength + 1, 0x5a);
  EXPECT_EQ(hesai::kHkdfSha256MaxLength, 8160u);
  ASSERT_EQ(hesai::hkdf_sha256_expand(view(prk), view(c.info), longest.data(), 8160), Error::ok);
  EXPECT_EQ(to_hex(longest.data(), 82), c.okm);
  EXPECT_EQ(longest[8160], 0x5a) << "wrote past the requested length";

  // One byte more is refused, and nothing is written.
  Bytes too_long(8161, 0x5a);
  EXPECT_EQ(hesai::hkdf_sha256_expand(view(prk), view(c.info), too_long.data(), 8161), Error::invalid_argument);
  EXPECT_EQ(hesai::hkdf_sha256(view(c.salt), view(c.ikm), view(c.info), too_long.data(), 8161),
            Error::invalid_argument);
  EXPECT_EQ(too_long, Bytes(8161, 0x5a));

  // Zero bytes: fine, even with no buffer.
  EXPECT_EQ(hesai::hkdf_sha256_expand(view(prk), view(c.info), nullptr, 0), Error::ok);
}

// Session-key inputs shared by the tests below.
const Bytes kSecret = from_text("0123456789abcdef");  // 16 bytes
const Bytes kLidarRandom = counting(0x00, 32);
const Bytes kClientRandom = counting(0x20, 32);

TEST(HesaiSessionKey, RejectsSecretsOutside8To32Bytes) {
  for (std::size_t len : {0u, 7u, 33u, 64u}) {
    const Bytes secret(len, 0x11);
    std::uint8_t key[32];
    std::fill(std::begin(key), std::end(key), 0xee);
    EXPECT_EQ(hesai::hesai_session_key(view(secret), kLidarRandom.data(), kClientRandom.data(), key),
              Error::invalid_argument)
        << len << "-byte secret";
    EXPECT_EQ(to_hex(key, sizeof key), std::string(64, 'e')) << "key written for a refused secret";
  }
  for (std::size_t len : {8u, 32u}) {
    const Bytes secret(len, 0x11);
    std::uint8_t key[32];
    EXPECT_EQ(hesai::hesai_session_key(view(secret), kLidarRandom.data(), kClientRandom.data(), key), Error::ok)
        << len << "-byte secret";
  }
}

// The documented construction, spelled out step by step with HMAC-SHA256 (itself checked
// against RFC 4231): PRK = HMAC(lidar_random || client_random, secret), key = T(1) =
// HMAC(PRK, "finish session key" || 0x01).
TEST(HesaiSessionKey, EqualsHkdfWrittenOutWithHmac) {
  Bytes salt = kLidarRandom;
  salt.insert(salt.end(), kClientRandom.begin(), kClientRandom.end());
  const Bytes info = from_text("finish session key");
  ASSERT_EQ(info.size(), 18u);

  std::uint8_t prk[32], expected[32];
  hesai::hmac_sha256(view(salt), view(kSecret), prk);
  Bytes t1_input = info;
  t1_input.push_back(0x01);
  hesai::hmac_sha256({prk, sizeof prk}, view(t1_input), expected);

  std::uint8_t key[32];
  ASSERT_EQ(hesai::hesai_session_key(view(kSecret), kLidarRandom.data(), kClientRandom.data(), key), Error::ok);
  EXPECT_EQ(to_hex(key, sizeof key), to_hex(expected, sizeof expected));

  std::uint8_t via_hkdf[32];
  ASSERT_EQ(hesai::hkdf_sha256(view(salt), view(kSecret), view(info), via_hkdf, sizeof via_hkdf), Error::ok);
  EXPECT_EQ(to_hex(key, sizeof key), to_hex(via_hkdf, sizeof via_hkdf));
}

// A fixed vector computed outside this code base, by two independent implementations that
// agree: Python 3's hmac/hashlib modules (the two HMAC steps above) and
// `openssl kdf -keylen 32 -kdfopt digest:SHA256 -kdfopt key:0123456789abcdef
//  -kdfopt hexsalt:000102...3f -kdfopt "info:finish session key" HKDF` (OpenSSL 3.0).
TEST(HesaiSessionKey, FixedVector) {
  std::uint8_t key[32];
  ASSERT_EQ(hesai::hesai_session_key(view(kSecret), kLidarRandom.data(), kClientRandom.data(), key), Error::ok);
  EXPECT_EQ(to_hex(key, sizeof key), "5cad3d54b4bbdc6a53db72377c692596048d55a395eea33996ec1b2cb63c9dc7");
  // Swapping the two randoms changes the salt and so the key.
  std::uint8_t swapped[32];
  ASSERT_EQ(hesai::hesai_session_key(view(kSecret), kClientRandom.data(), kLidarRandom.data(), swapped), Error::ok);
  EXPECT_NE(to_hex(swapped, sizeof swapped), to_hex(key, sizeof key));
}

}  // namespace
