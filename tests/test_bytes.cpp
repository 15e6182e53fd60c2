// The bounded byte reader, the explicit-byte-order loads, error names, civil time and sin/cos.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "hesai/bytes.h"
#include "hesai/civil_time.h"
#include "hesai/error.h"
#include "hesai/detail/math.h"

using namespace hesai;

TEST(Bytes, LoadsNameTheirByteOrder) {
  const std::uint8_t b[8] = {0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08};
  EXPECT_EQ(load_le16(b), 0x0201);
  EXPECT_EQ(load_be16(b), 0x0102);
  EXPECT_EQ(load_le32(b), 0x04030201u);
  EXPECT_EQ(load_be32(b), 0x01020304u);
  EXPECT_EQ(load_le64(b), 0x0807060504030201ull);
  EXPECT_EQ(load_be64(b), 0x0102030405060708ull);
  std::uint8_t out[8] = {};
  store_le32(out, 0xA1B2C3D4u);
  EXPECT_EQ(out[0], 0xD4);
  EXPECT_EQ(out[3], 0xA1);
  store_be32(out, 0xA1B2C3D4u);
  EXPECT_EQ(out[0], 0xA1);
  store_le16(out, 0xBEEF);
  EXPECT_EQ(out[0], 0xEF);
  EXPECT_EQ(out[1], 0xBE);
}

TEST(ByteReader, ReadsInOrderAndStopsAtTheEnd) {
  const std::uint8_t b[7] = {0xEE, 0xFF, 0x40, 0x06, 0x10, 0x20, 0x30};
  ByteReader r(ByteView{b, sizeof b});
  std::uint16_t magic = 0;
  std::uint8_t lasers = 0;
  ASSERT_TRUE(r.le16(magic));
  EXPECT_EQ(magic, 0xFFEE);
  ASSERT_TRUE(r.u8(lasers));
  EXPECT_EQ(lasers, 0x40);
  EXPECT_EQ(r.position(), 3u);
  EXPECT_EQ(r.remaining(), 4u);
  // A 4-byte read fits exactly; the next read of any size fails and leaves the cursor.
  std::uint32_t v = 0xDEADBEEF;
  ASSERT_TRUE(r.be32(v));
  EXPECT_EQ(v, 0x06102030u);
  EXPECT_EQ(r.error(), Error::ok);
  std::uint8_t one = 0x55;
  EXPECT_FALSE(r.u8(one));
  EXPECT_EQ(one, 0x55);  // untouched
  EXPECT_EQ(r.position(), 7u);
  EXPECT_EQ(r.error(), Error::truncated);
}

TEST(ByteReader, FailedReadLeavesTheCursorAndLaterReadsThatFitWork) {
  const std::uint8_t b[5] = {1, 2, 3, 4, 5};
  ByteReader r(ByteView{b, sizeof b});
  ASSERT_TRUE(r.skip(2));
  std::uint32_t v = 0;
  EXPECT_FALSE(r.le32(v));  // 4 > 3 remaining
  EXPECT_EQ(r.position(), 2u);
  std::uint16_t w = 0;
  EXPECT_TRUE(r.le16(w));  // still reads what fits
  EXPECT_EQ(w, 0x0403);
  ByteView tail;
  EXPECT_FALSE(r.bytes(2, tail));
  EXPECT_TRUE(r.bytes(1, tail));
  EXPECT_EQ(tail.size, 1u);
  EXPECT_EQ(tail[0], 5);
  EXPECT_FALSE(r.seek(6));
  EXPECT_TRUE(r.seek(5));
  EXPECT_FALSE(r.skip(1));
  // Huge sizes do not wrap around the bound check.
  EXPECT_FALSE(r.skip(static_cast<std::size_t>(-1)));
  EXPECT_EQ(r.position(), 5u);
}

TEST(ByteReader, EmptyView) {
  ByteReader r(ByteView{});
  std::uint8_t x = 0;
  EXPECT_FALSE(r.u8(x));
  EXPECT_EQ(r.error(), Error::truncated);
}

TEST(Error, EveryCodeHasItsOwnName) {
  std::set<std::string> names;
  for (unsigned v = 0; v <= static_cast<unsigned>(kLastError); ++v) {
    const std::string n = error_name(static_cast<Error>(v));
    EXPECT_NE(n, "unknown") << v;
    EXPECT_TRUE(names.insert(n).second) << n;
  }
  EXPECT_STREQ(error_name(Error::crc_body), "crc_body");
  EXPECT_STREQ(error_name(Error::channel_config_required), "channel_config_required");
  EXPECT_STREQ(error_name(Error::channel_config_mismatch), "channel_config_mismatch");
  EXPECT_STREQ(error_name(static_cast<Error>(static_cast<unsigned>(kLastError) + 1)), "unknown");
}

TEST(CivilTime, HandCheckedDates) {
  // 2017-09-06 16:19:46 UTC = 1504714786 (the Pandar40P capture's first packet).
  EXPECT_EQ(unix_seconds(DateTime{2017, 9, 6, 16, 19, 46}), 1504714786);
  // 2000-02-29 exists (divisible by 400), 2100-02-29 does not.
  EXPECT_TRUE(is_valid(DateTime{2000, 2, 29, 0, 0, 0}));
  EXPECT_FALSE(is_valid(DateTime{2100, 2, 29, 0, 0, 0}));
  EXPECT_FALSE(is_valid(DateTime{2024, 4, 31, 0, 0, 0}));
  EXPECT_FALSE(is_valid(DateTime{2024, 0, 1, 0, 0, 0}));
  EXPECT_FALSE(is_valid(DateTime{1969, 12, 31, 23, 59, 59}));
}

TEST(Math, SinCosAgainstTheCLibrary) {
  double worst = 0;
  for (int i = -720000; i <= 720000; i += 7) {
    const double deg = i * 0.001;
    const SinCos sc = sin_cos_deg(deg);
    worst = std::max({worst, std::fabs(sc.sin - std::sin(deg * M_PI / 180)), std::fabs(sc.cos - std::cos(deg * M_PI / 180))});
  }
  EXPECT_LT(worst, 5e-14);  // the reference itself rounds deg x pi / 180 at +-720 degrees
  EXPECT_EQ(sin_cos_deg(0).sin, 0.0);
  EXPECT_EQ(sin_cos_deg(-90).sin, -1.0);
  EXPECT_EQ(sin_cos_deg(360).cos, 1.0);
}

// The block azimuth's sine and cosine in single precision: every value a packet can carry
// (0.00 .. 359.99 degrees) against the C library in double.
TEST(Math, SinCosCentidegreesInSinglePrecision) {
  double worst = 0;
  for (int c = 0; c < 36000; ++c) {
    const SinCosF sc = sin_cos_centideg(static_cast<std::uint16_t>(c));
    const double rad = c / 100.0 * M_PI / 180;
    worst = std::max({worst, std::fabs(sc.sin - std::sin(rad)), std::fabs(sc.cos - std::cos(rad))});
  }
  EXPECT_LT(worst, 3e-7);  // a few float ulps; at 200 m, 0.06 mm
  EXPECT_EQ(sin_cos_centideg(0).sin, 0.0f);
  EXPECT_EQ(sin_cos_centideg(9000).sin, 1.0f);
  EXPECT_EQ(sin_cos_centideg(18000).cos, -1.0f);
  EXPECT_EQ(sin_cos_centideg(27000).sin, -1.0f);
}
