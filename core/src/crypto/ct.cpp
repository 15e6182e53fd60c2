#include "hesai/ct.h"

#include <cstring>

#include "../base/compiler.h"

namespace hesai {
namespace {

// Hides `v` from the optimiser: afterwards it cannot know the value, so it can neither stop a
// loop early once the value is known nor rewrite the loop as a call to memcmp.
#if HESAI_GNU
inline void opaque(std::uint32_t& v) noexcept { __asm__ volatile("" : "+r"(v)); }
#else
// ISO C++: a volatile access is observable behaviour, so the value must round-trip memory.
inline void opaque(std::uint32_t& v) noexcept {
  volatile std::uint32_t cell = v;
  v = cell;
}
#endif

}  // namespace

bool constant_time_equal(const std::uint8_t* a, const std::uint8_t* b, std::size_t n) noexcept {
  std::uint32_t diff = 0;
  for (std::size_t i = 0; i < n; ++i) {
    diff |= static_cast<std::uint32_t>(a[i] ^ b[i]);
    opaque(diff);
  }
  // diff is 0..255: (diff - 1) borrows into bit 8 exactly when diff == 0.
  return ((diff - 1u) >> 8) & 1u;
}

void secure_wipe(void* p, std::size_t n) noexcept {
  if (n == 0) return;
#if HESAI_GNU
  std::memset(p, 0, n);
  // The asm may read any memory through `p`, so the stores above must happen.
  __asm__ volatile("" : : "r"(p) : "memory");
#else
  // ISO C++: stores through a volatile lvalue are observable behaviour and cannot be dropped
  // (Mbed TLS's mbedtls_platform_zeroize falls back the same way). Byte stores: the wiped
  // buffers are key states and blocks of at most 64 bytes.
  volatile std::uint8_t* q = static_cast<volatile std::uint8_t*>(p);
  for (std::size_t i = 0; i < n; ++i) q[i] = 0;
#endif
}

}  // namespace hesai
