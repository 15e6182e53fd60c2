// The columnar decode with AVX2 on x86-64 (see columns_simd.h): eight units a step. Compiled with
// a function-level target attribute, so that the library needs no -m flags; chosen at run time
// from CPUID, as the CRC's PCLMULQDQ path is. Empty on other targets.
#include "columns_simd.h"

#if defined(HESAI_COLUMNS_AVX2)

#include <immintrin.h>

#include <cstddef>

#include "../base/cpu_x86.h"

#define HESAI_AVX2_TARGET __attribute__((target("avx2,popcnt")))

namespace hesai::detail {
namespace {

HESAI_AVX2_TARGET inline __m128i load16(const std::int8_t* p) noexcept {
  return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
}

// Eight units of a block, as both paths read them: fields, position (the scalar loop's
// operations in its order, block_points.h unit_xyz) and which are kept.
struct Eight {
  __m256i raw;
  __m128i intensity, confidence;  // bytes 0..7
  __m256 r, x, y, z;
  unsigned keep;                  // bit i: unit i has a valid distance
};

// The block's constants as vectors, and the step from units to Eight.
class EightUnits {
 public:
  HESAI_AVX2_TARGET EightUnits(const BlockConstants& k, std::size_t unit_bytes) noexcept
      : unit_bytes_(unit_bytes),
        second_(kSecond[unit_bytes == 4 ? 1 : 0]),
        dir_cos_(k.dir_cos),
        dir_sin_(k.dir_sin),
        sin_el_(k.sin_el) {
    const UnitShuffle& lo = kShuffle[unit_bytes == 4 ? 1 : 0][0];
    const UnitShuffle& hi = kShuffle[unit_bytes == 4 ? 1 : 0][1];
    lo_[0] = load16(lo.distance), lo_[1] = load16(lo.intensity), lo_[2] = load16(lo.confidence);
    hi_[0] = load16(hi.distance), hi_[1] = load16(hi.intensity), hi_[2] = load16(hi.confidence);
    sin_a_ = _mm256_set1_ps(k.sin_a), cos_a_ = _mm256_set1_ps(k.cos_a), unit_m_ = _mm256_set1_ps(k.unit_m);
    below_ = _mm256_set1_epi32(k.min_distance - 1);
  }

  // Units j .. j + 7.
  HESAI_AVX2_TARGET Eight at(const std::uint8_t* units, std::size_t j) const noexcept {
    const std::uint8_t* p = units + j * unit_bytes_;
    const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
    const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + second_));
    Eight e;
    e.raw = _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_shuffle_epi8(a, lo_[0])), _mm_shuffle_epi8(b, hi_[0]), 1);
    e.intensity = _mm_or_si128(_mm_shuffle_epi8(a, lo_[1]), _mm_shuffle_epi8(b, hi_[1]));
    e.confidence = _mm_or_si128(_mm_shuffle_epi8(a, lo_[2]), _mm_shuffle_epi8(b, hi_[2]));
    e.r = _mm256_mul_ps(_mm256_cvtepi32_ps(e.raw), unit_m_);
    const __m256 dc = _mm256_loadu_ps(dir_cos_ + j);
    const __m256 ds = _mm256_loadu_ps(dir_sin_ + j);
    e.x = _mm256_mul_ps(e.r, _mm256_add_ps(_mm256_mul_ps(sin_a_, dc), _mm256_mul_ps(cos_a_, ds)));
    e.y = _mm256_mul_ps(e.r, _mm256_sub_ps(_mm256_mul_ps(cos_a_, dc), _mm256_mul_ps(sin_a_, ds)));
    e.z = _mm256_mul_ps(e.r, _mm256_loadu_ps(sin_el_ + j));
    e.keep = static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(e.raw, below_))));
    return e;
  }

 private:
  std::size_t unit_bytes_, second_;
  const float* dir_cos_;
  const float* dir_sin_;
  const float* sin_el_;
  __m128i lo_[3], hi_[3];  // byte shuffles: distance, intensity, confidence
  __m256 sin_a_, cos_a_, unit_m_;
  __m256i below_;
};

// The channels 1..8 of the first eight units, as bytes.
HESAI_AVX2_TARGET inline __m128i first_channels() noexcept { return _mm_setr_epi8(1, 2, 3, 4, 5, 6, 7, 8, 0, 0, 0, 0, 0, 0, 0, 0); }

// `out` by value: stores through its byte columns may alias anything in memory but not a local.
HESAI_AVX2_TARGET std::size_t columns_avx2(const BlockConstants& k, const std::uint8_t* units, std::size_t unit_count,
                                           std::size_t unit_bytes, const PointColumns out, std::size_t& count) noexcept {
  const EightUnits eight_units(k, unit_bytes);
  const __m256i offset = _mm256_set1_epi32(k.offset_ns);
  const std::int32_t* const fire_ns = k.fire_ns;
  const __m128i ret = _mm_set1_epi8(static_cast<char>(k.return_index));
  __m128i channel = first_channels();
  std::size_t n = count;
  std::size_t j = 0;
  for (; j + 8 <= unit_count; j += 8) {
    const Eight e = eight_units.at(units, j);
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
  count = n;
  return j;
}

// The 8 bytes of a Point from `intensity` on: intensity, channel, return index, confidence, block,
// and the 3 bytes of padding (written as 0).
static_assert(offsetof(Point, y) == 4 && offsetof(Point, z) == 8 && offsetof(Point, distance_m) == 12 &&
              offsetof(Point, azimuth_deg) == 16 && offsetof(Point, elevation_deg) == 20 &&
              offsetof(Point, time_ns) == 24 && offsetof(Point, intensity) == 32 && offsetof(Point, channel) == 33 &&
              offsetof(Point, return_index) == 34 && offsetof(Point, confidence) == 35 && offsetof(Point, block) == 36 &&
              sizeof(Point) == 40, "points_avx2 writes this layout");

// Eight units a step, as columns_avx2; then each point's 40 bytes in two stores (x, y, z,
// distance, azimuth, elevation and time; the bytes) instead of twelve, from the eight lanes
// transposed.
HESAI_AVX2_TARGET std::size_t points_avx2(const BlockConstants& k, const std::uint8_t* units, std::size_t unit_count,
                                          std::size_t unit_bytes, Point* out, std::size_t& count) noexcept {
  const EightUnits eight_units(k, unit_bytes);
  const __m256 block_deg = _mm256_set1_ps(k.block_deg), full_turn = _mm256_set1_ps(360.0f);
  const __m256i block_time = _mm256_set1_epi64x(static_cast<long long>(k.block_time_ns));
  const __m128i ret = _mm_set1_epi8(static_cast<char>(k.return_index));
  const __m128i block = _mm_set1_epi32(k.block);  // the block byte, then three zero bytes
  __m128i channel = first_channels();
  const float* const azimuth_deg = k.azimuth_deg;
  const float* const elevation_deg = k.elevation_deg;
  const std::int32_t* const fire_ns = k.fire_ns;
  std::uint8_t* const base = reinterpret_cast<std::uint8_t*>(out);
  std::size_t n = count;
  std::size_t j = 0;
  for (; j + 8 <= unit_count; j += 8) {
    const Eight e = eight_units.at(units, j);
    // The scalar loop's operations in its order (block_points.h, write_points).
    const __m256 sum = _mm256_add_ps(block_deg, _mm256_loadu_ps(azimuth_deg + j));
    const __m256 az = _mm256_sub_ps(sum, _mm256_and_ps(_mm256_cmp_ps(sum, full_turn, _CMP_GE_OQ), full_turn));
    const __m256 el = _mm256_loadu_ps(elevation_deg + j);
    const __m256i fire = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(fire_ns + j));
    const __m256i t_lo = _mm256_add_epi64(block_time, _mm256_cvtepi32_epi64(_mm256_castsi256_si128(fire)));
    const __m256i t_hi = _mm256_add_epi64(block_time, _mm256_cvtepi32_epi64(_mm256_extracti128_si256(fire, 1)));
    // x, y, z, distance of point i: 128-bit lane i / 4 of xyzr[i % 4].
    const __m256 xy_lo = _mm256_unpacklo_ps(e.x, e.y), xy_hi = _mm256_unpackhi_ps(e.x, e.y);
    const __m256 zr_lo = _mm256_unpacklo_ps(e.z, e.r), zr_hi = _mm256_unpackhi_ps(e.z, e.r);
    const __m256 xyzr[4] = {_mm256_shuffle_ps(xy_lo, zr_lo, 0x44), _mm256_shuffle_ps(xy_lo, zr_lo, 0xEE),
                            _mm256_shuffle_ps(xy_hi, zr_hi, 0x44), _mm256_shuffle_ps(xy_hi, zr_hi, 0xEE)};
    // Azimuth, elevation of points 2q, 2q + 1: the halves of ae[q]; likewise time and the bytes.
    const __m256 ae_lo = _mm256_unpacklo_ps(az, el), ae_hi = _mm256_unpackhi_ps(az, el);
    const __m128 ae[4] = {_mm256_castps256_ps128(ae_lo), _mm256_castps256_ps128(ae_hi), _mm256_extractf128_ps(ae_lo, 1),
                          _mm256_extractf128_ps(ae_hi, 1)};
    const __m128i t[4] = {_mm256_castsi256_si128(t_lo), _mm256_extracti128_si256(t_lo, 1), _mm256_castsi256_si128(t_hi),
                          _mm256_extracti128_si256(t_hi, 1)};
    const __m128i ic = _mm_unpacklo_epi8(e.intensity, channel), rc = _mm_unpacklo_epi8(ret, e.confidence);
    const __m128i icrc_lo = _mm_unpacklo_epi16(ic, rc), icrc_hi = _mm_unpackhi_epi16(ic, rc);
    const __m128i bytes[4] = {_mm_unpacklo_epi32(icrc_lo, block), _mm_unpackhi_epi32(icrc_lo, block),
                              _mm_unpacklo_epi32(icrc_hi, block), _mm_unpackhi_epi32(icrc_hi, block)};
    for (unsigned q = 0; q < 4; ++q) {
      // Bytes 16..31 of points 2q and 2q + 1: azimuth, elevation, time.
      const __m128i aet[2] = {_mm_unpacklo_epi64(_mm_castps_si128(ae[q]), t[q]),
                              _mm_unpackhi_epi64(_mm_castps_si128(ae[q]), t[q])};
      for (unsigned h = 0; h < 2; ++h) {
        const unsigned i = 2 * q + h;
        std::uint8_t* o = base + n * sizeof(Point);
        const __m256 v = xyzr[i % 4];
        const __m128 xyz_distance = i < 4 ? _mm256_castps256_ps128(v) : _mm256_extractf128_ps(v, 1);
        _mm256_storeu_ps(reinterpret_cast<float*>(o),
                         _mm256_insertf128_ps(_mm256_castps128_ps256(xyz_distance), _mm_castsi128_ps(aet[h]), 1));
        if (h == 0) {
          _mm_storel_epi64(reinterpret_cast<__m128i*>(o + 32), bytes[q]);
        } else {
          _mm_storeh_pd(reinterpret_cast<double*>(o + 32), _mm_castsi128_pd(bytes[q]));
        }
        n += (e.keep >> i) & 1u;
      }
    }
    channel = _mm_add_epi8(channel, _mm_set1_epi8(8));
  }
  count = n;
  return j;
}

}  // namespace

bool columns_simd_available() noexcept { return x86_has(X86Feature::avx2); }

std::size_t points_simd(const BlockConstants& k, const std::uint8_t* units, std::size_t unit_count,
                        std::size_t unit_bytes, Point* out, std::size_t& count) noexcept {
  if (!columns_simd_available()) return 0;
  return points_avx2(k, units, unit_count, unit_bytes, out, count);
}

std::size_t columns_simd(const BlockConstants& k, const std::uint8_t* units, std::size_t unit_count,
                         std::size_t unit_bytes, const PointColumns out, std::size_t& count) noexcept {
  if (!columns_simd_available()) return 0;
  return columns_avx2(k, units, unit_count, unit_bytes, out, count);
}

}  // namespace hesai::detail

#endif  // HESAI_COLUMNS_AVX2
