// Points (hesai::Point, 40 bytes each) by the x86-64 vector kernels: AVX-512, sixteen units a
// step, and AVX2, eight units a step (x86_units.h). Empty on other targets.
#include "vector_kernels.h"

#if defined(HESAI_KERNELS_X86)

#include <cstddef>

#include "kernel_counters.h"
#include "x86_units.h"

namespace hesai::kernels {
namespace {


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
HESAI_AVX2_TARGET void points_avx2(const PacketConstants& k, Point* out, std::size_t& count) noexcept {
  EightUnits eight_units(k);
  const BlockSinCos sc = block_sin_cos(k);
  const std::size_t blocks = k.blocks, units = k.units;
  const __m256 full_turn = _mm256_set1_ps(360.0f);
  const float* const elevation_deg = k.elevation_deg;
  std::uint8_t* const base = reinterpret_cast<std::uint8_t*>(out);
  std::size_t n = count;
  std::size_t return_of_block = 0;  // return_index(k.returns, b)
  for (std::size_t b = 0; b < blocks; ++b, return_of_block = next_return_index(return_of_block, k.returns)) {
    const BlockRef& kb = k.block[b];
    eight_units.start(kb, sc.sin[b], sc.cos[b]);
    const __m256 block_deg = _mm256_set1_ps(static_cast<float>(k.block_azimuth[b]) * 0.01f);
    const __m256i block_time = _mm256_set1_epi64x(static_cast<long long>(k.time_ns + kb.offset_ns));
    const __m128i ret = _mm_set1_epi8(static_cast<char>(return_of_block));
    const __m128i block = _mm_set1_epi32(static_cast<int>(b));  // the block byte, then three zero bytes
    const float* const azimuth_deg = k.azimuth_deg[kb.loop];
    const std::int32_t* const fire_ns = k.fire_ns[kb.loop];
    __m128i channel = first_channels();
    for (std::size_t j = 0; j < units; j += 8) {
      const Eight e = eight_units.at(j);
      // The scalar loop's operations in its order (scalar_loops.h, write_points).
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
      const __m128 ae[4] = {_mm256_castps256_ps128(ae_lo), _mm256_castps256_ps128(ae_hi),
                            _mm256_extractf128_ps(ae_lo, 1), _mm256_extractf128_ps(ae_hi, 1)};
      const __m128i t[4] = {_mm256_castsi256_si128(t_lo), _mm256_extracti128_si256(t_lo, 1),
                            _mm256_castsi256_si128(t_hi), _mm256_extracti128_si256(t_hi, 1)};
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
  }
  count = n;
}

// Points, sixteen units a step: each point's 40 bytes in two stores (x, y, z, distance, azimuth,
// elevation, time; then the bytes), the eight fields of the first store transposed from the
// sixteen lanes by 22 two-source permutations, where the AVX2 loop takes about 90 shuffles for
// as many units.
template <std::size_t kUnitBytes>
HESAI_AVX512_TARGET void points_avx512(const PacketConstants& k, Point* out, std::size_t& count) noexcept {
  SixteenUnits<kUnitBytes> sixteen_units(k);
  const std::size_t blocks = k.blocks, units = k.units;
  // Intensity in byte 0 and the confidence byte of a 4-byte unit in byte 3 of each lane.
  const __m512i intensity_confidence = every_lane(kIntensityConfidence[kUnitBytes == 4]);
  const __m512 full_turn = _mm512_set1_ps(360.0f);
  const float* const elevation_deg = k.elevation_deg;
  // Two-source permutations (indices 16.. and 8.. name the second source): dwords of units
  // 0..7 (8..15) of a and b in pairs; qword pairs u of a and b for units 0..3 (4..7); the
  // 128-bit halves of units 2m, 2m + 1 (m even, odd) side by side.
  const __m512i pair_lo = _mm512_setr_epi32(0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23);
  const __m512i pair_hi = _mm512_setr_epi32(8, 24, 9, 25, 10, 26, 11, 27, 12, 28, 13, 29, 14, 30, 15, 31);
  const __m512i quad_lo = _mm512_setr_epi64(0, 8, 1, 9, 2, 10, 3, 11);
  const __m512i quad_hi = _mm512_setr_epi64(4, 12, 5, 13, 6, 14, 7, 15);
  const __m512i rows_lo = _mm512_setr_epi64(0, 1, 8, 9, 2, 3, 10, 11);
  const __m512i rows_hi = _mm512_setr_epi64(4, 5, 12, 13, 6, 7, 14, 15);
  const BlockSinCos sc = block_sin_cos_avx512(k);
  std::uint8_t* const base = reinterpret_cast<std::uint8_t*>(out);
  std::size_t n = count;
  std::size_t return_of_block = 0;  // return_index(k.returns, b)
  for (std::size_t b = 0; b < blocks; ++b, return_of_block = next_return_index(return_of_block, k.returns)) {
    const BlockRef& kb = k.block[b];
    sixteen_units.start(kb, sc.sin[b], sc.cos[b]);
    const __m512 block_deg = _mm512_set1_ps(static_cast<float>(k.block_azimuth[b]) * 0.01f);
    const __m512i block_time = _mm512_set1_epi64(static_cast<long long>(k.time_ns + kb.offset_ns));
    // Channel j + 1 in byte 1 and the return index in byte 2 of lane j; the block byte at byte 4
    // of each unit's 8 trailing bytes.
    __m512i channel_return =
        _mm512_or_si512(_mm512_slli_epi32(_mm512_add_epi32(lane_indices(), _mm512_set1_epi32(1)), 8),
                        _mm512_set1_epi32(static_cast<int>(return_of_block) << 16));
    const __m512i block = _mm512_set1_epi64(static_cast<long long>(b) << 32);
    const float* const azimuth_deg = k.azimuth_deg[kb.loop];
    const std::int32_t* const fire_ns = k.fire_ns[kb.loop];
    // A step of sixteen units (kFull) or the block's last, of fewer.
    const auto step = [&](std::size_t j, auto full) HESAI_AVX512_TARGET {
      constexpr bool kFull = decltype(full)::value;
      const Sixteen s = sixteen_units.template at<kFull>(j);
      // The scalar loop's operations in its order (scalar_loops.h, write_points).
      const __m512 sum = _mm512_add_ps(block_deg, _mm512_maskz_loadu_ps(s.lanes, azimuth_deg + j));
      const __m512 az = _mm512_mask_sub_ps(sum, _mm512_cmp_ps_mask(sum, full_turn, _CMP_GE_OQ), sum, full_turn);
      const __m512 el = _mm512_maskz_loadu_ps(s.lanes, elevation_deg + j);
      const __m512i fire = _mm512_maskz_loadu_epi32(s.lanes, fire_ns + j);
      const __m512i t[2] = {_mm512_add_epi64(block_time, _mm512_cvtepi32_epi64(_mm512_castsi512_si256(fire))),
                            _mm512_add_epi64(block_time, _mm512_cvtepi32_epi64(_mm512_extracti64x4_epi64(fire, 1)))};
      // The trailing 8 bytes of each point: intensity, channel, return index, confidence, block, 0.
      const __m512i tail32 = _mm512_or_si512(_mm512_shuffle_epi8(s.bytes, intensity_confidence), channel_return);
      const __m512i tail[2] = {_mm512_or_si512(_mm512_cvtepu32_epi64(_mm512_castsi512_si256(tail32)), block),
                               _mm512_or_si512(_mm512_cvtepu32_epi64(_mm512_extracti64x4_epi64(tail32, 1)), block)};
      channel_return = _mm512_add_epi32(channel_return, _mm512_set1_epi32(16 << 8));
      for (unsigned h = 0; h < 2; ++h) {  // units 8h .. 8h + 7
        const __m512i pair = h == 0 ? pair_lo : pair_hi;
        const __m512d xy = _mm512_castps_pd(_mm512_permutex2var_ps(s.x, pair, s.y));
        const __m512d zr = _mm512_castps_pd(_mm512_permutex2var_ps(s.z, pair, s.r));
        const __m512d ae = _mm512_castps_pd(_mm512_permutex2var_ps(az, pair, el));
        const __m512d td = _mm512_castsi512_pd(t[h]);
        for (unsigned g = 0; g < 2; ++g) {  // units 8h + 4g .. + 3
          const __m512i quad = g == 0 ? quad_lo : quad_hi;
          const __m512d xyzr = _mm512_permutex2var_pd(xy, quad, zr);  // 16 bytes a unit
          const __m512d aet = _mm512_permutex2var_pd(ae, quad, td);   // 16 bytes a unit
          for (unsigned m = 0; m < 2; ++m) {  // units 8h + 4g + 2m, + 1
            const __m512d rows = _mm512_permutex2var_pd(xyzr, m == 0 ? rows_lo : rows_hi, aet);
            for (unsigned e = 0; e < 2; ++e) {
              const unsigned i = 8 * h + 4 * g + 2 * m + e;
              if (!kFull && i >= s.count) break;
              std::uint8_t* o = base + n * sizeof(Point);
              _mm256_storeu_pd(reinterpret_cast<double*>(o), e == 0 ? _mm512_castpd512_pd256(rows) : _mm512_extractf64x4_pd(rows, 1));
              const __m128i pair_tail = lane_of(tail[h], 2 * g + m);
              if (e == 0) {
                _mm_storel_epi64(reinterpret_cast<__m128i*>(o + 32), pair_tail);
              } else {
                _mm_storeh_pd(reinterpret_cast<double*>(o + 32), _mm_castsi128_pd(pair_tail));
              }
              n += (s.keep >> i) & 1u;
            }
          }
        }
      }
    };
    std::size_t j = 0;
    for (; j + 16 <= units; j += 16) step(j, std::true_type{});
    if (j < units) step(j, std::false_type{});
  }
  count = n;
}

}  // namespace

bool points_vector(const PacketConstants& k, VectorIsa isa, Point* out, std::size_t& count) noexcept {
  switch (isa) {
    case VectorIsa::avx512:
      HESAI_COUNT_KERNEL(avx512_points);
      if (k.unit_bytes == 4) points_avx512<4>(k, out, count);
      else points_avx512<3>(k, out, count);
      return true;
    case VectorIsa::avx2:
      if (k.units % 8 != 0) return false;
      HESAI_COUNT_KERNEL(avx2_points);
      points_avx2(k, out, count);
      return true;
    default: break;
  }
  return false;
}

}  // namespace hesai::kernels

#endif  // HESAI_KERNELS_X86
