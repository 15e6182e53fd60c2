// The vector kernels (internal to the core): SensorBase::emit_blocks (sensors/block_points.h)
// hands them a whole packet's blocks, once per packet, when the units need no channel map; they
// write every unit, or decline (return false) and the scalar loops (scalar_loops.h), which every
// target has, write them. Each gives the scalar loop's values: the same float operations in the
// same order, no fused multiply-add (tests/kernels/test_columns.cpp checks every point of every capture on
// every path).
// - x86-64: AVX-512 (F, BW, DQ, VL) sixteen units a step, AVX2 eight (x86_columns.cpp,
//   x86_points.cpp, their shared loads in x86_units.h).
// - AArch64: NEON, eight units a step (neon_columns.cpp, neon_points.cpp, neon_units.h).
// vector_isa.h picks which one runs.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/detail/math.h"
#include "hesai/point.h"
#include "kernel_inputs.h"
#include "vector_isa.h"

#if defined(HESAI_KERNELS_VECTOR)

namespace hesai::kernels {

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
// points kept; false (nothing written) when `isa` has no kernel here or for this block size.
// Writes whole vectors: entries past the new count, all below the units decoded so far, so below
// max_points. `out` by value: stores through its byte columns may alias anything in memory but
// not a local copy, whose pointers then stay in registers.
bool columns_vector(const PacketConstants& k, VectorIsa isa, PointColumns out, std::size_t& count) noexcept;
// The same as Points at out[count...].
bool points_vector(const PacketConstants& k, VectorIsa isa, Point* out, std::size_t& count) noexcept;

// What the unit scan (the sensors' UnitScan) needs of a packet: its blocks, with no channel maps.
struct ScanConstants {
  const BlockRef* block;       // [block]
  std::size_t blocks;          // at most kMaxBlocks
  std::size_t units;           // units per block; unit j is channel j
  std::size_t unit_bytes;      // 3 or 4
  std::uint32_t limit;         // distances above it are beyond the rated range
  std::uint16_t min_distance;  // a repeated return's smallest distance
  bool markers;                // distance 1 is a blockage marker
  bool dual;                   // blocks 2f and 2f + 1 are the two returns of firing f
};
// Where it writes: counts, per-channel blockage counters (kMaxChannels of them, each advanced by
// one a marker, wrapping as a std::uint8_t), and each firing's repeated-return bits (bit c % 8 of
// byte c / 8; a null row keeps none), OR-ed in.
struct ScanOutput {
  std::uint32_t blockage, beyond, duplicates;
  std::uint8_t* blockage_by_channel;
  std::uint8_t* repeated[kMaxBlocks / 2];
};
// The scalar scan's counts and bits for the units of k, added to `out`; false (nothing written)
// when `isa` has no scan here or for this block size (AVX2, chosen for AVX-512 too: steps of
// eight units, at most kMaxChannels of them).
bool scan_vector(const ScanConstants& k, VectorIsa isa, ScanOutput& out) noexcept;

}  // namespace hesai::kernels

#endif  // HESAI_KERNELS_VECTOR
