// Points (hesai::Point, 40 bytes each) by NEON on AArch64: a packet's blocks eight units a step,
// as two vectors of four (neon_units.h). Empty on other targets.
#include "vector_kernels.h"

#if defined(HESAI_KERNELS_NEON)

#include <cstddef>

#include "kernel_counters.h"
#include "neon_units.h"

namespace hesai::kernels {

// The 8 bytes of a Point from `intensity` on: intensity, channel, return index, confidence, block,
// and the 3 bytes of padding (written as 0).
static_assert(offsetof(Point, y) == 4 && offsetof(Point, z) == 8 && offsetof(Point, distance_m) == 12 &&
              offsetof(Point, azimuth_deg) == 16 && offsetof(Point, elevation_deg) == 20 &&
              offsetof(Point, time_ns) == 24 && offsetof(Point, intensity) == 32 && offsetof(Point, channel) == 33 &&
              offsetof(Point, return_index) == 34 && offsetof(Point, confidence) == 35 && offsetof(Point, block) == 36 &&
              sizeof(Point) == 40, "points_vector (NEON) writes this layout");

// Points, eight units a step as columns_vector reads them (EightUnits); each point's 40 bytes in
// three stores (x, y, z, distance; azimuth, elevation, time; the bytes) from the four lanes
// transposed. Every unit's point is written at n, kept (n advanced) when its distance is valid, as
// the scalar loop.
bool points_vector(const PacketConstants& k, VectorIsa isa, Point* out, std::size_t& count) noexcept {
  if (!neon_fits(k, isa)) return false;
  HESAI_COUNT_KERNEL(neon_points);
  EightUnits eight_units(k);
  const std::size_t blocks = k.blocks, units = k.units;
  const float32x4_t full_turn = vdupq_n_f32(360.0f);
  const uint8x8_t eight = vdup_n_u8(8);
  const float* const elevation_deg = k.elevation_deg;  // in registers: k may be aliased by the stores
  std::uint8_t* const base = reinterpret_cast<std::uint8_t*>(out);
  const BlockSinCos sc = block_sin_cos(k);
  std::size_t n = count;
  for (std::size_t block = 0; block < blocks; ++block) {
    const BlockRef& kb = k.block[block];
    eight_units.start(kb, sc.sin[block], sc.cos[block]);
    // The Points' own block values, as SensorBase::emit_blocks computes them for the scalar loop.
    const float32x4_t block_deg = vdupq_n_f32(static_cast<float>(k.block_azimuth[block]) * 0.01f);
    const int64x2_t block_time = vdupq_n_s64(k.time_ns + kb.offset_ns);
    const uint8x8_t ret = vdup_n_u8(return_index(k.returns, block));
    const uint32x4_t block_word = vdupq_n_u32(static_cast<std::uint32_t>(block));  // the block byte, then three zero bytes
    const float* const azimuth_deg = k.azimuth_deg[kb.loop];
    const std::int32_t* const fire_ns = k.fire_ns[kb.loop];
    uint8x8_t channel = first_channels();
    for (std::size_t j = 0; j < units; j += 8) {
      const Eight e = eight_units.at(j);
      // The bytes of point i: 32-bit lane i % 4 of bytes_of[i / 4] (intensity, channel, return,
      // confidence), then the block word.
      const uint8x16_t ic = vcombine_u8(vzip1_u8(e.intensity, channel), vzip2_u8(e.intensity, channel));
      const uint8x16_t rc = vcombine_u8(vzip1_u8(ret, e.confidence), vzip2_u8(ret, e.confidence));
      const uint32x4_t bytes_of[2] = {vreinterpretq_u32_u16(vzip1q_u16(vreinterpretq_u16_u8(ic), vreinterpretq_u16_u8(rc))),
                                      vreinterpretq_u32_u16(vzip2q_u16(vreinterpretq_u16_u8(ic), vreinterpretq_u16_u8(rc)))};
      channel = vadd_u8(channel, eight);
      for (std::size_t h = 0; h < 2; ++h) {
        const std::size_t c = j + 4 * h;
        // The scalar loop's operations in its order (scalar_loops.h, write_points).
        const Four f = eight_units.half(e, j, h);
        const float32x4_t sum = vaddq_f32(block_deg, vld1q_f32(azimuth_deg + c));
        const float32x4_t az = vbslq_f32(vcgeq_f32(sum, full_turn), vsubq_f32(sum, full_turn), sum);
        const float32x4_t el = vld1q_f32(elevation_deg + c);
        const int32x4_t fire = vld1q_s32(fire_ns + c);
        const int64x2_t t[2] = {vaddq_s64(block_time, vmovl_s32(vget_low_s32(fire))),
                                vaddq_s64(block_time, vmovl_high_s32(fire))};
        // x, y, z, distance of point i: xyzr[i]; azimuth, elevation and time: aet[i].
        const float64x2_t xy[2] = {vreinterpretq_f64_f32(vzip1q_f32(f.x, f.y)), vreinterpretq_f64_f32(vzip2q_f32(f.x, f.y))};
        const float64x2_t zr[2] = {vreinterpretq_f64_f32(vzip1q_f32(f.z, f.r)), vreinterpretq_f64_f32(vzip2q_f32(f.z, f.r))};
        const float64x2_t xyzr[4] = {vzip1q_f64(xy[0], zr[0]), vzip2q_f64(xy[0], zr[0]), vzip1q_f64(xy[1], zr[1]),
                                     vzip2q_f64(xy[1], zr[1])};
        const int64x2_t ae[2] = {vreinterpretq_s64_f32(vzip1q_f32(az, el)), vreinterpretq_s64_f32(vzip2q_f32(az, el))};
        const int64x2_t aet[4] = {vzip1q_s64(ae[0], t[0]), vzip2q_s64(ae[0], t[0]), vzip1q_s64(ae[1], t[1]),
                                  vzip2q_s64(ae[1], t[1])};
        const uint32x4_t bytes[2] = {vzip1q_u32(bytes_of[h], block_word), vzip2q_u32(bytes_of[h], block_word)};
        const std::uint32_t keep_bits[4] = {vgetq_lane_u32(e.kept[h], 0), vgetq_lane_u32(e.kept[h], 1),
                                            vgetq_lane_u32(e.kept[h], 2), vgetq_lane_u32(e.kept[h], 3)};
        for (unsigned i = 0; i < 4; ++i) {
          std::uint8_t* const o = base + n * sizeof(Point);
          vst1q_u8(o, vreinterpretq_u8_f64(xyzr[i]));
          vst1q_u8(o + 16, vreinterpretq_u8_s64(aet[i]));
          const uint8x16_t two = vreinterpretq_u8_u32(bytes[i / 2]);
          vst1_u8(o + 32, i % 2 == 0 ? vget_low_u8(two) : vget_high_u8(two));
          n += keep_bits[i] & 1u;
        }
      }
    }
  }
  count = n;
  return true;
}

}  // namespace hesai::kernels

#endif  // HESAI_KERNELS_NEON
