// Columns (PointColumns) by NEON on AArch64: a packet's blocks eight units a step, as two vectors
// of four. Empty on other targets.
#include "vector_kernels.h"

#if defined(HESAI_KERNELS_NEON)

#include "neon_units.h"

namespace hesai::kernels {

bool columns_vector(const PacketConstants& k, VectorIsa isa, const PointColumns out, std::size_t& count) noexcept {
  if (isa != VectorIsa::neon || k.units % 8 != 0) return false;
  const std::size_t wide = k.unit_bytes == 4 ? 1 : 0;
  const std::size_t unit_bytes = k.unit_bytes, second = kSecond[wide];
  const std::size_t blocks = k.blocks, units = k.units;
  const uint8x16_t lo_distance = load_shuffle(kShuffle[wide][0].distance);
  const uint8x16_t hi_distance = load_shuffle(kShuffle[wide][1].distance);
  const uint8x16_t lo_intensity = load_shuffle(kShuffle[wide][0].intensity);
  const uint8x16_t hi_intensity = load_shuffle(kShuffle[wide][1].intensity);
  const float32x4_t unit_m = vdupq_n_f32(k.unit_m);
  const uint32x4_t min_distance = vdupq_n_u32(k.min_distance);
  const uint32_t lane_bit_values[4] = {1, 2, 4, 8};
  const uint32x4_t lane_bits = vld1q_u32(lane_bit_values);
  const std::uint8_t first_channels[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  const uint8x8_t eight = vdup_n_u8(8);
  const float* const sin_el = k.sin_el;  // in registers: k may be aliased by the byte stores
  const BlockSinCos sc = block_sin_cos(k);
  std::size_t n = count;
  for (std::size_t block = 0; block < blocks; ++block) {
    const BlockRef& kb = k.block[block];
    const std::uint8_t* const block_units = kb.units;
    const float32x4_t sin_a = vdupq_n_f32(sc.sin[block]), cos_a = vdupq_n_f32(sc.cos[block]);
    const int32x4_t offset = vdupq_n_s32(kb.offset_ns);
    const uint8x8_t ret = vdup_n_u8(return_index(k.returns, block));
    const float* const dir_cos = k.dir_cos[kb.loop];
    const float* const dir_sin = k.dir_sin[kb.loop];
    const std::int32_t* const fire_ns = k.fire_ns[kb.loop];
    uint8x8_t channel = vld1_u8(first_channels);
    for (std::size_t j = 0; j < units; j += 8) {
      const std::uint8_t* p = block_units + j * unit_bytes;
      const uint8x16_t a = vld1q_u8(p);
      const uint8x16_t b = vld1q_u8(p + second);
      const uint32x4_t raw[2] = {vreinterpretq_u32_u8(vqtbl1q_u8(a, lo_distance)),
                                 vreinterpretq_u32_u8(vqtbl1q_u8(b, hi_distance))};
      const uint8x8_t intensity =
          vorr_u8(vget_low_u8(vqtbl1q_u8(a, lo_intensity)), vget_low_u8(vqtbl1q_u8(b, hi_intensity)));
      unsigned keep[2];
      for (std::size_t h = 0; h < 2; ++h) keep[h] = vaddvq_u32(vandq_u32(vcgeq_u32(raw[h], min_distance), lane_bits));
      // The bytes of all eight at once, packed by the 8-lane table.
      const uint8x8_t order = vcreate_u8(kCompress[keep[0] | keep[1] << 4]);
      vst1_u8(out.intensity + n, vtbl1_u8(intensity, order));
      vst1_u8(out.channel + n, vtbl1_u8(channel, order));
      vst1_u8(out.return_index + n, ret);
      channel = vadd_u8(channel, eight);
      // The floats four at a time: the scalar loop's operations in its order (scalar_loops.h,
      // unit_xyz), no fused multiply-add.
      for (std::size_t h = 0; h < 2; ++h) {
        const std::size_t c = j + 4 * h;
        const float32x4_t r = vmulq_f32(vcvtq_f32_u32(raw[h]), unit_m);
        const float32x4_t dc = vld1q_f32(dir_cos + c);
        const float32x4_t ds = vld1q_f32(dir_sin + c);
        const float32x4_t x = vmulq_f32(r, vaddq_f32(vmulq_f32(sin_a, dc), vmulq_f32(cos_a, ds)));
        const float32x4_t y = vmulq_f32(r, vsubq_f32(vmulq_f32(cos_a, dc), vmulq_f32(sin_a, ds)));
        const float32x4_t z = vmulq_f32(r, vld1q_f32(sin_el + c));
        const int32x4_t t = vaddq_s32(offset, vld1q_s32(fire_ns + c));
        store_packed(reinterpret_cast<std::uint8_t*>(out.x + n), vreinterpretq_u8_f32(x), keep[h]);
        store_packed(reinterpret_cast<std::uint8_t*>(out.y + n), vreinterpretq_u8_f32(y), keep[h]);
        store_packed(reinterpret_cast<std::uint8_t*>(out.z + n), vreinterpretq_u8_f32(z), keep[h]);
        store_packed(reinterpret_cast<std::uint8_t*>(out.time_ns + n), vreinterpretq_u8_s32(t), keep[h]);
        n += static_cast<std::size_t>(__builtin_popcount(keep[h]));
      }
    }
  }
  count = n;
  return true;
}

}  // namespace hesai::kernels

#endif  // HESAI_KERNELS_NEON
