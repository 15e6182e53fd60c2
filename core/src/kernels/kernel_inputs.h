// What the per-point kernels take (internal to the core): a packet's blocks as a sensor's walk
// describes them (BlockRef), and the constants each block (BlockConstants, the scalar loops of
// scalar_loops.h) or the whole packet (PacketConstants, the vector kernels) shares. The sensors'
// code fills them (sensors/block_points.h); the kernels know no sensor.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "../base/compiler.h"

// Which vector kernels this target compiles: x86-64 (GNU compilers; AVX-512 or AVX2 chosen at
// run time, vector_isa.h), AArch64 little-endian (GNU compilers; NEON), none elsewhere (Cortex-M...).
#if defined(__x86_64__) && HESAI_GNU
#define HESAI_KERNELS_X86 1
#elif defined(__aarch64__) && HESAI_GNU && !defined(__ARM_BIG_ENDIAN)
#define HESAI_KERNELS_NEON 1
#endif
#if defined(HESAI_KERNELS_X86) || defined(HESAI_KERNELS_NEON)
#define HESAI_KERNELS_VECTOR 1
#endif
// The assembly unit loops of ARMv7E-M with a single-precision FPU (Cortex-M4F, Cortex-M7; GNU
// assembler syntax, little-endian Thumb-2): armv7m_loops.h.
#if defined(__ARM_ARCH_7EM__) && defined(__thumb2__) && defined(__ARM_FP) && (__ARM_FP & 4) && HESAI_GNU && \
    !defined(__ARM_BIG_ENDIAN)
#define HESAI_KERNELS_ARMV7M 1
#endif

namespace hesai::kernels {

// One block of a packet, as a sensor's walk describes it (sensors/block_points.h, SensorBase::emit_blocks).
// No default member initialisers: a walk's array of them (`BlockRef blocks[kBlocks];`, each then
// assigned whole) is then not zeroed first, which took a memset call a packet (picolibc's stores a
// byte at a time; 670 instructions a Pandar40 packet on the Cortex-M4F, 540 a PandarXT's).
struct BlockRef {
  const std::uint8_t* units;       // the block's first unit
  const std::uint8_t* channel_of;  // unit j is channel channel_of[j] (nullptr: channel j)
  std::int32_t offset_ns;          // block time from the packet time t0
  std::uint8_t loop;               // firing sequence: 0, or 1 (the QT128's second)
};

/// The most blocks a packet has (the Pandar40's 10; PacketInfo::block_azimuth holds as many).
inline constexpr std::size_t kMaxBlocks = 10;

// The blocks of a firing (2 in dual return, 3 in triple) come together: the k-th is return k.
inline std::uint8_t return_index(std::size_t returns, std::size_t block) noexcept {
  return static_cast<std::uint8_t>(returns > 1 ? static_cast<std::uint32_t>(block) % static_cast<std::uint32_t>(returns) : 0);
}
// The return index of the block after one of return index r, for loops that walk the blocks in
// order: in the x86-64 kernels a division a block (64-bit) cost the PandarXT16 columns decode 10%,
// and a 32-bit one still 2-4% more than this.
inline std::size_t next_return_index(std::size_t r, std::size_t returns) noexcept { return r + 1 < returns ? r + 1 : 0; }

// What every unit of one block shares, for the scalar loops (scalar_loops.h).
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


// What the vector paths need of a whole packet: the same values as each block's BlockConstants,
// the per-block ones once per block, the shared ones once. No default member initialisers, as
// BlockRef: SensorBase::emit_blocks sets every member, and with them GCC 12 zeroed the 112 bytes
// of pointers first by a `rep stos` before storing each (x86-64: a tenth of a PandarXT16 columns
// decode under perf).
struct PacketConstants {
  std::size_t blocks;             // blocks in the packet
  std::size_t units;              // units per block; unit j is channel j
  std::size_t unit_bytes;         // 3 or 4 (a confidence byte)
  float unit_m;
  std::uint16_t min_distance;
  std::int64_t time_ns;           // packet time (Points)
  const float* sin_el;
  const float* elevation_deg;     // Points
  // [firing loop][channel]
  const float* dir_cos[2];
  const float* dir_sin[2];
  const float* azimuth_deg[2];    // Points
  const std::int32_t* fire_ns[2];
  const std::uint16_t* block_azimuth;  // [block], 0.01 degree, below 36000 (validate())
  const BlockRef* block;               // [block]: no channel maps
  std::uint8_t returns;                // block b is return b % returns of its firing
};


}  // namespace hesai::kernels
