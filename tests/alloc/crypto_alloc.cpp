// SHA-256, HMAC-SHA256 and HKDF-SHA256 allocate nothing.
#include <gtest/gtest.h>

#include <cstdint>

#include "alloc_counter.h"
#include "hesai/hkdf.h"
#include "hesai/hmac.h"
#include "hesai/sha256.h"

TEST(ZeroAllocation, Crypto) {
  std::uint8_t data[300];
  for (std::size_t i = 0; i < sizeof data; ++i) data[i] = static_cast<std::uint8_t>(i * 7);
  const hesai::ByteView msg(data, sizeof data);
  const hesai::ByteView long_key(data, 131);  // hashed first
  std::uint8_t out[64];
  hesai::Error expanded = hesai::Error::truncated, derived = hesai::Error::truncated, session = hesai::Error::truncated;

  const std::size_t n = hesai_test::allocations_during([&] {
    for (hesai::Sha256Path path : {hesai::Sha256Path::portable, hesai::Sha256Path::hardware}) {
      hesai::Sha256 h(path);
      h.update(msg);
      h.update(msg.sub(0, 17));
      h.finish(out);
    }
    hesai::sha256(msg, out);

    hesai::HmacSha256Key key;
    key.set(long_key);
    key.set(msg.sub(0, 32));
    hesai::HmacSha256 mac(key);
    mac.update(msg);
    mac.finish(out);
    mac.update(msg.sub(0, 5));
    mac.finish(out);
    hesai::hmac_sha256(msg.sub(0, 16), msg, out);

    std::uint8_t prk[32];
    hesai::hkdf_sha256_extract(msg.sub(0, 13), msg.sub(13, 22), prk);
    expanded = hesai::hkdf_sha256_expand({prk, sizeof prk}, msg.sub(40, 10), out, sizeof out);
    derived = hesai::hkdf_sha256(msg.sub(0, 64), msg.sub(64, 16), msg.sub(80, 18), out, 42);
    session = hesai::hesai_session_key(msg.sub(0, 16), data + 32, data + 64, out);  // 16-byte secret: 8..32
  });
  EXPECT_EQ(n, 0u);
  EXPECT_EQ(expanded, hesai::Error::ok);  // 64 bytes <= 255 * 32
  EXPECT_EQ(derived, hesai::Error::ok);
  EXPECT_EQ(session, hesai::Error::ok);
}
