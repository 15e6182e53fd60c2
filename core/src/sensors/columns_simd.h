// The vector paths of the columnar decode (internal to the core): Decoder::emit_block hands
// them a block's units when the caller asked for columns and the units need no channel map; they
// write whole vectors of units and leave the rest to the scalar loop in block_points.h, which
// every target has. Each gives the scalar loop's values: the same float operations in the same
// order, no fused multiply-add (tests/test_columns.cpp checks every point of every capture).
// - x86-64 (GNU compilers): AVX2, chosen at run time from CPUID (columns_x86.cpp).
// - AArch64 (GNU compilers, little-endian): NEON, at compile time (columns_neon.cpp).
// - Elsewhere (Cortex-M, ...): none; columns_simd() is 0 and the scalar loop does every unit.
#pragma once

#include <cstddef>
#include <cstdint>

#include "../base/compiler.h"
#include "hesai/point.h"

#if defined(__x86_64__) && HESAI_GNU
#define HESAI_COLUMNS_AVX2 1
#elif defined(__aarch64__) && HESAI_GNU && !defined(__ARM_BIG_ENDIAN)
#define HESAI_COLUMNS_NEON 1
#endif

namespace hesai::detail {

// What every unit of one block shares, for the scalar loops and the vector paths alike.
struct BlockConstants {
  float sin_a = 0, cos_a = 0;        // of the block azimuth
  float unit_m = 0;                  // distance step, metres
  std::int32_t offset_ns = 0;        // block time from the packet time
  std::uint16_t min_distance = 1;    // raw distances below it yield no point
  std::uint8_t return_index = 0;
  const float* dir_cos = nullptr;    // [channel]: the spin cache of the block's firing loop
  const float* dir_sin = nullptr;
  const float* sin_el = nullptr;
  const std::int32_t* fire_ns = nullptr;
};

#if defined(HESAI_COLUMNS_AVX2) || defined(HESAI_COLUMNS_NEON)
// Units [0, done) of a block whose unit j is channel j (unit_bytes 3 or 4), written as columns at
// out[count...], count advanced by the points kept; returns done (a multiple of the vector width,
// 0 when the CPU lacks the instructions). Writes whole vectors: up to 7 entries past the new count,
// all below the block's own units, so below max_points.
std::size_t columns_simd(const BlockConstants& k, const std::uint8_t* units, std::size_t unit_count,
                         std::size_t unit_bytes, const PointColumns& out, std::size_t& count) noexcept;
/// Whether columns_simd() runs vector code on this CPU.
bool columns_simd_available() noexcept;
#else
inline std::size_t columns_simd(const BlockConstants&, const std::uint8_t*, std::size_t, std::size_t,
                                const PointColumns&, std::size_t&) noexcept {
  return 0;
}
inline bool columns_simd_available() noexcept { return false; }
#endif

}  // namespace hesai::detail
