// The scalar per-point loops, which every target has (internal to the core): one block's units
// to Points or to columns. SensorBase::emit_blocks (sensors/block_points.h) runs them block by
// block where no vector kernel takes the packet (Cortex-M, DecodePath::portable, customised QT128
// channels, block sizes a kernel declines).
// A unit is one channel's measurement; unit j is channel j, except in QT128 packets with
// customised channels, where the channel configuration maps it.
//
// x = r cos(e) sin(a), y = r cos(e) cos(a), z = r sin(e), with a = block azimuth + the channel's
// beam azimuth (offset + firing-time correction, cached per spin rate: beam_cache.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "../base/compiler.h"
#include "hesai/bytes.h"
#include "hesai/point.h"
#include "kernel_inputs.h"

namespace hesai {
namespace kernels {

// The units of one block with their channel: unit j is channel j, or channel_of[j] with a map.
// The loop exists twice, with a map (customised QT128 channels) and without, where one
// induction variable walks every array (an identity map, or a test per unit, cost 21-28% more
// instructions per packet under callgrind).
template <std::size_t kUnitBytes, typename F>
HESAI_ALWAYS_INLINE inline void for_each_unit(const std::uint8_t* units, std::size_t unit_count, const std::uint8_t* channel_of, F&& f) {
  if (channel_of != nullptr) {
    for (std::size_t j = 0; j < unit_count; ++j) f(units + j * kUnitBytes, std::size_t{channel_of[j]});
  } else {
    for (std::size_t j = 0; j < unit_count; ++j) f(units + j * kUnitBytes, j);
  }
}

// A unit's position: range r and its beam direction turned by the block azimuth (point azimuth
// a + b by the angle-sum identities; dir_cos, dir_sin carry cos(e)).
struct Xyz {
  float x, y, z;
};
HESAI_ALWAYS_INLINE inline Xyz unit_xyz(const BlockConstants& k, float r, std::size_t ch) noexcept {
  return {r * (k.sin_a * k.dir_cos[ch] + k.cos_a * k.dir_sin[ch]),
          r * (k.cos_a * k.dir_cos[ch] - k.sin_a * k.dir_sin[ch]), r * k.sin_el[ch]};
}

// raw >= min_distance (min_distance >= 1) as 1 or 0: raw + 0x10000 - min_distance carries into
// bit 16 exactly then. On ARMv7-M an add and an add with a shifted operand, where the comparison
// took a compare, an IT and a conditional add.
HESAI_ALWAYS_INLINE inline std::uint32_t keep_bias(std::uint16_t min_distance) noexcept {
  return 0x10000u - min_distance;
}
HESAI_ALWAYS_INLINE inline std::size_t keep(std::uint16_t raw, std::uint32_t bias) noexcept {
  return static_cast<std::size_t>((raw + bias) >> 16);
}

// The units of a block as columns at out[n...]; returns n advanced by the points kept. k and the columns by value: locals whose address does not escape, so that the stores
// through the byte columns (which may alias anything in memory) leave them in registers.
template <std::size_t kUnitBytes>
inline std::size_t write_columns(const BlockConstants k, const std::uint8_t* units, std::size_t unit_count,
                                 const std::uint8_t* channel_of, const PointColumns out, std::size_t n) noexcept {
  const std::uint32_t bias = keep_bias(k.min_distance);
  for_each_unit<kUnitBytes>(units, unit_count, channel_of, [&](const std::uint8_t* p, std::size_t ch) HESAI_ALWAYS_INLINE {
    const std::uint16_t raw = load_le16(p);
    const Xyz v = unit_xyz(k, static_cast<float>(raw) * k.unit_m, ch);
    out.x[n] = v.x;
    out.y[n] = v.y;
    out.z[n] = v.z;
    out.time_ns[n] = k.offset_ns + k.fire_ns[ch];
    out.intensity[n] = p[2];
    out.channel[n] = static_cast<std::uint8_t>(ch + 1);
    out.return_index[n] = k.return_index;
    n += keep(raw, bias);
  });
  return n;
}

static_assert(offsetof(Point, channel) == offsetof(Point, intensity) + 1 &&
                  offsetof(Point, return_index) == offsetof(Point, intensity) + 2 &&
                  offsetof(Point, confidence) == offsetof(Point, intensity) + 3,
              "write_points stores the four bytes as one word");

// Bytes 0-3 of v to p[0..3], byte 0 first: with GNU C++ on a little-endian target one word store
// (GCC does not merge store_le32's four byte stores, and -ffreestanding makes std::memcpy a call);
// not on ARMv6-M, where GCC copies the word a byte at a time with more instructions than store_le32.
HESAI_ALWAYS_INLINE inline void store_bytes4(std::uint8_t* p, std::uint32_t v) noexcept {
#if HESAI_GNU && defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ && !defined(__ARM_ARCH_6M__)
  __builtin_memcpy(p, &v, sizeof v);
#else
  store_le32(p, v);
#endif
}

// The same as Points (k by value for the same reason).
template <std::size_t kUnitBytes>
inline std::size_t write_points(const BlockConstants k, const std::uint8_t* units, std::size_t unit_count,
                                const std::uint8_t* channel_of, Point* const out, std::size_t n) noexcept {
  const std::uint32_t bias = keep_bias(k.min_distance);
  const std::uint32_t return_index = std::uint32_t{k.return_index} << 16;
  for_each_unit<kUnitBytes>(units, unit_count, channel_of, [&](const std::uint8_t* p, std::size_t ch) HESAI_ALWAYS_INLINE {
    const std::uint16_t raw = load_le16(p);
    const float r = static_cast<float>(raw) * k.unit_m;
    const Xyz v = unit_xyz(k, r, ch);
    Point& o = out[n];
    o.x = v.x;
    o.y = v.y;
    o.z = v.z;
    o.distance_m = r;
    // Both terms lie in [0, 360): one exact subtraction brings the sum into range.
    float az = k.block_deg + k.azimuth_deg[ch];
    if (az >= 360.0f) az -= 360.0f;
    o.azimuth_deg = az;
    o.elevation_deg = k.elevation_deg[ch];
    o.time_ns = k.block_time_ns + k.fire_ns[ch];
    // intensity, channel, return_index, confidence: one little-endian word (a single store on
    // ARMv7-M, where four byte stores took eight instructions with their operands).
    const std::uint32_t confidence = kUnitBytes == 4 ? std::uint32_t{p[3]} << 24 : 0u;
    // (Through the Point's own bytes, so that the four lie within the object the pointer points into.)
    store_bytes4(reinterpret_cast<std::uint8_t*>(&o) + offsetof(Point, intensity),
                 std::uint32_t{p[2]} | static_cast<std::uint32_t>(ch + 1) << 8 | return_index | confidence);
    o.block = k.block;
    n += keep(raw, bias);
  });
  return n;
}

}  // namespace kernels

}  // namespace hesai
