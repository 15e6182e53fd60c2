// Columns (PointColumns) by the x86-64 vector kernels: AVX-512, sixteen units a step, and AVX2,
// eight units a step (x86_units.h). Empty on other targets.
#include "vector_kernels.h"

#if defined(HESAI_KERNELS_X86)

#include "kernel_counters.h"
#include "x86_units.h"

namespace hesai::kernels {
namespace {

// `out` by value: stores through its byte columns may alias anything in memory but not a local.
HESAI_AVX2_TARGET void columns_avx2(const PacketConstants& k, const PointColumns out, std::size_t& count) noexcept {
  EightUnits eight_units(k);
  const BlockSinCos sc = block_sin_cos(k);
  const std::size_t blocks = k.blocks, units = k.units;
  std::size_t n = count;
  std::size_t return_of_block = 0;  // return_index(k.returns, b)
  for (std::size_t b = 0; b < blocks; ++b, return_of_block = next_return_index(return_of_block, k.returns)) {
    const BlockRef& kb = k.block[b];
    eight_units.start(kb, sc.sin[b], sc.cos[b]);
    const __m256i offset = _mm256_set1_epi32(kb.offset_ns);
    const std::int32_t* const fire_ns = k.fire_ns[kb.loop];
    const __m128i ret = _mm_set1_epi8(static_cast<char>(return_of_block));
    __m128i channel = first_channels();
    for (std::size_t j = 0; j < units; j += 8) {
      const Eight e = eight_units.at(j);
      const __m256i t = _mm256_add_epi32(offset, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(fire_ns + j)));
      // Keep the lanes with a valid distance, packed to the front.
      const __m128i order = _mm_cvtsi64_si128(static_cast<long long>(kCompress[e.keep]));
      const __m256i perm = _mm256_cvtepu8_epi32(order);
      _mm256_storeu_ps(out.x + n, _mm256_permutevar8x32_ps(e.x, perm));
      _mm256_storeu_ps(out.y + n, _mm256_permutevar8x32_ps(e.y, perm));
      _mm256_storeu_ps(out.z + n, _mm256_permutevar8x32_ps(e.z, perm));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.time_ns + n), _mm256_permutevar8x32_epi32(t, perm));
      _mm_storel_epi64(reinterpret_cast<__m128i*>(out.intensity + n), _mm_shuffle_epi8(e.intensity, order));
      _mm_storel_epi64(reinterpret_cast<__m128i*>(out.channel + n), _mm_shuffle_epi8(channel, order));
      _mm_storel_epi64(reinterpret_cast<__m128i*>(out.return_index + n), ret);
      channel = _mm_add_epi8(channel, _mm_set1_epi8(8));
      n += static_cast<std::size_t>(_mm_popcnt_u32(e.keep));
    }
  }
  count = n;
}

// The kept lanes packed to the front: one compression gives the permutation, which each column
// applies (a vpermd costs less than a vpcompressd).
template <std::size_t kUnitBytes>
HESAI_AVX512_TARGET void columns_avx512(const PacketConstants& k, const PointColumns out, std::size_t& count) noexcept {
  SixteenUnits<kUnitBytes> sixteen_units(k);
  const std::size_t blocks = k.blocks, units = k.units;
  const __m512i intensity = every_lane(kIntensity[kUnitBytes == 4]);
  const __m512i lane_index = lane_indices();
  const __m512i next_channels = _mm512_set1_epi32(16 << 8);
  const BlockSinCos sc = block_sin_cos_avx512(k);
  std::size_t n = count;
  std::size_t return_of_block = 0;  // return_index(k.returns, b)
  for (std::size_t b = 0; b < blocks; ++b, return_of_block = next_return_index(return_of_block, k.returns)) {
    const BlockRef& kb = k.block[b];
    sixteen_units.start(kb, sc.sin[b], sc.cos[b]);
    const __m512i offset = _mm512_set1_epi32(kb.offset_ns);
    const __m128i ret = _mm_set1_epi8(static_cast<char>(return_of_block));
    const std::int32_t* const fire_ns = k.fire_ns[kb.loop];
    // Channel j + 1 in byte 1 of lane j, beside the intensity in byte 0.
    __m512i channel = _mm512_slli_epi32(_mm512_add_epi32(lane_index, _mm512_set1_epi32(1)), 8);
    // A step of sixteen units (kFull) or the block's last, of fewer.
    const auto step = [&](std::size_t j, auto full) HESAI_AVX512_TARGET {
      constexpr bool kFull = decltype(full)::value;
      const Sixteen s = sixteen_units.template at<kFull>(j);
      const __m512i t = _mm512_add_epi32(offset, _mm512_maskz_loadu_epi32(s.lanes, fire_ns + j));
      const __m512i order = _mm512_maskz_compress_epi32(s.keep, lane_index);
      // Intensity and channel: one permutation for both.
      const __m512i ic = _mm512_permutexvar_epi32(order, _mm512_or_si512(_mm512_shuffle_epi8(s.bytes, intensity), channel));
      const __m512 x = _mm512_permutexvar_ps(order, s.x), y = _mm512_permutexvar_ps(order, s.y);
      const __m512 z = _mm512_permutexvar_ps(order, s.z);
      const __m512i time = _mm512_permutexvar_epi32(order, t);
      const __m128i intensities = _mm512_cvtepi32_epi8(ic), channels = _mm512_cvtepi32_epi8(_mm512_srli_epi32(ic, 8));
      const auto kept = static_cast<unsigned>(_mm_popcnt_u32(s.keep));
      if constexpr (kFull) {
        // Whole vectors: up to 15 entries past the new count, all below this step's units.
        _mm512_storeu_ps(out.x + n, x);
        _mm512_storeu_ps(out.y + n, y);
        _mm512_storeu_ps(out.z + n, z);
        _mm512_storeu_si512(out.time_ns + n, time);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out.intensity + n), intensities);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out.channel + n), channels);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out.return_index + n), ret);
      } else {
        // Only the kept: the rest of a vector could reach past max_points.
        const auto stored = static_cast<__mmask16>((1u << kept) - 1);
        _mm512_mask_storeu_ps(out.x + n, stored, x);
        _mm512_mask_storeu_ps(out.y + n, stored, y);
        _mm512_mask_storeu_ps(out.z + n, stored, z);
        _mm512_mask_storeu_epi32(out.time_ns + n, stored, time);
        _mm_mask_storeu_epi8(out.intensity + n, stored, intensities);
        _mm_mask_storeu_epi8(out.channel + n, stored, channels);
        _mm_mask_storeu_epi8(out.return_index + n, stored, ret);
      }
      channel = _mm512_add_epi32(channel, next_channels);
      n += kept;
    };
    std::size_t j = 0;
    for (; j + 16 <= units; j += 16) step(j, std::true_type{});
    if (j < units) step(j, std::false_type{});
  }
  count = n;
}

}  // namespace

bool columns_vector(const PacketConstants& k, VectorIsa isa, const PointColumns out, std::size_t& count) noexcept {
  switch (isa) {
    case VectorIsa::avx512:
      HESAI_COUNT_KERNEL(avx512_columns);
      if (k.unit_bytes == 4) columns_avx512<4>(k, out, count);
      else columns_avx512<3>(k, out, count);
      return true;
    case VectorIsa::avx2:
      if (k.units % 8 != 0) return false;
      HESAI_COUNT_KERNEL(avx2_columns);
      columns_avx2(k, out, count);
      return true;
    default: break;
  }
  return false;
}

}  // namespace hesai::kernels

#endif  // HESAI_KERNELS_X86
