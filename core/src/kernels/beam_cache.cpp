#include "beam_cache.h"

#include "hesai/detail/math.h"
#include "kernel_counters.h"
#include "kernel_inputs.h"
#include "x86_units.h"

namespace hesai::kernels {

namespace {

// One firing loop of the per-spin-rate cache. Rebuilt on every change of spin rate, which real
// units make every few hundred packets and a stream may make on every packet: no branch per
// channel, so that the compiler vectorises it. lo_key and hi_key take the spread's order keys.
HESAI_ALWAYS_INLINE inline void spin_loop(const std::int32_t* fire_ns, const float* cos_el_cos_az,
                                          const float* cos_el_sin_az, const float* offset_deg, float* dir_cos,
                                          float* dir_sin, float* azimuth_deg, std::size_t channels, float omega,
                                          std::int32_t& lo_key, std::int32_t& hi_key) noexcept {
  constexpr float kRadToDeg = static_cast<float>(180.0 / kPi);
  std::int32_t lo = lo_key, hi = hi_key;  // locals: through the references the loop stays scalar
  for (std::size_t ch = 0; ch < channels; ++ch) {
    // Beam azimuth b = azimuth offset + firing-time correction d (|d| < 0.01 rad at the manuals'
    // firing times; <= 0.16 rad at 1 000 us and 1 500 rpm, the most accepted: a short series).
    const float d = static_cast<float>(fire_ns[ch]) * omega;
    const float cos_d = 1.0f - 0.5f * d * d;
    const float sin_d = d - d * d * d * (1.0f / 6.0f);
    const float cc = cos_el_cos_az[ch];
    const float cs = cos_el_sin_az[ch];
    dir_cos[ch] = cc * cos_d - cs * sin_d;
    dir_sin[ch] = cs * cos_d + cc * sin_d;
    // In [0, 360): the offset lies in [-360, 360] (set_angles) and d within 9 degrees, so at most
    // two additions of 360 or one subtraction, each rounded as a loop of them would round it.
    const float az0 = offset_deg[ch] + d * kRadToDeg;
    const float up0 = az0 + 360.0f;
    const float az1 = select(below_zero(az0), up0, az0);
    const float up1 = az1 + 360.0f;
    const float az2 = select(below_zero(az1), up1, az1);
    const float down = az2 - 360.0f;
    const float az = select(at_least(az2, 360.0f), down, az2);
    azimuth_deg[ch] = az;
    // The spread, of the azimuth folded into (-180, 180].
    const float folded = az - 360.0f;
    const std::int32_t key = order_key(select(above(az, 180.0f), folded, az));
    lo = key < lo ? key : lo;
    hi = key > hi ? key : hi;
  }
  lo_key = lo;
  hi_key = hi;
}

#if defined(HESAI_KERNELS_X86)
// The same loop for AVX2 (8 channels a step) and AVX-512 (16), where the decode finds them (from
// CPUID) and the caller's DecodePath allows them, written with intrinsics: the same float
// operations in the same order (no FMA), so the same bits. The wraps compare the floats as
// floats, which for the finite values here is what below_zero/at_least/above compute on the
// bits, and add 360 under the comparison's mask: 2 instructions a wrap with AVX-512 (a compare
// into a mask register and a masked addition) and 3 with AVX2 (compare, add, blend), where GCC
// 12's vectorisation of spin_loop took 5 and 4 (a sign flip, an integer compare and the
// selection's two xors). Per 16 channels the AVX-512 step is about 40 instructions against GCC's 44.
// Quiet comparisons (_OQ): no exception flag for any input.

// One step's azimuth wraps and spread key, as spin_loop computes them.
HESAI_AVX2_TARGET inline __m256 wrap_avx2(__m256 az0, __m256i& key) noexcept {
  const __m256 zero = _mm256_setzero_ps(), full = _mm256_set1_ps(360.0f);
  const __m256 az1 = _mm256_blendv_ps(az0, _mm256_add_ps(az0, full), _mm256_cmp_ps(az0, zero, _CMP_LT_OQ));
  const __m256 az2 = _mm256_blendv_ps(az1, _mm256_add_ps(az1, full), _mm256_cmp_ps(az1, zero, _CMP_LT_OQ));
  const __m256 az = _mm256_blendv_ps(az2, _mm256_sub_ps(az2, full), _mm256_cmp_ps(az2, full, _CMP_GE_OQ));
  const __m256 folded =
      _mm256_blendv_ps(az, _mm256_sub_ps(az, full), _mm256_cmp_ps(az, _mm256_set1_ps(180.0f), _CMP_GT_OQ));
  const __m256i b = _mm256_castps_si256(folded);
  key = _mm256_xor_si256(b, _mm256_and_si256(_mm256_srai_epi32(b, 31), _mm256_set1_epi32(0x7FFFFFFF)));
  return az;
}

// kArrays false: the spread alone (the azimuths of the loops a packet does not use).
template <bool kArrays>
HESAI_AVX2_TARGET void spin_loop_avx2(const BeamLoop& l, std::size_t channels, float omega, std::int32_t& lo_key,
                                      std::int32_t& hi_key) noexcept {
  const __m256 w = _mm256_set1_ps(omega), one = _mm256_set1_ps(1.0f), half = _mm256_set1_ps(0.5f);
  const __m256 sixth = _mm256_set1_ps(1.0f / 6.0f), rad_to_deg = _mm256_set1_ps(static_cast<float>(180.0 / kPi));
  __m256i lo = _mm256_set1_epi32(lo_key), hi = _mm256_set1_epi32(hi_key);
  // Locals: the stores through the output pointers could otherwise alias the BeamLoop.
  const std::int32_t* fire_ns = l.fire_ns;
  const float *cos_el_cos_az = l.cos_el_cos_az, *cos_el_sin_az = l.cos_el_sin_az, *offset_deg = l.offset_deg;
  float *dir_cos = l.dir_cos, *dir_sin = l.dir_sin, *azimuth_deg = l.azimuth_deg;
  std::size_t ch = 0;
  for (; channels - ch >= 8; ch += 8) {
    const __m256 d =
        _mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(fire_ns + ch))), w);
    if constexpr (kArrays) {
      const __m256 dd = _mm256_mul_ps(d, d);
      const __m256 cos_d = _mm256_sub_ps(one, _mm256_mul_ps(_mm256_mul_ps(half, d), d));
      const __m256 sin_d = _mm256_sub_ps(d, _mm256_mul_ps(_mm256_mul_ps(dd, d), sixth));
      const __m256 cc = _mm256_loadu_ps(cos_el_cos_az + ch), cs = _mm256_loadu_ps(cos_el_sin_az + ch);
      _mm256_storeu_ps(dir_cos + ch, _mm256_sub_ps(_mm256_mul_ps(cc, cos_d), _mm256_mul_ps(cs, sin_d)));
      _mm256_storeu_ps(dir_sin + ch, _mm256_add_ps(_mm256_mul_ps(cs, cos_d), _mm256_mul_ps(cc, sin_d)));
    }
    __m256i key;
    const __m256 az = wrap_avx2(_mm256_add_ps(_mm256_loadu_ps(offset_deg + ch), _mm256_mul_ps(d, rad_to_deg)), key);
    if constexpr (kArrays) _mm256_storeu_ps(azimuth_deg + ch, az);
    lo = _mm256_min_epi32(lo, key);
    hi = _mm256_max_epi32(hi, key);
  }
  // Across the lanes (each started from lo_key and hi_key): halves, then pairs, then neighbours.
  lo = _mm256_min_epi32(lo, _mm256_permute2x128_si256(lo, lo, 1));
  hi = _mm256_max_epi32(hi, _mm256_permute2x128_si256(hi, hi, 1));
  lo = _mm256_min_epi32(lo, _mm256_shuffle_epi32(lo, 0x4E));
  hi = _mm256_max_epi32(hi, _mm256_shuffle_epi32(hi, 0x4E));
  lo = _mm256_min_epi32(lo, _mm256_shuffle_epi32(lo, 0xB1));
  hi = _mm256_max_epi32(hi, _mm256_shuffle_epi32(hi, 0xB1));
  lo_key = _mm256_cvtsi256_si32(lo);
  hi_key = _mm256_cvtsi256_si32(hi);
  if (ch < channels && kArrays)  // no sensor's channel count leaves a remainder; the scalar loop if one did
    spin_loop(fire_ns + ch, cos_el_cos_az + ch, cos_el_sin_az + ch, offset_deg + ch, dir_cos + ch,
              dir_sin + ch, azimuth_deg + ch, channels - ch, omega, lo_key, hi_key);
}

// 16 channels a step; the last, partial step (the Pandar40's 40 channels) under a lane mask.
struct Avx512Spin {
  __m512 w, one, half, sixth, rad_to_deg, zero, full, half_turn;
  __m512i magnitude, lo, hi;

  // Channels [ch, ch + 16) of the lanes in m; kArrays false: the spread alone.
  template <bool kArrays>
  HESAI_AVX512_TARGET HESAI_ALWAYS_INLINE inline void step(const std::int32_t* fire_ns, const float* cos_el_cos_az,
                                                           const float* cos_el_sin_az, const float* offset_deg,
                                                           float* dir_cos, float* dir_sin, float* azimuth_deg,
                                                           __mmask16 m) noexcept {
    const __m512 d = _mm512_mul_ps(_mm512_cvtepi32_ps(_mm512_maskz_loadu_epi32(m, fire_ns)), w);
    if constexpr (kArrays) {
      const __m512 dd = _mm512_mul_ps(d, d);
      const __m512 cos_d = _mm512_sub_ps(one, _mm512_mul_ps(_mm512_mul_ps(half, d), d));
      const __m512 sin_d = _mm512_sub_ps(d, _mm512_mul_ps(_mm512_mul_ps(dd, d), sixth));
      const __m512 cc = _mm512_maskz_loadu_ps(m, cos_el_cos_az), cs = _mm512_maskz_loadu_ps(m, cos_el_sin_az);
      _mm512_mask_storeu_ps(dir_cos, m, _mm512_sub_ps(_mm512_mul_ps(cc, cos_d), _mm512_mul_ps(cs, sin_d)));
      _mm512_mask_storeu_ps(dir_sin, m, _mm512_add_ps(_mm512_mul_ps(cs, cos_d), _mm512_mul_ps(cc, sin_d)));
    }
    const __m512 az0 = _mm512_add_ps(_mm512_maskz_loadu_ps(m, offset_deg), _mm512_mul_ps(d, rad_to_deg));
    const __m512 az1 = _mm512_mask_add_ps(az0, _mm512_cmp_ps_mask(az0, zero, _CMP_LT_OQ), az0, full);
    const __m512 az2 = _mm512_mask_add_ps(az1, _mm512_cmp_ps_mask(az1, zero, _CMP_LT_OQ), az1, full);
    const __m512 az = _mm512_mask_sub_ps(az2, _mm512_cmp_ps_mask(az2, full, _CMP_GE_OQ), az2, full);
    if constexpr (kArrays) _mm512_mask_storeu_ps(azimuth_deg, m, az);
    const __m512i b =
        _mm512_castps_si512(_mm512_mask_sub_ps(az, _mm512_cmp_ps_mask(az, half_turn, _CMP_GT_OQ), az, full));
    const __m512i key = _mm512_ternarylogic_epi32(b, _mm512_srai_epi32(b, 31), magnitude, 0x78);  // b ^ (sign & magnitude)
    lo = _mm512_mask_min_epi32(lo, m, lo, key);
    hi = _mm512_mask_max_epi32(hi, m, hi, key);
  }
};

template <bool kArrays>
HESAI_AVX512_TARGET void spin_loop_avx512(const BeamLoop& l, std::size_t channels, float omega, std::int32_t& lo_key,
                                          std::int32_t& hi_key) noexcept {
  Avx512Spin s{_mm512_set1_ps(omega),
               _mm512_set1_ps(1.0f),
               _mm512_set1_ps(0.5f),
               _mm512_set1_ps(1.0f / 6.0f),
               _mm512_set1_ps(static_cast<float>(180.0 / kPi)),
               _mm512_setzero_ps(),
               _mm512_set1_ps(360.0f),
               _mm512_set1_ps(180.0f),
               _mm512_set1_epi32(0x7FFFFFFF),
               _mm512_set1_epi32(lo_key),
               _mm512_set1_epi32(hi_key)};
  // Locals: the stores through the output pointers could otherwise alias the BeamLoop.
  const std::int32_t* fire_ns = l.fire_ns;
  const float *cc = l.cos_el_cos_az, *cs = l.cos_el_sin_az, *offset = l.offset_deg;
  float *dir_cos = l.dir_cos, *dir_sin = l.dir_sin, *az = l.azimuth_deg;
  std::size_t ch = 0;
  for (; channels - ch >= 16; ch += 16)
    s.step<kArrays>(fire_ns + ch, cc + ch, cs + ch, offset + ch, dir_cos + ch, dir_sin + ch, az + ch, 0xFFFF);
  if (ch < channels)
    s.step<kArrays>(fire_ns + ch, cc + ch, cs + ch, offset + ch, dir_cos + ch, dir_sin + ch, az + ch,
           static_cast<__mmask16>((1u << (channels - ch)) - 1));
  const __m512i lo = s.lo, hi = s.hi;
  lo_key = _mm512_reduce_min_epi32(lo);
  hi_key = _mm512_reduce_max_epi32(hi);
}
#endif

}  // namespace

void rebuild_beams(const BeamLoop& l, std::size_t channels, float omega, [[maybe_unused]] VectorIsa isa,
                   std::int32_t& lo_key, std::int32_t& hi_key) noexcept {
#if defined(HESAI_KERNELS_X86)
  if (isa == VectorIsa::avx512) {
    HESAI_COUNT_KERNEL(avx512_beams);
    spin_loop_avx512<true>(l, channels, omega, lo_key, hi_key);
    return;
  }
  if (isa == VectorIsa::avx2) {
    HESAI_COUNT_KERNEL(avx2_beams);
    spin_loop_avx2<true>(l, channels, omega, lo_key, hi_key);
    return;
  }
#endif
  spin_loop(l.fire_ns, l.cos_el_cos_az, l.cos_el_sin_az, l.offset_deg, l.dir_cos, l.dir_sin, l.azimuth_deg, channels,
            omega, lo_key, hi_key);
}

bool spread_of_beams([[maybe_unused]] const BeamLoop& l, [[maybe_unused]] std::size_t channels,
                     [[maybe_unused]] float omega, [[maybe_unused]] VectorIsa isa,
                     [[maybe_unused]] std::int32_t& lo_key, [[maybe_unused]] std::int32_t& hi_key) noexcept {
#if defined(HESAI_KERNELS_X86)
  if (isa == VectorIsa::avx512) {
    spin_loop_avx512<false>(l, channels, omega, lo_key, hi_key);
    return true;
  }
  if (isa == VectorIsa::avx2 && channels % 8 == 0) {
    spin_loop_avx2<false>(l, channels, omega, lo_key, hi_key);
    return true;
  }
#endif
  return false;
}

}  // namespace hesai::kernels
