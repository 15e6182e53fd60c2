// Columns (PointColumns) by NEON on AArch64: a packet's blocks eight units a step, as two vectors
// of four (neon_units.h). Empty on other targets.
#include "vector_kernels.h"

#if defined(HESAI_KERNELS_NEON)

#include "kernel_counters.h"
#include "neon_units.h"

namespace hesai::kernels {

bool columns_vector(const PacketConstants& k, VectorIsa isa, const PointColumns out, std::size_t& count) noexcept {
  if (!neon_fits(k, isa)) return false;
  HESAI_COUNT_KERNEL(neon_columns);
  EightUnits eight_units(k);
  const std::size_t blocks = k.blocks, units = k.units;
  const uint32_t lane_bit_values[4] = {1, 2, 4, 8};
  const uint32x4_t lane_bits = vld1q_u32(lane_bit_values);
  const uint8x8_t eight = vdup_n_u8(8);
  const BlockSinCos sc = block_sin_cos(k);
  std::size_t n = count;
  for (std::size_t block = 0; block < blocks; ++block) {
    const BlockRef& kb = k.block[block];
    eight_units.start(kb, sc.sin[block], sc.cos[block]);
    const int32x4_t offset = vdupq_n_s32(kb.offset_ns);
    const uint8x8_t ret = vdup_n_u8(return_index(k.returns, block));
    const std::int32_t* const fire_ns = k.fire_ns[kb.loop];
    uint8x8_t channel = first_channels();
    for (std::size_t j = 0; j < units; j += 8) {
      const Eight e = eight_units.at(j);
      unsigned keep[2];
      for (std::size_t h = 0; h < 2; ++h) keep[h] = vaddvq_u32(vandq_u32(e.kept[h], lane_bits));
      // The bytes of all eight at once, packed by the 8-lane table.
      const uint8x8_t order = vcreate_u8(kCompress[keep[0] | keep[1] << 4]);
      vst1_u8(out.intensity + n, vtbl1_u8(e.intensity, order));
      vst1_u8(out.channel + n, vtbl1_u8(channel, order));
      vst1_u8(out.return_index + n, ret);
      channel = vadd_u8(channel, eight);
      // The floats four at a time (EightUnits::half).
      for (std::size_t h = 0; h < 2; ++h) {
        const Four f = eight_units.half(e, j, h);
        const int32x4_t t = vaddq_s32(offset, vld1q_s32(fire_ns + j + 4 * h));
        store_packed(reinterpret_cast<std::uint8_t*>(out.x + n), vreinterpretq_u8_f32(f.x), keep[h]);
        store_packed(reinterpret_cast<std::uint8_t*>(out.y + n), vreinterpretq_u8_f32(f.y), keep[h]);
        store_packed(reinterpret_cast<std::uint8_t*>(out.z + n), vreinterpretq_u8_f32(f.z), keep[h]);
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
