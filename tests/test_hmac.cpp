// HMAC-SHA256 known answers from RFC 4231 section 4, and the constant-time helpers.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "crypto_test_util.h"
#include "hesai/ct.h"
#include "hesai/hmac.h"

namespace {

using hesai::HmacSha256;
using hesai::HmacSha256Key;
using hesai::Sha256Path;
using hesai_test::Bytes;
using hesai_test::from_hex;
using hesai_test::from_text;
using hesai_test::to_hex;
using hesai_test::view;

struct Case {
  int number;
  Bytes key;
  Bytes data;
  std::string mac;  // hex; case 5 gives only the first 128 bits
};

std::vector<Case> rfc4231_cases() {
  const Bytes key131(131, 0xaa);
  return {
      {1, Bytes(20, 0x0b), from_text("Hi There"),
       "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7"},
      {2, from_text("Jefe"), from_text("what do ya want for nothing?"),
       "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843"},
      {3, Bytes(20, 0xaa), Bytes(50, 0xdd), "773ea91e36800e46854db8ebd09181a72959098b3ef8c122d9635514ced565fe"},
      {4, from_hex("0102030405060708090a0b0c0d0e0f10111213141516171819"), Bytes(50, 0xcd),
       "82558a389a443c0ea4cc819899f2083a85f0faa3e578f8077a2e3ff46729665b"},
      {5, Bytes(20, 0x0c), from_text("Test With Truncation"), "a3b6167473100ee06e0c796c2955552b"},
      {6, key131, from_text("Test Using Larger Than Block-Size Key - Hash Key First"),
       "60e431591ee0b67f0d8a26aacbf5b77f8e0bc6213728c5140546040f0ee37f54"},
      {7, key131,
       from_text("This is a test using a larger than block-size key and a larger than block-size data. "
                 "The key needs to be hashed before being used by the HMAC algorithm."),
       "9b09ffa71b942fcb27635fbcd5b0e944bfdc63644f0713938a7f51535c3a35e2"},
  };
}

// The MAC as hex, cut to the length the RFC gives.
std::string mac_hex(const std::uint8_t (&mac)[hesai::kSha256Size], const Case& c) {
  return to_hex(mac, c.mac.size() / 2);
}

std::string path_name(const ::testing::TestParamInfo<Sha256Path>& info) {
  return info.param == Sha256Path::portable ? "portable" : "hardware";
}

class HmacKat : public ::testing::TestWithParam<Sha256Path> {
 protected:
  void SetUp() override {
    if (GetParam() == Sha256Path::hardware && !hesai::sha256_hardware_available())
      GTEST_SKIP() << "no SHA instructions on this CPU";
  }
};

TEST(HmacSha256, Rfc4231OneShot) {
  for (const Case& c : rfc4231_cases()) {
    std::uint8_t mac[hesai::kSha256Size];
    hesai::hmac_sha256(view(c.key), view(c.data), mac);
    EXPECT_EQ(mac_hex(mac, c), c.mac) << "case " << c.number;
  }
}

TEST_P(HmacKat, Rfc4231Whole) {
  for (const Case& c : rfc4231_cases()) {
    const HmacSha256Key key(view(c.key), GetParam());
    HmacSha256 h(key);
    h.update(view(c.data));
    std::uint8_t mac[hesai::kSha256Size];
    h.finish(mac);
    EXPECT_EQ(mac_hex(mac, c), c.mac) << "case " << c.number;
  }
}

TEST_P(HmacKat, Rfc4231ByteByByte) {
  for (const Case& c : rfc4231_cases()) {
    const HmacSha256Key key(view(c.key), GetParam());
    HmacSha256 h(key);
    for (std::size_t i = 0; i < c.data.size(); ++i) h.update(view(c.data, i, 1));
    std::uint8_t mac[hesai::kSha256Size];
    h.finish(mac);
    EXPECT_EQ(mac_hex(mac, c), c.mac) << "case " << c.number;
  }
}

TEST_P(HmacKat, Rfc4231SplitAtEveryOffset) {
  for (const Case& c : rfc4231_cases()) {
    const HmacSha256Key key(view(c.key), GetParam());
    for (std::size_t at = 0; at <= c.data.size(); ++at) {
      HmacSha256 h(key);
      h.update(view(c.data, 0, at));
      h.update(view(c.data, at, c.data.size() - at));
      std::uint8_t mac[hesai::kSha256Size];
      h.finish(mac);
      EXPECT_EQ(mac_hex(mac, c), c.mac) << "case " << c.number << " split at " << at;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Paths, HmacKat, ::testing::Values(Sha256Path::portable, Sha256Path::hardware),
                         path_name);

// One prepared key, many messages: fresh HmacSha256 objects, and one object reused after finish().
TEST(HmacSha256, OneKeyManyMessages) {
  const auto cases = rfc4231_cases();
  const Case& c6 = cases[5];
  const Case& c7 = cases[6];
  ASSERT_EQ(c6.key, c7.key);
  const HmacSha256Key key(view(c6.key));
  std::uint8_t mac[hesai::kSha256Size];

  HmacSha256 reused(key);
  for (int round = 0; round < 3; ++round) {
    for (const Case* c : {&c6, &c7}) {
      reused.update(view(c->data));
      reused.finish(mac);
      EXPECT_EQ(mac_hex(mac, *c), c->mac) << "reused object, case " << c->number << ", round " << round;

      HmacSha256 fresh(key);
      fresh.update(view(c->data));
      fresh.finish(mac);
      EXPECT_EQ(mac_hex(mac, *c), c->mac) << "fresh object, case " << c->number << ", round " << round;
    }
  }
}

TEST(HmacSha256, KeySetAgainAndWiped) {
  const auto cases = rfc4231_cases();
  HmacSha256Key key;
  std::uint8_t mac[hesai::kSha256Size];
  for (const Case& c : cases) {  // one key object through all seven keys
    key.set(view(c.key));
    HmacSha256 h(key);
    h.update(view(c.data));
    h.finish(mac);
    EXPECT_EQ(mac_hex(mac, c), c.mac) << "case " << c.number;
  }
  key.wipe();
  key.set(view(cases[1].key));
  HmacSha256 h(key);
  h.update(view(cases[1].data));
  h.finish(mac);
  EXPECT_EQ(mac_hex(mac, cases[1]), cases[1].mac);
}

TEST(HmacSha256, DefaultKeyIsTheEmptyKey) {
  const Bytes msg = from_text("message");
  std::uint8_t expected[hesai::kSha256Size], got[hesai::kSha256Size];
  hesai::hmac_sha256(hesai::ByteView{}, view(msg), expected);
  const HmacSha256Key key;
  HmacSha256 h(key);
  h.update(view(msg));
  h.finish(got);
  EXPECT_EQ(to_hex(got, sizeof got), to_hex(expected, sizeof expected));
  // HMAC zero-pads the key, so an empty key equals a key of 64 zero bytes.
  const Bytes zeros(64, 0);
  hesai::hmac_sha256(view(zeros), view(msg), got);
  EXPECT_EQ(to_hex(got, sizeof got), to_hex(expected, sizeof expected));
}

// Keys at the block-size edge, against RFC 2104's definition written out with SHA-256 (itself
// checked against FIPS 180-4): a 64-byte key is used as is, a 65-byte key is hashed first.
std::string hmac_by_definition(Bytes key, const Bytes& msg) {
  std::uint8_t digest[hesai::kSha256Size];
  if (key.size() > 64) {
    hesai::sha256(view(key), digest);
    key.assign(digest, digest + sizeof digest);
  }
  key.resize(64, 0);
  Bytes inner, outer;
  for (std::uint8_t k : key) inner.push_back(static_cast<std::uint8_t>(k ^ 0x36));
  for (std::uint8_t k : key) outer.push_back(static_cast<std::uint8_t>(k ^ 0x5c));
  inner.insert(inner.end(), msg.begin(), msg.end());
  hesai::sha256(view(inner), digest);
  outer.insert(outer.end(), digest, digest + sizeof digest);
  hesai::sha256(view(outer), digest);
  return to_hex(digest, sizeof digest);
}

TEST(HmacSha256, KeysAroundTheBlockSize) {
  const Bytes msg = from_text("what do ya want for nothing?");
  for (std::size_t len : {0u, 1u, 32u, 63u, 64u, 65u, 100u}) {
    const Bytes key = hesai_test::pseudo_random_bytes(len, static_cast<std::uint32_t>(len) + 3);
    std::uint8_t mac[hesai::kSha256Size];
    hesai::hmac_sha256(view(key), view(msg), mac);
    EXPECT_EQ(to_hex(mac, sizeof mac), hmac_by_definition(key, msg)) << len << "-byte key";
  }
}

TEST(ConstantTime, EqualAndUnequal) {
  const Bytes a = hesai_test::pseudo_random_bytes(32, 99);
  Bytes b = a;
  EXPECT_TRUE(hesai::constant_time_equal(a.data(), b.data(), a.size()));
  EXPECT_TRUE(hesai::constant_time_equal(a.data(), b.data(), 0));
  for (std::size_t i = 0; i < b.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      b[i] = static_cast<std::uint8_t>(b[i] ^ (1u << bit));
      EXPECT_FALSE(hesai::constant_time_equal(a.data(), b.data(), b.size())) << "byte " << i << " bit " << bit;
      EXPECT_TRUE(hesai::constant_time_equal(a.data(), b.data(), i)) << "prefix before byte " << i;
      b[i] = a[i];
    }
  }
  const Bytes zeros(32, 0x00), ones(32, 0xff);
  EXPECT_FALSE(hesai::constant_time_equal(zeros.data(), ones.data(), 32));
}

TEST(ConstantTime, SecureWipeZeroesExactlyTheRange) {
  const Bytes original = hesai_test::pseudo_random_bytes(100, 5);
  Bytes buf = original;
  hesai::secure_wipe(buf.data() + 10, 80);
  EXPECT_EQ(Bytes(buf.begin(), buf.begin() + 10), Bytes(original.begin(), original.begin() + 10));
  EXPECT_EQ(Bytes(buf.begin() + 10, buf.begin() + 90), Bytes(80, 0));
  EXPECT_EQ(Bytes(buf.begin() + 90, buf.end()), Bytes(original.begin() + 90, original.end()));
  hesai::secure_wipe(nullptr, 0);  // no bytes, no access
}

}  // namespace
