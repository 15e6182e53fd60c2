// From a sensor's walk to the per-point kernels (internal to the core): each sensor's file
// describes its packet's blocks as BlockRefs and calls SensorBase::emit_blocks once per packet,
// which fills the kernels' inputs from the decoder's geometry and beam cache and writes Points or
// columns, whichever the caller of decode() asked for, into a DecodeOutput: by a vector kernel
// where one takes the whole packet, else block by block by the scalar loops (core/src/kernels/).
#pragma once

#include <cstddef>
#include <cstdint>

#include "../base/compiler.h"
#include "../kernels/armv7m_loops.h"
#include "../kernels/kernel_counters.h"
#include "../kernels/scalar_loops.h"
#include "../kernels/vector_kernels.h"
#include "hesai/bytes.h"
#include "hesai/decoder.h"
#include "hesai/detail/math.h"
#include "sensor.h"

namespace hesai {

// Where a block walk writes: Points (points != nullptr) or columns, and the points so far.
struct DecodeOutput {
  // A constructor of its own, so that each member is set by a store of its own: GCC zeroed the
  // whole by a memset call (picolibc's, a byte at a time: 160 instructions a packet on the
  // Cortex-M4F, 200 on the M0+).
  DecodeOutput() noexcept {}
  Point* points = nullptr;
  PointColumns columns;
  DecodePath path = DecodePath::best;
  std::size_t count = 0;
  UnitScan* scan = nullptr;  // when set, the units are scanned too (scan_units)
  Decoder::UnitPass units{};  // when set, run over the units (each return compared with its firing's others; or counted)

  // Replaces the intensity of points [first, count) by table[intensity].
  void map_intensity(std::size_t first, const std::uint8_t* table) noexcept {
    for (std::size_t i = first; i < count; ++i) {
      std::uint8_t& v = points != nullptr ? points[i].intensity : columns.intensity[i];
      v = table[v];
    }
  }
};

// Whether a unit of any block needs a channel map (customised QT128 channels): the scalar loops then.
HESAI_ALWAYS_INLINE inline bool has_channel_map(const kernels::BlockRef* blocks, std::size_t block_count) noexcept {
  bool mapped = false;
  for (std::size_t b = 0; b < block_count; ++b) mapped = mapped || blocks[b].channel_of != nullptr;
  return mapped;
}

// The largest raw distance within the rated range: distance x unit > rated  <=>  distance >
// floor(rated / unit), for whole numbers; the limit is far above the smallest kept distance
// (50 000 or 12 500 at 4 mm). 0xFFFF (none beyond) where the model has no rated range.
HESAI_ALWAYS_INLINE inline std::uint32_t beyond_limit(const PacketInfo& info) noexcept {
  const std::uint32_t rated_mm = 1000u * rated_range_m(info.model);
  return rated_mm != 0 && info.dis_unit_mm != 0 ? rated_mm / info.dis_unit_mm : 0xFFFFu;
}

// Blockage markers, repeated dual returns and distances beyond the rated range, from the units
// themselves (UnitScan, decoder.h); `scan` was reset by the caller. The reference: the firmware
// builds run it; the hosted scans below (branch-free, AVX2) are tested against it
// (tests/kernels/test_scan.cpp).
//
// Its first pass, blockage markers and distances beyond the rated range, is also what the
// ARMv7E-M loops leave to C for a packet that sets Q (scan_rare_units).
template <std::size_t kUnitBytes>
HESAI_ALWAYS_INLINE inline void scan_markers_and_range(const kernels::BlockRef* blocks, std::size_t block_count,
                                                       std::size_t unit_count, const PacketInfo& info,
                                                       std::uint16_t min_distance, UnitScan& scan,
                                                       std::uint32_t& blockage, std::uint32_t& beyond) noexcept {
  const std::uint32_t limit = beyond_limit(info);
  const bool markers = min_distance > 1;  // distance 1 is a marker only where it is not a point
  for (std::size_t b = 0; b < block_count; ++b) {
    const std::uint8_t* u = blocks[b].units;
    for (std::size_t j = 0; j < unit_count; ++j, u += kUnitBytes) {
      const std::uint32_t distance = load_le16(u);
      beyond += distance > limit ? 1u : 0u;
      if (markers && distance == 1) {
        ++blockage;
        const std::uint8_t ch = blocks[b].channel_of != nullptr ? blocks[b].channel_of[j] : static_cast<std::uint8_t>(j);
        ++scan.blockage_by_channel[ch % kMaxChannels];
      }
    }
  }
}

template <std::size_t kUnitBytes>
HESAI_NOINLINE_FOR_SIZE void scan_units(const kernels::BlockRef* blocks, std::size_t block_count, std::size_t unit_count,
                                        const PacketInfo& info, std::uint16_t min_distance, UnitScan& scan) noexcept {
  std::uint32_t blockage = 0, beyond = 0, duplicates = 0;
  scan_markers_and_range<kUnitBytes>(blocks, block_count, unit_count, info, min_distance, scan, blockage, beyond);
  if (info.returns == 2) {  // blocks 2i and 2i + 1 are the two returns of a firing
    for (std::size_t b = 0; b + 1 < block_count; b += 2) {
      const std::uint8_t* u0 = blocks[b].units;
      const std::uint8_t* u1 = blocks[b + 1].units;
      for (std::size_t j = 0; j < unit_count; ++j, u0 += kUnitBytes, u1 += kUnitBytes) {
        const std::uint16_t d0 = load_le16(u0);
        if (d0 >= min_distance && d0 == load_le16(u1) && u0[2] == u1[2]) {
          ++duplicates;
          const std::uint8_t ch = blocks[b + 1].channel_of != nullptr ? blocks[b + 1].channel_of[j] : static_cast<std::uint8_t>(j);
          if (b / 2 < kMaxDualFirings) scan.repeated[b / 2][(ch % kMaxChannels) / 8] |= static_cast<std::uint8_t>(1u << (ch % 8));
        }
      }
    }
  }
  scan.blockage_units = static_cast<std::uint16_t>(blockage);
  scan.beyond_rated_range = static_cast<std::uint16_t>(beyond);
  scan.duplicate_returns = static_cast<std::uint16_t>(duplicates);
}

#if defined(HESAI_KERNELS_ARMV7M)
// scan_units' blockage markers and distances beyond the rated range, for the assembly loops'
// packets that set Q (SensorBase::emit_blocks_armv7m), which count the repeated returns themselves.
template <std::size_t kUnitBytes>
HESAI_NOINLINE_FOR_SIZE void scan_rare_units(const kernels::BlockRef* blocks, std::size_t block_count, std::size_t unit_count,
                                             const PacketInfo& info, std::uint16_t min_distance, UnitScan& scan) noexcept {
  std::uint32_t blockage = 0, beyond = 0;
  scan_markers_and_range<kUnitBytes>(blocks, block_count, unit_count, info, min_distance, scan, blockage, beyond);
  scan.blockage_units = static_cast<std::uint16_t>(blockage);
  scan.beyond_rated_range = static_cast<std::uint16_t>(beyond);
}
#endif

#if defined(HESAI_KERNELS_ARMV7M)
// emit_blocks_armv7m's Points with the unit scan (the _scan and _repeat loops, armv7m_loops.h), a
// function of its own so that the decode without a scan keeps its registers. `k` holds the
// packet's constants; dir_cos: each firing loop's table. The loops that check for blockage markers
// (an SSAT a unit) serve the models whose smallest kept distance is above 1 (the QT128C2X's 2):
// no model has them with 3-byte units (emit_blocks scans such units in C); those that check for
// neither markers nor a rated range (the PandarQT64 and XT) run their first returns by the plain
// loops.
template <std::size_t kUnitBytes>
HESAI_NOINLINE_FOR_SIZE void emit_points_scanned_armv7m(kernels::ArmPointsBlock& k, const float* const dir_cos[2],
                                                        const kernels::BlockRef* blocks, std::size_t block_count,
                                                        std::size_t unit_count, std::uint16_t min_distance,
                                                        const PacketInfo& info, DecodeOutput& out) noexcept {
  UnitScan& scan = *out.scan;
  const std::uint32_t limit = beyond_limit(info);
  const bool checks = kUnitBytes == 3 || min_distance > 1 || limit != 0xFFFFu;  // else the u4 loops
  const bool dual = info.returns == 2;
  const float* const sin_el = k.sin_el;
  const auto steps_left = static_cast<std::uint32_t>(unit_count / 2 - 1) << 8;
  std::uint32_t duplicates = 0, return_index = 0;
  SinCosF ab{};
  std::uint32_t last_azimuth = 0x10000;
  k.limit_bias = 0x7FFFFFFFu - limit;
  kernels::clear_saturation();
  for (std::size_t b = 0; b < block_count;
       ++b, return_index = static_cast<std::uint32_t>(kernels::next_return_index(return_index, info.returns))) {
    const kernels::BlockRef& r = blocks[b];
    if (info.block_azimuth[b] != last_azimuth) ab = sin_cos_centideg(info.block_azimuth[b]);
    last_azimuth = info.block_azimuth[b];
    const auto block_time = static_cast<std::uint64_t>(info.time_ns + r.offset_ns);
    const float* const table = dir_cos[r.loop];
    const std::uint32_t return_tag = return_index << 16;
    k.units = r.units, k.dir_cos = table;
    k.tag = 1u << 8 | return_tag;
    k.block_and_steps = static_cast<std::uint32_t>(b) | steps_left;
    k.sin_a = ab.sin, k.cos_a = ab.cos, k.block_deg = static_cast<float>(info.block_azimuth[b]) * 0.01f;
    k.block_time_lo = static_cast<std::uint32_t>(block_time), k.block_time_hi = static_cast<std::uint32_t>(block_time >> 32);
    if (!dual || return_index == 0) {
      k.out = kUnitBytes == 3 ? (r.loop == 0 ? hesai_armv7m_points_scan_u3_l0(&k) : hesai_armv7m_points_scan_u3_l1(&k))
              : checks        ? (r.loop == 0 ? hesai_armv7m_points_scan_u4m_l0(&k) : hesai_armv7m_points_scan_u4m_l1(&k))
                              : (r.loop == 0 ? hesai_armv7m_points_u4_l0(&k) : hesai_armv7m_points_u4_l1(&k));
      continue;
    }
    // The second return of a firing (blocks 2f and 2f + 1): compared with the first unit by unit,
    // 32 units (one word of the repeated bits) a call.
    k.first_offset = static_cast<std::int32_t>(blocks[b - 1].units - r.units) - static_cast<std::int32_t>(kUnitBytes);
    std::uint8_t* const row = b / 2 < kMaxDualFirings ? scan.repeated[b / 2].data() : nullptr;
    for (std::size_t first = 0; first < unit_count; first += 32) {
      const std::size_t n = unit_count - first < 32 ? unit_count - first : 32;
      k.units = r.units + first * kUnitBytes, k.dir_cos = table + first, k.sin_el = sin_el + first;
      k.tag = static_cast<std::uint32_t>(first + 1) << 8 | return_tag;
      k.block_and_steps = static_cast<std::uint32_t>(b) | static_cast<std::uint32_t>(n / 2 - 1) << 8;
      const std::uint64_t o =
          kUnitBytes == 3 ? (r.loop == 0 ? hesai_armv7m_points_repeat_u3_l0(&k) : hesai_armv7m_points_repeat_u3_l1(&k))
          : checks || r.loop != 0 ? (r.loop == 0 ? hesai_armv7m_points_repeat_u4m_l0(&k) : hesai_armv7m_points_repeat_u4m_l1(&k))
                                  : hesai_armv7m_points_repeat_u4_l0(&k);
      k.out = reinterpret_cast<Point*>(static_cast<std::uintptr_t>(static_cast<std::uint32_t>(o)));
      const std::uint32_t repeated = static_cast<std::uint32_t>(o >> 32) >> (32 - n);
      duplicates += kernels::bit_count(repeated);
      // One unaligned word store (store_le32 is four byte stores here; ARMv7E-M is little-endian).
      if (row != nullptr) __builtin_memcpy(row + first / 8, &repeated, 4);
    }
    k.sin_el = sin_el;
  }
  out.count = static_cast<std::size_t>(k.out - out.points);
  scan.duplicate_returns = static_cast<std::uint16_t>(duplicates);
  // A unit beyond the rated range or a blockage marker set Q (rare: none in the bundled captures):
  // those counts exactly, by the reference's loop.
  if (kernels::saturated()) scan_rare_units<kUnitBytes>(blocks, block_count, unit_count, info, min_distance, scan);
}
#endif

// Where the units are scanned without a branch on them: every target but the microcontrollers
// (ARM M profile), whose firmware images run the reference scan_units alone (a short pipeline,
// and flash and instruction budgets: docs/FIRMWARE.md).
#if !(defined(__ARM_ARCH_PROFILE) && __ARM_ARCH_PROFILE == 'M')
#define HESAI_SCAN_BRANCH_FREE 1
#else
#define HESAI_SCAN_BRANCH_FREE 0
#endif

#if HESAI_SCAN_BRANCH_FREE
// scan_units without a branch on the units (their distances and reflectivities: blockage markers,
// empty and repeated returns come in no order a predictor learns): every test evaluated in full,
// the counts advanced by 0 or 1, the blockage counter and the repeated bit written for every unit.
template <std::size_t kUnitBytes>
HESAI_ALWAYS_INLINE inline void scan_units_branch_free(const kernels::BlockRef* blocks, std::size_t block_count,
                                                       std::size_t unit_count, const PacketInfo& info,
                                                       std::uint16_t min_distance, UnitScan& scan) noexcept {
  const std::uint32_t limit = beyond_limit(info);
  const bool markers = min_distance > 1;  // distance 1 is a marker only where it is not a point
  std::uint32_t blockage = 0, beyond = 0, duplicates = 0;
  for (std::size_t b = 0; b < block_count; ++b) {
    const std::uint8_t* u = blocks[b].units;
    const std::uint8_t* const map = blocks[b].channel_of;
    if (!markers) {  // the same for every block of the packet
      for (std::size_t j = 0; j < unit_count; ++j, u += kUnitBytes) beyond += load_le16(u) > limit;
      continue;
    }
    for (std::size_t j = 0; j < unit_count; ++j, u += kUnitBytes) {
      const std::uint32_t distance = load_le16(u);
      beyond += distance > limit;
      const std::uint32_t marker = distance == 1;
      blockage += marker;
      std::uint8_t& count = scan.blockage_by_channel[(map != nullptr ? map[j] : j) % kMaxChannels];
      count = static_cast<std::uint8_t>(count + marker);
    }
  }
  if (info.returns == 2) {  // blocks 2i and 2i + 1 are the two returns of a firing
    std::uint8_t spare[kMaxChannels / 8];  // the bits of firings beyond kMaxDualFirings, dropped
    for (std::size_t b = 0; b + 1 < block_count; b += 2) {
      const std::uint8_t* u0 = blocks[b].units;
      const std::uint8_t* u1 = blocks[b + 1].units;
      const std::uint8_t* const map = blocks[b + 1].channel_of;
      std::uint8_t* const row = b / 2 < kMaxDualFirings ? scan.repeated[b / 2].data() : spare;
      for (std::size_t j = 0; j < unit_count; ++j, u0 += kUnitBytes, u1 += kUnitBytes) {
        const std::uint32_t d0 = load_le16(u0);
        const std::uint32_t repeated = static_cast<std::uint32_t>(d0 >= min_distance) &
                                       static_cast<std::uint32_t>(d0 == load_le16(u1)) &
                                       static_cast<std::uint32_t>(u0[2] == u1[2]);
        duplicates += repeated;
        const std::size_t ch = (map != nullptr ? map[j] : j) % kMaxChannels;
        row[ch / 8] = static_cast<std::uint8_t>(row[ch / 8] | repeated << (ch % 8));
      }
    }
  }
  scan.blockage_units = static_cast<std::uint16_t>(blockage);
  scan.beyond_rated_range = static_cast<std::uint16_t>(beyond);
  scan.duplicate_returns = static_cast<std::uint16_t>(duplicates);
}
#endif

// The packet's unit scan, by the fastest scan here: on x86-64 the AVX2 scan where `path` runs
// vector code and the units need no channel map, else the branch-free loop; on the
// microcontrollers the reference loop.
template <std::size_t kUnitBytes>
HESAI_ALWAYS_INLINE inline void scan_packet(const kernels::BlockRef* blocks, std::size_t block_count,
                                            std::size_t unit_count, const PacketInfo& info,
                                            std::uint16_t min_distance, DecodePath path, UnitScan& scan) noexcept {
#if HESAI_SCAN_BRANCH_FREE
#if HESAI_KERNEL_COUNTERS
  if (kernels::reference_scan) return scan_units<kUnitBytes>(blocks, block_count, unit_count, info, min_distance, scan);
#endif
#if defined(HESAI_KERNELS_X86)
  const kernels::VectorIsa isa = kernels::vector_isa(path);
  if (isa != kernels::VectorIsa::none && !has_channel_map(blocks, block_count)) {
    kernels::ScanConstants k;
    k.block = blocks, k.blocks = block_count, k.units = unit_count, k.unit_bytes = kUnitBytes;
    k.limit = beyond_limit(info), k.min_distance = min_distance, k.markers = min_distance > 1, k.dual = info.returns == 2;
    kernels::ScanOutput o;
    o.blockage = o.beyond = o.duplicates = 0;
    o.blockage_by_channel = scan.blockage_by_channel.data();
    for (std::size_t f = 0; f < kernels::kMaxBlocks / 2; ++f) o.repeated[f] = f < kMaxDualFirings ? scan.repeated[f].data() : nullptr;
    if (kernels::scan_vector(k, isa, o)) {
      scan.blockage_units = static_cast<std::uint16_t>(o.blockage);
      scan.beyond_rated_range = static_cast<std::uint16_t>(o.beyond);
      scan.duplicate_returns = static_cast<std::uint16_t>(o.duplicates);
      return;
    }
  }
#else
  (void)path;
#endif
  scan_units_branch_free<kUnitBytes>(blocks, block_count, unit_count, info, min_distance, scan);
#else
  (void)path;
  scan_units<kUnitBytes>(blocks, block_count, unit_count, info, min_distance, scan);
#endif
}

// Optimising for size (-Os, the firmware builds), every sensor calls one shared copy per unit
// size: inlined into each sensor's block walk it took 0.8 KB more flash on the Cortex-M0+.
// Optimising for speed it is inlined, where the constant channel count and the absent map of the
// Pandars make a shorter loop (8% fewer instructions per Pandar64 packet under callgrind).
//
// Points or columns: the whole packet by the vector code in one call where there is one (and the
// units need no channel map), otherwise block by block by the scalar loops above. Every unit's
// point is written at index n and kept (n advanced) only when its distance is valid: no branch to
// mispredict. n <= the units before this one, so the writes stay below blocks x channels =
// max_points(d.model()), the capacity decode() checked.
template <std::size_t kUnitBytes>
HESAI_NOINLINE_FOR_SIZE void SensorBase::emit_blocks(const Decoder& d, const kernels::BlockRef* blocks,
                                                     std::size_t block_count, std::size_t unit_count,
                                                     const PacketInfo& info, DecodeOutput& out) noexcept {
  const Decoder::Geometry& geo_ = d.geo_;
  const Decoder::SpinCache& spin_ = d.spin_;
  // The beam cache at the packet's spin rate, for the firing loops its blocks use.
  const std::uint16_t rpm = d.firetime_correction_ ? info.motor_rpm : 0;
  if (rpm != spin_.rpm || spin_.stale_loops != 0) {
    unsigned loops = 0;
    for (std::size_t b = 0; b < block_count; ++b) loops |= 1u << blocks[b].loop;
    d.update_spin(rpm, loops, out.path);
  }
  const float unit_m = static_cast<float>(info.dis_unit_mm) * 0.001f;
  const std::uint16_t min_distance = sensor_of(d.model_)->min_distance;
  // The units' own pass, which leaves the blocks to make points of: none for Decoder::survey(),
  // whose pass scans the units too. Where vector or assembly code follows, no block left is a
  // return (and the walk's constant block count stays a constant below); elsewhere the scalar
  // loop runs no block, which takes less flash than the return (the Cortex-M0+: 4 bytes, not 20).
  if (out.units.into != nullptr) {
    const std::size_t left = out.units.run(blocks, block_count, unit_count, kUnitBytes, info, out.units.into);
#if defined(HESAI_KERNELS_VECTOR) || defined(HESAI_KERNELS_ARMV7M)
    if (left == 0) return;
#else
    block_count = left;
#endif
  }
#if defined(HESAI_KERNELS_ARMV7M)
  // The assembly loops; as Points, with the unit scan folded into them (the units read once).
  if (kernels::vector_isa(out.path) == kernels::VectorIsa::armv7m && unit_count % 2 == 0 && unit_count >= 2 &&
      unit_count <= 256 && !has_channel_map(blocks, block_count)) {
    // Columns, and 3-byte units with blockage markers (no such model): the scan in C.
    if (out.scan != nullptr && (out.points == nullptr || (kUnitBytes == 3 && min_distance > 1))) {
      scan_packet<kUnitBytes>(blocks, block_count, unit_count, info, min_distance, out.path, *out.scan);
      out.scan = nullptr;
    }
    emit_blocks_armv7m<kUnitBytes>(d, blocks, block_count, unit_count, unit_m, min_distance, info, out);
    return;
  }
#endif
  if (out.scan != nullptr) scan_packet<kUnitBytes>(blocks, block_count, unit_count, info, min_distance, out.path, *out.scan);
#if defined(HESAI_KERNELS_VECTOR)
  const kernels::VectorIsa isa = kernels::vector_isa(out.path);  // none for DecodePath::portable
  if (isa != kernels::VectorIsa::none && block_count <= kernels::kMaxBlocks) {
    kernels::PacketConstants k;
    k.blocks = block_count;
    k.units = unit_count;
    k.unit_bytes = kUnitBytes;
    k.unit_m = unit_m;
    k.min_distance = min_distance;
    k.time_ns = info.time_ns;
    k.sin_el = geo_.sin_el.data();
    k.elevation_deg = geo_.elevation_deg.data();
    for (std::size_t loop = 0; loop < 2; ++loop) {
      k.dir_cos[loop] = spin_.loop[loop].dir_cos.data();
      k.dir_sin[loop] = spin_.loop[loop].dir_sin.data();
      k.azimuth_deg[loop] = spin_.loop[loop].azimuth_deg.data();
      k.fire_ns[loop] = geo_.fire_ns[loop].data();
    }
    k.block_azimuth = info.block_azimuth.data();
    k.block = blocks;
    k.returns = info.returns;
    if (!has_channel_map(blocks, block_count) && (out.points != nullptr ? kernels::points_vector(k, isa, out.points, out.count)
                                          : kernels::columns_vector(k, isa, out.columns, out.count)))
      return;
  }
#endif
  for (std::size_t b = 0; b < block_count; ++b) {
    const kernels::BlockRef& r = blocks[b];
    const std::uint16_t block_azimuth = info.block_azimuth[b];
    const SinCosF ab = sin_cos_centideg(block_azimuth);
    kernels::BlockConstants k;
    k.sin_a = ab.sin;
    k.cos_a = ab.cos;
    k.unit_m = unit_m;
    k.min_distance = min_distance;
    k.return_index = kernels::return_index(info.returns, b);
    k.offset_ns = r.offset_ns;
    k.dir_cos = spin_.loop[r.loop].dir_cos.data();
    k.dir_sin = spin_.loop[r.loop].dir_sin.data();
    k.sin_el = geo_.sin_el.data();
    k.fire_ns = geo_.fire_ns[r.loop].data();
    if (out.points == nullptr) {
      out.count = kernels::write_columns<kUnitBytes>(k, r.units, unit_count, r.channel_of, out.columns, out.count);
      continue;
    }
    // The Points' own fields.
    k.block_deg = static_cast<float>(block_azimuth) * 0.01f;
    k.block_time_ns = info.time_ns + r.offset_ns;
    k.block = static_cast<std::uint8_t>(b);
    k.azimuth_deg = spin_.loop[r.loop].azimuth_deg.data();
    k.elevation_deg = geo_.elevation_deg.data();
    out.count = kernels::write_points<kUnitBytes>(k, r.units, unit_count, r.channel_of, out.points, out.count);
  }
}

#if defined(HESAI_KERNELS_ARMV7M)
// The same by the ARMv7E-M assembly loops (kernels/armv7m_loops.h), with emit_blocks' distance unit
// and smallest distance, one call a block; the block
// record is filled once and only its per-block fields changed, and a block at the azimuth of the
// one before it (the returns of one firing) reuses its sine and cosine.
template <std::size_t kUnitBytes>
HESAI_ALWAYS_INLINE inline void SensorBase::emit_blocks_armv7m(const Decoder& d, const kernels::BlockRef* blocks,
                                                               std::size_t block_count, std::size_t unit_count,
                                                               float unit_m, std::uint16_t min_distance,
                                                               const PacketInfo& info, DecodeOutput& out) noexcept {
  using Geometry = Decoder::Geometry;
  using Beams = Decoder::SpinCache::Beams;
  static_assert(offsetof(Geometry, elevation_deg) == offsetof(Geometry, sin_el) + kernels::kArmTableBytes &&
                    offsetof(Geometry, fire_ns) == offsetof(Geometry, sin_el) + 2 * kernels::kArmTableBytes &&
                    sizeof(Geometry::fire_ns[0]) == kernels::kArmTableBytes &&
                    offsetof(Beams, dir_sin) == offsetof(Beams, dir_cos) + kernels::kArmTableBytes &&
                    offsetof(Beams, azimuth_deg) == offsetof(Beams, dir_cos) + 2 * kernels::kArmTableBytes,
                "the offsets at which armv7m_loops.cpp reaches the tables");
  static_assert(kUnitBytes == 3 || kUnitBytes == 4, "3- or 4-byte units");
  const Geometry& geo = d.geo_;
  const Decoder::SpinCache& spin = d.spin_;
  HESAI_ASSERT(min_distance >= 1);
  const std::uint32_t keep_bias = (0x10000u - min_distance) << 16;
  const auto steps_left = static_cast<std::uint32_t>(unit_count / 2 - 1) << 8;  // two units a step
  SinCosF ab{};
  std::uint32_t last_azimuth = 0x10000;  // none yet: above any block azimuth
  // The records assigned field by field: a braced initialiser made GCC zero them first by a memset
  // call (picolibc's, a byte at a time: 261 instructions a packet).
  if (out.points == nullptr) {
    HESAI_COUNT_KERNEL(armv7m_columns);
    const PointColumns& c = out.columns;
    kernels::ArmColumnsBlock k;
    k.n = out.count, k.x = c.x, k.y = c.y, k.z = c.z, k.time_ns = c.time_ns, k.intensity = c.intensity;
    k.channel_column = c.channel, k.return_column = c.return_index;
    k.sin_el = geo.sin_el.data(), k.keep_bias = keep_bias, k.channel_and_steps = 1 | steps_left, k.unit_m = unit_m;
    for (std::size_t b = 0; b < block_count; ++b) {
      const kernels::BlockRef& r = blocks[b];
      if (info.block_azimuth[b] != last_azimuth) ab = sin_cos_centideg(info.block_azimuth[b]);
      last_azimuth = info.block_azimuth[b];
      k.units = r.units, k.dir_cos = spin.loop[r.loop].dir_cos.data(), k.return_index = kernels::return_index(info.returns, b);
      k.sin_a = ab.sin, k.cos_a = ab.cos, k.offset_ns = r.offset_ns;
      k.n = kUnitBytes == 3 ? (r.loop == 0 ? hesai_armv7m_columns_u3_l0(&k) : hesai_armv7m_columns_u3_l1(&k))
                            : (r.loop == 0 ? hesai_armv7m_columns_u4_l0(&k) : hesai_armv7m_columns_u4_l1(&k));
    }
    out.count = k.n;
    return;
  }
  HESAI_COUNT_KERNEL(armv7m_points);
  kernels::ArmPointsBlock k;
  k.out = out.points + out.count, k.sin_el = geo.sin_el.data(), k.keep_bias = keep_bias, k.unit_m = unit_m;
  k.full_turn = 360.0f;
  if (out.scan == nullptr) {
    for (std::size_t b = 0; b < block_count; ++b) {
      const kernels::BlockRef& r = blocks[b];
      if (info.block_azimuth[b] != last_azimuth) ab = sin_cos_centideg(info.block_azimuth[b]);
      last_azimuth = info.block_azimuth[b];
      const auto block_time = static_cast<std::uint64_t>(info.time_ns + r.offset_ns);
      k.units = r.units, k.dir_cos = spin.loop[r.loop].dir_cos.data();
      k.tag = 1u << 8 | std::uint32_t{kernels::return_index(info.returns, b)} << 16;
      k.block_and_steps = static_cast<std::uint32_t>(b) | steps_left;
      k.sin_a = ab.sin, k.cos_a = ab.cos, k.block_deg = static_cast<float>(info.block_azimuth[b]) * 0.01f;
      k.block_time_lo = static_cast<std::uint32_t>(block_time), k.block_time_hi = static_cast<std::uint32_t>(block_time >> 32);
      k.out = kUnitBytes == 3 ? (r.loop == 0 ? hesai_armv7m_points_u3_l0(&k) : hesai_armv7m_points_u3_l1(&k))
                              : (r.loop == 0 ? hesai_armv7m_points_u4_l0(&k) : hesai_armv7m_points_u4_l1(&k));
    }
    out.count = static_cast<std::size_t>(k.out - out.points);
    return;
  }
  const float* const dir_cos[2] = {spin.loop[0].dir_cos.data(), spin.loop[1].dir_cos.data()};
  emit_points_scanned_armv7m<kUnitBytes>(k, dir_cos, blocks, block_count, unit_count, min_distance, info, out);
}
#endif

}  // namespace hesai
