// The vector paths of the decode (internal to the core): Decoder::emit_blocks hands them a whole
// packet's blocks, once per packet, when the units need no channel map; they write every unit, or
// decline (return false) and the scalar loops in block_points.h, which every target has, write
// them. Each gives the scalar loop's values: the same float operations in the same order, no fused
// multiply-add (tests/test_columns.cpp checks every point of every capture on every path).
// - x86-64 (GNU compilers), chosen at run time from CPUID: AVX-512 (F, BW, DQ, VL) where present,
//   else AVX2, for columns and Points (columns_x86.cpp).
// - AArch64 (GNU compilers, little-endian): NEON for columns and Points, at compile time
//   (columns_neon.cpp).
// - Elsewhere (Cortex-M, ...): none; the scalar loops write every unit.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "../base/compiler.h"
#include "hesai/decoder.h"
#include "hesai/detail/math.h"
#include "hesai/point.h"

#if defined(__x86_64__) && HESAI_GNU
#define HESAI_COLUMNS_AVX2 1
#elif defined(__aarch64__) && HESAI_GNU && !defined(__ARM_BIG_ENDIAN)
#define HESAI_COLUMNS_NEON 1
#endif
#if defined(HESAI_COLUMNS_AVX2) || defined(HESAI_COLUMNS_NEON)
#define HESAI_DECODE_SIMD 1
#endif

namespace hesai::detail {

// One block of a packet, as a sensor's walk describes it (Decoder::emit_blocks).
struct BlockRef {
  const std::uint8_t* units = nullptr;       // the block's first unit
  const std::uint8_t* channel_of = nullptr;  // unit j is channel channel_of[j] (nullptr: channel j)
  std::int32_t offset_ns = 0;                // block time from the packet time t0
  std::uint8_t loop = 0;                     // firing sequence: 0, or 1 (the QT128's second)
};

// The blocks of a firing (2 in dual return, 3 in triple) come together: the k-th is return k.
inline std::uint8_t return_index(std::size_t returns, std::size_t block) noexcept {
  return static_cast<std::uint8_t>(returns > 1 ? block % returns : 0);
}

// What every unit of one block shares, for the scalar loops (block_points.h).
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

#if defined(HESAI_DECODE_SIMD)
/// The most blocks a packet has (the Pandar40's 10; PacketInfo::block_azimuth holds as many).
inline constexpr std::size_t kMaxBlocks = 10;

// What the vector paths need of a whole packet: the same values as each block's BlockConstants,
// the per-block ones once per block, the shared ones once.
struct PacketConstants {
  std::size_t blocks = 0;            // blocks in the packet
  std::size_t units = 0;             // units per block; unit j is channel j
  std::size_t unit_bytes = 3;        // 3 or 4 (a confidence byte)
  float unit_m = 0;
  std::uint16_t min_distance = 1;
  std::int64_t time_ns = 0;          // packet time (Points)
  const float* sin_el = nullptr;
  const float* elevation_deg = nullptr;  // Points
  // [firing loop][channel]
  const float* dir_cos[2] = {};
  const float* dir_sin[2] = {};
  const float* azimuth_deg[2] = {};  // Points
  const std::int32_t* fire_ns[2] = {};
  const std::uint16_t* block_azimuth = nullptr;  // [block], 0.01 degree, below 36000 (validate())
  const BlockRef* block = nullptr;               // [block]: no channel maps
  std::uint8_t returns = 1;                      // block b is return b % returns of its firing
};

// sin and cos of each block azimuth of the packet, block b at index b (all computed before the
// first block's units: independent chains that overlap, where one per block would wait).
struct BlockSinCos {
  float sin[kMaxBlocks], cos[kMaxBlocks];
};
inline BlockSinCos block_sin_cos(const PacketConstants& k) noexcept {
  BlockSinCos out;
  for (std::size_t b = 0; b < k.blocks; ++b) {
    const SinCosF v = sin_cos_centideg(k.block_azimuth[b]);
    out.sin[b] = v.sin, out.cos[b] = v.cos;
  }
  return out;
}

// The eight-unit steps (AVX2, NEON) use these tables.
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

// Every unit of every block of k, written as columns at out[count...], count advanced by the
// points kept; false (nothing written) when `path` has no vector code on this CPU or for this
// block size. Writes whole vectors: entries past the new count, all below the units decoded so
// far, so below max_points.
// `out` by value: stores through its byte columns may alias anything in memory but not a local
// copy, whose pointers then stay in registers.
bool columns_simd(const PacketConstants& k, DecodePath path, PointColumns out, std::size_t& count) noexcept;
// The same as Points at out[count...].
bool points_simd(const PacketConstants& k, DecodePath path, Point* out, std::size_t& count) noexcept;
/// Whether DecodePath::best runs vector code on this CPU, and which (hesai::decode_simd_name()).
bool columns_simd_available() noexcept;
const char* columns_simd_name() noexcept;
#else
inline bool columns_simd_available() noexcept { return false; }
inline const char* columns_simd_name() noexcept { return "none"; }
#endif

}  // namespace hesai::detail
