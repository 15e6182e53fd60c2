// The NEON kernels' shared parts (internal to the core; neon_columns.cpp and neon_points.cpp):
// the byte shuffles that pack kept lanes. Compiled for every little-endian AArch64 target (NEON
// is part of ARMv8-A); empty on other targets.
#pragma once

#include "vector_kernels.h"

#if defined(HESAI_KERNELS_NEON)

#include <arm_neon.h>

#include <array>
#include <cstdint>

namespace hesai::kernels {

// For each 4-bit mask of kept 32-bit lanes, the byte shuffle that packs them to the front.
constexpr std::array<std::array<std::uint8_t, 16>, 16> compress4_table() {
  std::array<std::array<std::uint8_t, 16>, 16> t{};
  for (std::size_t m = 0; m < 16; ++m) {
    for (auto& b : t[m]) b = 0xFF;  // out of range: vqtbl1q gives 0
    unsigned k = 0;
    for (unsigned lane = 0; lane < 4; ++lane) {
      if (!(m & (1u << lane))) continue;
      for (unsigned b = 0; b < 4; ++b) t[m][4 * k + b] = static_cast<std::uint8_t>(4 * lane + b);
      ++k;
    }
  }
  return t;
}
inline constexpr std::array<std::array<std::uint8_t, 16>, 16> kCompress4 = compress4_table();

inline uint8x16_t load_shuffle(const std::int8_t* p) noexcept { return vreinterpretq_u8_s8(vld1q_s8(p)); }

// 32-bit lanes kept by `keep` stored packed at `to`.
inline void store_packed(std::uint8_t* to, uint8x16_t lanes, unsigned keep) noexcept {
  vst1q_u8(to, vqtbl1q_u8(lanes, vld1q_u8(kCompress4[keep].data())));
}

}  // namespace hesai::kernels

#endif  // HESAI_KERNELS_NEON
