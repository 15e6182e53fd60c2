// The unit loops for ARMv7E-M with a single-precision FPU (Cortex-M4F, Cortex-M7), written in
// assembly (armv7m_loops.cpp; internal to the core). They compute what the scalar loops of
// scalar_loops.h compute, the same float operations on the same operands (a VMLA/VMLS is a
// multiply rounded, then an add rounded, as GCC's own code for those loops uses it), so the same
// bits: the firmware image decodes every packet both ways and compares (tests/firmware/).
//
// Why assembly: GCC 12 at -Os keeps about 18 values live in the C loop against 13 registers and
// reloads the rest from the stack on every unit (42 instructions a unit as columns, 51 as Points).
// Here each block's constants sit in registers (the FPU's spare ones among them), every table of a
// channel is reached from one walked pointer with a fixed offset, and two units make a step, so a
// unit takes 31.5 instructions as columns and 36 as Points (38 with 4-byte units).
// SensorBase::emit_blocks (sensors/block_points.h) calls them one block at a time for packets whose
// blocks have an even number of units and no channel map, unless the caller asked for
// DecodePath::portable.
#pragma once

#include <cstddef>
#include <cstdint>

#include "hesai/model.h"
#include "hesai/point.h"
#include "kernel_inputs.h"

#if defined(HESAI_KERNELS_ARMV7M)

namespace hesai::kernels {

// The fixed offsets the loops use: dir_sin and azimuth_deg lie one and two tables (kMaxChannels
// values, HESAI_ARMV7M_TABLE bytes) after dir_cos, elevation_deg and fire_ns[loop] one and 2 + loop
// tables after sin_el. Decoder::Geometry and Decoder::SpinCache are laid out so; block_points.h
// checks it with static_asserts.
#define HESAI_ARMV7M_TABLE 512
inline constexpr std::size_t kArmTableBytes = HESAI_ARMV7M_TABLE;
static_assert(kArmTableBytes == kMaxChannels * 4, "a table is kMaxChannels floats or int32s");

// One block for the Points loop. The field order is the loop's register order (one LDM, one VLDM):
// do not reorder. A block has an even number of units, 2 to 256.
struct ArmPointsBlock {
  const std::uint8_t* units;      // r0: the block's first unit
  Point* out;                     // r1: where the next point goes
  const float* dir_cos;           // r2: the block's firing loop's dir_cos (dir_sin, azimuth_deg follow)
  const float* sin_el;            // r3: Geometry::sin_el (elevation_deg, fire_ns follow)
  std::uint32_t tag;              // r4: channel 1 << 8 | return index << 16 (a Point's bytes 32-35)
  std::uint32_t keep_bias;        // r5: (0x10000 - min_distance) << 16: raw << 16 + it carries iff raw >= min
  std::uint32_t block_and_steps;  // r6: the block index | (units / 2 - 1) << 8
  float sin_a, cos_a;             // s10, s11: of the block azimuth
  float unit_m;                   // s12
  float block_deg;                // s13
  float full_turn;                // s14: 360
  std::uint32_t block_time_lo;    // s15, s16: the block time, ns, low and high words
  std::uint32_t block_time_hi;
  // The unit scan's (the _scan and _repeat loops only):
  std::uint32_t limit_bias;       // r11: 0x7FFFFFFF - the largest raw distance within the rated range
  std::int32_t first_offset;      // r12: the first return's unit from this unit's end (_repeat): its
                                  // block's units - this block's units - the unit size
};

// One block for the columns loop, the same way.
struct ArmColumnsBlock {
  const std::uint8_t* units;        // r0
  std::uint32_t return_index;       // r1
  std::size_t n;                    // r2: the next column index
  float* x;                         // r3-r7: columns
  float* y;
  float* z;
  std::int32_t* time_ns;
  std::uint8_t* intensity;
  const float* dir_cos;             // r8
  const float* sin_el;              // r9
  std::uint32_t keep_bias;          // r10
  std::uint32_t channel_and_steps;  // r11: 1 (the first unit's channel) | (units / 2 - 1) << 8
  float sin_a, cos_a;               // s7, s8
  float unit_m;                     // s9
  std::int32_t offset_ns;           // s10: the block time from the packet time
  std::uint8_t* channel_column;     // s11, s12: the last two columns
  std::uint8_t* return_column;
};

static_assert(sizeof(void*) == 4 && offsetof(ArmPointsBlock, sin_a) == 28 && offsetof(ArmPointsBlock, block_time_hi) == 52 &&
                  offsetof(ArmPointsBlock, limit_bias) == 56 && offsetof(ArmPointsBlock, first_offset) == 60,
              "armv7m_loops.cpp loads ArmPointsBlock at these offsets");
static_assert(offsetof(ArmColumnsBlock, sin_a) == 48 && offsetof(ArmColumnsBlock, return_column) == 68,
              "armv7m_loops.cpp loads ArmColumnsBlock at these offsets");
static_assert(offsetof(Point, distance_m) == 12 && offsetof(Point, elevation_deg) == 20 && offsetof(Point, time_ns) == 24 &&
                  offsetof(Point, intensity) == 32 && offsetof(Point, block) == 36 && sizeof(Point) == 40,
              "armv7m_loops.cpp stores a Point at these offsets");

// Each returns where the next point goes: the pointer past the last Point kept, or the next column
// index. u3/u4: 3- or 4-byte units; l0/l1: the block's firing loop (which fire_ns table).
extern "C" {
Point* hesai_armv7m_points_u3_l0(const ArmPointsBlock* block) noexcept;
Point* hesai_armv7m_points_u3_l1(const ArmPointsBlock* block) noexcept;
Point* hesai_armv7m_points_u4_l0(const ArmPointsBlock* block) noexcept;
Point* hesai_armv7m_points_u4_l1(const ArmPointsBlock* block) noexcept;
// The same with the unit scan folded in (issue #43: the units read once). _scan: Q (the sticky
// saturation flag of APSR, which nothing else on the path sets; clear it first) is set if any unit
// lies beyond the rated range (raw > limit, a QADD a unit) or, in the u4m loops (models whose
// smallest kept distance is above 1), is not kept yet not 0 (a blockage marker, distance 1, or
// below the smallest kept distance: an SSAT a unit): then the caller counts those exactly in C.
// The u4 loop checks neither (models with neither a rated range nor markers; their first returns
// take the plain loops). _repeat, for the second return of a dual-return firing, at most 32 units
// a call: the same, and returns in the high word the units that repeat the first return's (the
// same distance and reflectivity, kept), unit i of n at bit 32 - n + i; the low word is the out
// pointer.
Point* hesai_armv7m_points_scan_u3_l0(const ArmPointsBlock* block) noexcept;
Point* hesai_armv7m_points_scan_u3_l1(const ArmPointsBlock* block) noexcept;
Point* hesai_armv7m_points_scan_u4m_l0(const ArmPointsBlock* block) noexcept;
Point* hesai_armv7m_points_scan_u4m_l1(const ArmPointsBlock* block) noexcept;
std::uint64_t hesai_armv7m_points_repeat_u3_l0(const ArmPointsBlock* block) noexcept;
std::uint64_t hesai_armv7m_points_repeat_u3_l1(const ArmPointsBlock* block) noexcept;
std::uint64_t hesai_armv7m_points_repeat_u4_l0(const ArmPointsBlock* block) noexcept;
std::uint64_t hesai_armv7m_points_repeat_u4m_l0(const ArmPointsBlock* block) noexcept;
std::uint64_t hesai_armv7m_points_repeat_u4m_l1(const ArmPointsBlock* block) noexcept;
std::size_t hesai_armv7m_columns_u3_l0(const ArmColumnsBlock* block) noexcept;
std::size_t hesai_armv7m_columns_u3_l1(const ArmColumnsBlock* block) noexcept;
std::size_t hesai_armv7m_columns_u4_l0(const ArmColumnsBlock* block) noexcept;
std::size_t hesai_armv7m_columns_u4_l1(const ArmColumnsBlock* block) noexcept;
}

// The Q flag of APSR: cleared before a packet's _scan/_repeat calls, read after them. A spurious
// Q (a saturating instruction of the compiler's in between) only costs the exact count in C.
inline void clear_saturation() noexcept { __asm volatile("msr APSR_nzcvq, %0" : : "r"(0u) : "cc"); }
inline bool saturated() noexcept {
  std::uint32_t apsr;
  __asm volatile("mrs %0, APSR" : "=r"(apsr));
  return (apsr & (1u << 27)) != 0;
}

// Set bits of a word (the repeated units of a chunk): ARMv7E-M has no popcount instruction.
inline std::uint32_t bit_count(std::uint32_t v) noexcept {
  v = v - ((v >> 1) & 0x55555555u);
  v = (v & 0x33333333u) + ((v >> 2) & 0x33333333u);
  v = (v + (v >> 4)) & 0x0F0F0F0Fu;
  return (v * 0x01010101u) >> 24;
}

}  // namespace hesai::kernels

#endif  // HESAI_KERNELS_ARMV7M
