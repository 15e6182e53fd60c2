#include "beam_cache.h"

#include "hesai/detail/math.h"
#include "kernel_inputs.h"

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
// The same loop for AVX2 (8 channels a step, native blends and integer minima: a third of the
// time of the SSE2 baseline per QT128 rebuild), where the decode finds AVX2 (from CPUID) and the
// caller's DecodePath allows it. No FMA: the same operations, so the same bits.
// __restrict: without it GCC 12 needs more run-time overlap checks than it allows and leaves the
// loop scalar (the baseline, inlined into update_spin, sees the arrays as members of one object).
__attribute__((target("avx2"))) void spin_loop_avx2(const std::int32_t* fire_ns, const float* cos_el_cos_az,
                                                    const float* cos_el_sin_az, const float* offset_deg,
                                                    float* __restrict dir_cos, float* __restrict dir_sin,
                                                    float* __restrict azimuth_deg,
                                                    std::size_t channels, float omega, std::int32_t& lo_key,
                                                    std::int32_t& hi_key) noexcept {
  spin_loop(fire_ns, cos_el_cos_az, cos_el_sin_az, offset_deg, dir_cos, dir_sin, azimuth_deg, channels, omega,
            lo_key, hi_key);
}

// And for AVX-512 (16 channels a step), where the decode finds it.
#if defined(__clang__)
#define HESAI_SPIN_AVX512 __attribute__((target("avx512f,avx512bw,avx512dq,avx512vl,avx2")))
#else  // GCC otherwise vectorises it 8 channels wide
#define HESAI_SPIN_AVX512 __attribute__((target("avx512f,avx512bw,avx512dq,avx512vl,avx2,prefer-vector-width=512")))
#endif
HESAI_SPIN_AVX512 void spin_loop_avx512(
    const std::int32_t* fire_ns, const float* cos_el_cos_az, const float* cos_el_sin_az, const float* offset_deg,
    float* __restrict dir_cos, float* __restrict dir_sin, float* __restrict azimuth_deg, std::size_t channels,
    float omega, std::int32_t& lo_key, std::int32_t& hi_key) noexcept {
  spin_loop(fire_ns, cos_el_cos_az, cos_el_sin_az, offset_deg, dir_cos, dir_sin, azimuth_deg, channels, omega,
            lo_key, hi_key);
}
#endif

}  // namespace

void rebuild_beams(const BeamLoop& l, std::size_t channels, float omega, [[maybe_unused]] VectorIsa isa,
                   std::int32_t& lo_key, std::int32_t& hi_key) noexcept {
#if defined(HESAI_KERNELS_X86)
  if (isa == VectorIsa::avx512) {
    spin_loop_avx512(l.fire_ns, l.cos_el_cos_az, l.cos_el_sin_az, l.offset_deg, l.dir_cos, l.dir_sin, l.azimuth_deg,
                     channels, omega, lo_key, hi_key);
    return;
  }
  if (isa == VectorIsa::avx2) {
    spin_loop_avx2(l.fire_ns, l.cos_el_cos_az, l.cos_el_sin_az, l.offset_deg, l.dir_cos, l.dir_sin, l.azimuth_deg,
                   channels, omega, lo_key, hi_key);
    return;
  }
#endif
  spin_loop(l.fire_ns, l.cos_el_cos_az, l.cos_el_sin_az, l.offset_deg, l.dir_cos, l.dir_sin, l.azimuth_deg, channels,
            omega, lo_key, hi_key);
}

}  // namespace hesai::kernels
