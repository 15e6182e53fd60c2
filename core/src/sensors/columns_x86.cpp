// The columnar decode with AVX2 on x86-64 (see columns_simd.h): eight units a step. Compiled with
// a function-level target attribute, so that the library needs no -m flags; chosen at run time
// from CPUID, as the CRC's PCLMULQDQ path is. Empty on other targets.
#include "columns_simd.h"

#if defined(HESAI_COLUMNS_AVX2)

#include <cpuid.h>
#include <immintrin.h>

#include <atomic>

#define HESAI_AVX2_TARGET __attribute__((target("avx2,popcnt")))

namespace hesai::detail {
namespace {

// 0: not asked yet, 1: absent, 2: present. Relaxed: every thread computes the same answer.
std::atomic<std::uint8_t> g_avx2{0};

bool cpu_has_avx2() noexcept {
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  if (__get_cpuid(1, &eax, &ebx, &ecx, &edx) == 0) return false;
  // CPUID.01H:ECX (Intel SDM vol. 2A, table 3-10): OSXSAVE (27) and AVX (28); XCR0 bits 1 and 2:
  // the OS saves the SSE and AVX state; CPUID.(EAX=07H, ECX=0):EBX bit 5: AVX2. POPCNT: ECX bit 23.
  constexpr unsigned kNeed = (1u << 23) | (1u << 27) | (1u << 28);
  if ((ecx & kNeed) != kNeed) return false;
  unsigned xcr0_lo = 0, xcr0_hi = 0;
  __asm__("xgetbv" : "=a"(xcr0_lo), "=d"(xcr0_hi) : "c"(0));
  if ((xcr0_lo & 6u) != 6u) return false;
  if (__get_cpuid_count(7, 0, &eax, &ebx, &ecx, &edx) == 0) return false;
  return (ebx & (1u << 5)) != 0;
}

HESAI_AVX2_TARGET inline __m128i load16(const std::int8_t* p) noexcept {
  return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
}

HESAI_AVX2_TARGET std::size_t columns_avx2(const BlockConstants& k, const std::uint8_t* units, std::size_t unit_count,
                                           std::size_t unit_bytes, const PointColumns& out, std::size_t& count) noexcept {
  const std::size_t wide = unit_bytes == 4 ? 1 : 0;
  const std::size_t second = kSecond[wide];
  const __m128i lo_distance = load16(kShuffle[wide][0].distance), lo_intensity = load16(kShuffle[wide][0].intensity);
  const __m128i hi_distance = load16(kShuffle[wide][1].distance), hi_intensity = load16(kShuffle[wide][1].intensity);
  const __m256 sin_a = _mm256_set1_ps(k.sin_a), cos_a = _mm256_set1_ps(k.cos_a), unit_m = _mm256_set1_ps(k.unit_m);
  const __m256i below = _mm256_set1_epi32(k.min_distance - 1);
  const __m256i offset = _mm256_set1_epi32(k.offset_ns);
  const __m128i ret = _mm_set1_epi8(static_cast<char>(k.return_index));
  __m128i channel = _mm_setr_epi8(1, 2, 3, 4, 5, 6, 7, 8, 0, 0, 0, 0, 0, 0, 0, 0);
  const __m128i eight = _mm_set1_epi8(8);
  // The columns in locals: stores through the byte columns may alias anything in memory.
  float* const x_out = out.x;
  float* const y_out = out.y;
  float* const z_out = out.z;
  std::int32_t* const time_out = out.time_ns;
  std::uint8_t* const intensity_out = out.intensity;
  std::uint8_t* const channel_out = out.channel;
  std::uint8_t* const return_out = out.return_index;
  const float* const dir_cos = k.dir_cos;
  const float* const dir_sin = k.dir_sin;
  const float* const sin_el = k.sin_el;
  const std::int32_t* const fire_ns = k.fire_ns;
  std::size_t n = count;
  std::size_t j = 0;
  for (; j + 8 <= unit_count; j += 8) {
    const std::uint8_t* p = units + j * unit_bytes;
    const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
    const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + second));
    const __m256i raw = _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_shuffle_epi8(a, lo_distance)),
                                                _mm_shuffle_epi8(b, hi_distance), 1);
    const __m128i intensity = _mm_or_si128(_mm_shuffle_epi8(a, lo_intensity), _mm_shuffle_epi8(b, hi_intensity));
    // The scalar loop's operations in its order (block_points.h, unit_xyz).
    const __m256 r = _mm256_mul_ps(_mm256_cvtepi32_ps(raw), unit_m);
    const __m256 dc = _mm256_loadu_ps(dir_cos + j);
    const __m256 ds = _mm256_loadu_ps(dir_sin + j);
    const __m256 x = _mm256_mul_ps(r, _mm256_add_ps(_mm256_mul_ps(sin_a, dc), _mm256_mul_ps(cos_a, ds)));
    const __m256 y = _mm256_mul_ps(r, _mm256_sub_ps(_mm256_mul_ps(cos_a, dc), _mm256_mul_ps(sin_a, ds)));
    const __m256 z = _mm256_mul_ps(r, _mm256_loadu_ps(sin_el + j));
    const __m256i t = _mm256_add_epi32(offset, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(fire_ns + j)));
    // Keep the lanes with a valid distance, packed to the front.
    const unsigned keep = static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(raw, below))));
    const __m128i order = _mm_cvtsi64_si128(static_cast<long long>(kCompress[keep]));
    const __m256i perm = _mm256_cvtepu8_epi32(order);
    _mm256_storeu_ps(x_out + n, _mm256_permutevar8x32_ps(x, perm));
    _mm256_storeu_ps(y_out + n, _mm256_permutevar8x32_ps(y, perm));
    _mm256_storeu_ps(z_out + n, _mm256_permutevar8x32_ps(z, perm));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(time_out + n), _mm256_permutevar8x32_epi32(t, perm));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(intensity_out + n), _mm_shuffle_epi8(intensity, order));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(channel_out + n), _mm_shuffle_epi8(channel, order));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(return_out + n), ret);
    channel = _mm_add_epi8(channel, eight);
    n += static_cast<std::size_t>(_mm_popcnt_u32(keep));
  }
  count = n;
  return j;
}

}  // namespace

bool columns_simd_available() noexcept {
  std::uint8_t state = g_avx2.load(std::memory_order_relaxed);
  if (state == 0) {
    state = cpu_has_avx2() ? 2 : 1;
    g_avx2.store(state, std::memory_order_relaxed);
  }
  return state == 2;
}

std::size_t columns_simd(const BlockConstants& k, const std::uint8_t* units, std::size_t unit_count,
                         std::size_t unit_bytes, const PointColumns& out, std::size_t& count) noexcept {
  if (!columns_simd_available()) return 0;
  return columns_avx2(k, units, unit_count, unit_bytes, out, count);
}

}  // namespace hesai::detail

#endif  // HESAI_COLUMNS_AVX2
