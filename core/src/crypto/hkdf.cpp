#include "hesai/hkdf.h"

#include <cstring>

#include "hesai/ct.h"
#include "hesai/hmac.h"

namespace hesai {
namespace {
constexpr std::uint8_t kSessionKeyInfo[] = {'f', 'i', 'n', 'i', 's', 'h', ' ', 's', 'e',
                                            's', 's', 'i', 'o', 'n', ' ', 'k', 'e', 'y'};
static_assert(sizeof kSessionKeyInfo == 18, "\"finish session key\", no NUL");
}  // namespace

// RFC 5869 section 2.2. HMAC zero-pads its key to the block, so the empty salt already
// equals the RFC's default of HashLen zero bytes.
void hkdf_sha256_extract(ByteView salt, ByteView ikm, std::uint8_t prk[kSha256Size]) noexcept {
  hmac_sha256(salt, ikm, prk);
}

// RFC 5869 section 2.3: T(i) = HMAC(PRK, T(i-1) || info || i), T(0) empty; OKM = T(1) || T(2)...
Error hkdf_sha256_expand(ByteView prk, ByteView info, std::uint8_t* out, std::size_t len) noexcept {
  if (len > kHkdfSha256MaxLength) return Error::invalid_argument;
  const HmacSha256Key key(prk);
  HmacSha256 mac(key);
  std::uint8_t t[kSha256Size];
  std::uint8_t counter = 1;
  for (std::size_t done = 0; done < len; done += kSha256Size, ++counter) {
    if (done != 0) mac.update({t, sizeof t});  // T(i-1); T(0) is empty
    mac.update(info);
    mac.update({&counter, 1});
    mac.finish(t);
    std::memcpy(out + done, t, len - done < kSha256Size ? len - done : kSha256Size);
  }
  secure_wipe(t, sizeof t);
  return Error::ok;
}

Error hkdf_sha256(ByteView salt, ByteView ikm, ByteView info, std::uint8_t* out,
                  std::size_t len) noexcept {
  if (len > kHkdfSha256MaxLength) return Error::invalid_argument;
  std::uint8_t prk[kSha256Size];
  hkdf_sha256_extract(salt, ikm, prk);
  const Error e = hkdf_sha256_expand({prk, sizeof prk}, info, out, len);
  secure_wipe(prk, sizeof prk);
  return e;
}

Error hesai_session_key(ByteView secret, const std::uint8_t lidar_random[32],
                        const std::uint8_t client_random[32], std::uint8_t key[32]) noexcept {
  if (secret.size < kHesaiSecretMin || secret.size > kHesaiSecretMax) return Error::invalid_argument;
  std::uint8_t salt[64];  // the two randoms travel in clear: not secret
  std::memcpy(salt, lidar_random, 32);
  std::memcpy(salt + 32, client_random, 32);
  return hkdf_sha256({salt, sizeof salt}, secret, {kSessionKeyInfo, sizeof kSessionKeyInfo}, key, 32);
}

}  // namespace hesai
