#include "hesai/ct.h"

#include <cstring>

namespace hesai {

bool constant_time_equal(const std::uint8_t* a, const std::uint8_t* b, std::size_t n) noexcept {
  std::uint32_t diff = 0;
  for (std::size_t i = 0; i < n; ++i) {
    diff |= static_cast<std::uint32_t>(a[i] ^ b[i]);
    // The empty asm hides `diff` from the optimiser, so it cannot stop the loop early once a
    // difference is known, nor rewrite the loop as a call to memcmp.
    __asm__ volatile("" : "+r"(diff));
  }
  // diff is 0..255: (diff - 1) borrows into bit 8 exactly when diff == 0.
  return ((diff - 1u) >> 8) & 1u;
}

void secure_wipe(void* p, std::size_t n) noexcept {
  if (n == 0) return;
  std::memset(p, 0, n);
  // The asm may read any memory through `p`, so the stores above must happen.
  __asm__ volatile("" : : "r"(p) : "memory");
}

}  // namespace hesai
