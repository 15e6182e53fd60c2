// The vector paths of the columnar decode (internal to the core): Decoder::emit_block hands
// them a block's units when the caller asked for columns and the units need no channel map; they
// write whole vectors of units and leave the rest to the scalar loop in block_points.h, which
// every target has. Each gives the scalar loop's values: the same float operations in the same
// order, no fused multiply-add (tests/test_columns.cpp checks every point of every capture).
// - x86-64 (GNU compilers): AVX2, chosen at run time from CPUID (columns_x86.cpp).
// - AArch64 (GNU compilers, little-endian): NEON, at compile time (columns_neon.cpp).
// - Elsewhere (Cortex-M, ...): none; columns_simd() is 0 and the scalar loop does every unit.
#pragma once

#include <array>
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
  // Points only.
  float block_deg = 0;               // block azimuth, degrees
  std::int64_t block_time_ns = 0;    // block time
  std::uint8_t block = 0;            // block index
  const float* azimuth_deg = nullptr;    // [channel]: beam azimuth of the block's firing loop
  const float* elevation_deg = nullptr;  // [channel]
};

#if defined(HESAI_COLUMNS_AVX2) || defined(HESAI_COLUMNS_NEON)
// Both vector paths take eight units a step, with these tables.
// For each 8-bit mask of kept lanes, the indices of the kept lanes, lowest first, one byte each
// (the rest 0): the permutation that packs them to the front (2 KiB).
constexpr std::array<std::uint64_t, 256> compress_table() {
  std::array<std::uint64_t, 256> t{};
  for (std::size_t m = 0; m < 256; ++m) {
    std::uint64_t v = 0;
    unsigned k = 0;
    for (unsigned lane = 0; lane < 8; ++lane)
      if (m & (1u << lane)) v |= static_cast<std::uint64_t>(lane) << (8 * k++);
    t[m] = v;
  }
  return t;
}
inline constexpr std::array<std::uint64_t, 256> kCompress = compress_table();

// Byte shuffles of one 16-byte load holding four units (the first at byte `first`, `stride`
// bytes apart): each unit's distance (little-endian 16 bits) into a 32-bit lane, and its intensity
// byte (and a 4-byte unit's confidence byte) into byte `to` + i. -1 clears.
struct UnitShuffle {
  std::int8_t distance[16], intensity[16], confidence[16];  // confidence: 4-byte units only
};
constexpr UnitShuffle unit_shuffle(int first, int stride, int to) {
  UnitShuffle u{};
  for (int i = 0; i < 16; ++i) u.distance[i] = u.intensity[i] = u.confidence[i] = -1;
  for (int i = 0; i < 4; ++i) {
    const int at = first + i * stride;
    u.distance[4 * i] = static_cast<std::int8_t>(at);
    u.distance[4 * i + 1] = static_cast<std::int8_t>(at + 1);
    u.intensity[to + i] = static_cast<std::int8_t>(at + 2);
    if (stride == 4) u.confidence[to + i] = static_cast<std::int8_t>(at + 3);
  }
  return u;
}
// [unit_bytes == 4][half]: units 0..3 from the 16 bytes at the first unit, 4..7 from the 16 bytes
// at kSecond[unit_bytes == 4]: 3-byte units 4..7 start at byte 12, read from byte 8 so as not to
// read past unit 7.
inline constexpr UnitShuffle kShuffle[2][2] = {{unit_shuffle(0, 3, 0), unit_shuffle(4, 3, 4)},
                                               {unit_shuffle(0, 4, 0), unit_shuffle(0, 4, 4)}};
inline constexpr std::size_t kSecond[2] = {8, 16};

// Units [0, done) of a block whose unit j is channel j (unit_bytes 3 or 4), written as columns at
// out[count...], count advanced by the points kept; returns done (a multiple of 8, 0 when the CPU
// lacks the instructions). Writes whole vectors: up to 7 entries past the new count, all below
// the block's own units, so below max_points.

// `out` by value: stores through its byte columns may alias anything in memory but not a local
// copy, whose pointers then stay in registers.
std::size_t columns_simd(const BlockConstants& k, const std::uint8_t* units, std::size_t unit_count,
                         std::size_t unit_bytes, PointColumns out, std::size_t& count) noexcept;
// The same as Points at out[count...] (x86-64 only so far: 0 on AArch64).
std::size_t points_simd(const BlockConstants& k, const std::uint8_t* units, std::size_t unit_count,
                        std::size_t unit_bytes, Point* out, std::size_t& count) noexcept;
/// Whether columns_simd() runs vector code on this CPU.
bool columns_simd_available() noexcept;
#else
inline std::size_t columns_simd(const BlockConstants&, const std::uint8_t*, std::size_t, std::size_t, PointColumns,
                                std::size_t&) noexcept {
  return 0;
}
inline std::size_t points_simd(const BlockConstants&, const std::uint8_t*, std::size_t, std::size_t, Point*,
                               std::size_t&) noexcept {
  return 0;
}
inline bool columns_simd_available() noexcept { return false; }
#endif

}  // namespace hesai::detail
