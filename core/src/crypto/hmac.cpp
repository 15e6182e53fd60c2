#include "hesai/hmac.h"

#include <cstring>

namespace hesai {

// RFC 2104 section 2: K0 = key zero-padded to the block (hashed first if longer);
// inner = H((K0 ^ ipad) || msg), outer = H((K0 ^ opad) || inner).
void HmacSha256Key::set(ByteView key, Sha256Path path) noexcept {
  std::uint8_t k0[kSha256BlockSize] = {};
  if (key.size > kSha256BlockSize) {
    inner_.reset(path);  // hashes the long key here rather than in a context on the stack
    inner_.update(key);
    inner_.finish(k0);
  } else if (key.size != 0) {
    std::memcpy(k0, key.data, key.size);
  }
  for (std::uint8_t& b : k0) b ^= 0x36;  // ipad
  inner_.reset(path);
  inner_.update({k0, sizeof k0});
  for (std::uint8_t& b : k0) b ^= 0x36 ^ 0x5c;  // ipad off, opad on
  outer_.reset(path);
  outer_.update({k0, sizeof k0});
  secure_wipe(k0, sizeof k0);
}

void HmacSha256Key::wipe() noexcept {
  inner_.reset();  // back to the public initial state; the buffered bytes are wiped
  outer_.reset();
}

void HmacSha256::finish(std::uint8_t out[kSha256Size]) noexcept {
  std::uint8_t inner_digest[kSha256Size];
  inner_.finish(inner_digest);
  inner_ = key_->outer_;  // the outer hash reuses this context: no second one on the stack
  inner_.update({inner_digest, sizeof inner_digest});
  inner_.finish(out);
  secure_wipe(inner_digest, sizeof inner_digest);
  inner_ = key_->inner_;
}

void hmac_sha256(ByteView key, ByteView msg, std::uint8_t out[kSha256Size]) noexcept {
  const HmacSha256Key k(key);
  HmacSha256 mac(k);
  mac.update(msg);
  mac.finish(out);
}

}  // namespace hesai
