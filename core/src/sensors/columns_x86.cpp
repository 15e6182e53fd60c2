// The decode's vector paths on x86-64 (see columns_simd.h), for columns and Points: AVX-512,
// sixteen units a step, and AVX2, eight units a step. Compiled with function-level target
// attributes, so that the library needs no -m flags; chosen at run time from CPUID, as the CRC's
// PCLMULQDQ path is. Empty on other targets.
#include "columns_simd.h"

#if defined(HESAI_COLUMNS_AVX2)

#include <immintrin.h>

#include <cstddef>
#include <type_traits>

#include "../base/cpu_x86.h"

// GCC 12 warns inside its own AVX-512 headers at every use of an intrinsic that starts from an
// undefined vector (GCC bug 105593, fixed in GCC 13): nothing here is uninitialised.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ < 13
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#define HESAI_AVX2_TARGET __attribute__((target("avx2,popcnt")))
#define HESAI_AVX512_TARGET __attribute__((target("avx512f,avx512bw,avx512dq,avx512vl,avx2,popcnt")))

namespace hesai::detail {
namespace {

HESAI_AVX2_TARGET inline __m128i load16(const std::int8_t* p) noexcept {
  return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
}

// Eight units of a block, as both AVX2 loops read them: fields, position (the scalar loop's
// operations in its order, block_points.h unit_xyz) and which are kept.
struct Eight {
  __m256i raw;
  __m128i intensity, confidence;  // bytes 0..7
  __m256 r, x, y, z;
  unsigned keep;                  // bit i: unit i has a valid distance
};

// The packet's constants as vectors (set up once per packet), the block's (once per block), and
// the step from units to Eight.
class EightUnits {
 public:
  HESAI_AVX2_TARGET explicit EightUnits(const PacketConstants& k) noexcept
      : unit_bytes_(k.unit_bytes), second_(kSecond[k.unit_bytes == 4 ? 1 : 0]), sin_el_(k.sin_el) {
    const UnitShuffle& lo = kShuffle[k.unit_bytes == 4 ? 1 : 0][0];
    const UnitShuffle& hi = kShuffle[k.unit_bytes == 4 ? 1 : 0][1];
    lo_[0] = load16(lo.distance), lo_[1] = load16(lo.intensity), lo_[2] = load16(lo.confidence);
    hi_[0] = load16(hi.distance), hi_[1] = load16(hi.intensity), hi_[2] = load16(hi.confidence);
    unit_m_ = _mm256_set1_ps(k.unit_m);
    below_ = _mm256_set1_epi32(k.min_distance - 1);
    for (std::size_t loop = 0; loop < 2; ++loop) dir_cos_loop_[loop] = k.dir_cos[loop], dir_sin_loop_[loop] = k.dir_sin[loop];
  }

  HESAI_AVX2_TARGET void start(const BlockRef& b, float sin_a, float cos_a) noexcept {
    units_ = b.units;
    sin_a_ = _mm256_set1_ps(sin_a), cos_a_ = _mm256_set1_ps(cos_a);
    dir_cos_ = dir_cos_loop_[b.loop], dir_sin_ = dir_sin_loop_[b.loop];
  }

  // Units j .. j + 7 of the block.
  HESAI_AVX2_TARGET Eight at(std::size_t j) const noexcept {
    const std::uint8_t* p = units_ + j * unit_bytes_;
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
  const float* sin_el_;
  const float* dir_cos_loop_[2];
  const float* dir_sin_loop_[2];
  __m128i lo_[3], hi_[3];  // byte shuffles: distance, intensity, confidence
  __m256 unit_m_;
  __m256i below_;
  // The block's.
  const std::uint8_t* units_ = nullptr;
  const float* dir_cos_ = nullptr;
  const float* dir_sin_ = nullptr;
  __m256 sin_a_, cos_a_;
};

// The channels 1..8 of the first eight units, as bytes.
HESAI_AVX2_TARGET inline __m128i first_channels() noexcept { return _mm_setr_epi8(1, 2, 3, 4, 5, 6, 7, 8, 0, 0, 0, 0, 0, 0, 0, 0); }

// `out` by value: stores through its byte columns may alias anything in memory but not a local.
HESAI_AVX2_TARGET void columns_avx2(const PacketConstants& k, const PointColumns out, std::size_t& count) noexcept {
  EightUnits eight_units(k);
  const BlockSinCos sc = block_sin_cos(k);
  const std::size_t blocks = k.blocks, units = k.units;
  std::size_t n = count;
  for (std::size_t b = 0; b < blocks; ++b) {
    const BlockRef& kb = k.block[b];
    eight_units.start(kb, sc.sin[b], sc.cos[b]);
    const __m256i offset = _mm256_set1_epi32(kb.offset_ns);
    const std::int32_t* const fire_ns = k.fire_ns[kb.loop];
    const __m128i ret = _mm_set1_epi8(static_cast<char>(return_index(k.returns, b)));
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
  for (std::size_t b = 0; b < blocks; ++b) {
    const BlockRef& kb = k.block[b];
    eight_units.start(kb, sc.sin[b], sc.cos[b]);
    const __m256 block_deg = _mm256_set1_ps(static_cast<float>(k.block_azimuth[b]) * 0.01f);
    const __m256i block_time = _mm256_set1_epi64x(static_cast<long long>(k.time_ns + kb.offset_ns));
    const __m128i ret = _mm_set1_epi8(static_cast<char>(return_index(k.returns, b)));
    const __m128i block = _mm_set1_epi32(static_cast<int>(b));  // the block byte, then three zero bytes
    const float* const azimuth_deg = k.azimuth_deg[kb.loop];
    const std::int32_t* const fire_ns = k.fire_ns[kb.loop];
    __m128i channel = first_channels();
    for (std::size_t j = 0; j < units; j += 8) {
      const Eight e = eight_units.at(j);
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

// AVX-512: sixteen units a step, any number of units per block (the last step masked).

// The dword shuffle that puts 3-byte units 4L..4L + 3 at the start of 128-bit lane L (their 12
// bytes start at dword 3L); 4-byte units are in place.
HESAI_AVX512_TARGET inline __m512i three_byte_lanes() noexcept {
  return _mm512_setr_epi32(0, 1, 2, 3, 3, 4, 5, 6, 6, 7, 8, 9, 9, 10, 11, 12);
}

// A byte shuffle for each 128-bit lane holding four units at bytes 0, s, 2s, 3s (s the unit
// size): bytes `field` and `field + 1` (width 2) or `field` alone of unit i into dword i, the rest
// 0; `top`, when not -1, into byte 3 of the dword.
struct LaneShuffle {
  std::int8_t byte[16];
};
constexpr LaneShuffle lane_shuffle(int unit_bytes, int field, int width, int top = -1) {
  LaneShuffle u{};
  for (int i = 0; i < 16; ++i) u.byte[i] = -1;
  for (int i = 0; i < 4; ++i) {
    const int at = i * unit_bytes;
    for (int b = 0; b < width; ++b) u.byte[4 * i + b] = static_cast<std::int8_t>(at + field + b);
    if (top >= 0) u.byte[4 * i + 3] = static_cast<std::int8_t>(at + top);
  }
  return u;
}
// [unit_bytes == 4]: the distance; the intensity; the intensity with a 4-byte unit's confidence
// in byte 3.
inline constexpr LaneShuffle kDistance[2] = {lane_shuffle(3, 0, 2), lane_shuffle(4, 0, 2)};
inline constexpr LaneShuffle kIntensity[2] = {lane_shuffle(3, 2, 1), lane_shuffle(4, 2, 1)};
inline constexpr LaneShuffle kIntensityConfidence[2] = {lane_shuffle(3, 2, 1), lane_shuffle(4, 2, 1, 3)};

HESAI_AVX512_TARGET inline __m512i every_lane(const LaneShuffle& u) noexcept {
  return _mm512_broadcast_i32x4(_mm_loadu_si128(reinterpret_cast<const __m128i*>(u.byte)));
}

// Sixteen units of a block, as both AVX-512 loops read them: the unit bytes (each unit's at the
// start of dword i's 128-bit lane group), position (the scalar loop's operations in its order,
// block_points.h unit_xyz), which lanes hold units and which are kept.
struct Sixteen {
  __m512i bytes, raw;
  __m512 r, x, y, z;
  __mmask16 lanes, keep;
  std::size_t count;  // units in the step: 16 but in a block's last step of fewer
};

template <std::size_t kUnitBytes>
class SixteenUnits {
 public:
  HESAI_AVX512_TARGET explicit SixteenUnits(const PacketConstants& k) noexcept
      : units_(k.units),
        sin_el_(k.sin_el),
        distance_(every_lane(kDistance[kUnitBytes == 4])),
        lanes_of_three_(three_byte_lanes()),
        unit_m_(_mm512_set1_ps(k.unit_m)),
        below_(_mm512_set1_epi32(k.min_distance - 1)) {
    for (std::size_t loop = 0; loop < 2; ++loop) dir_cos_loop_[loop] = k.dir_cos[loop], dir_sin_loop_[loop] = k.dir_sin[loop];
  }

  HESAI_AVX512_TARGET void start(const BlockRef& b, float sin_a, float cos_a) noexcept {
    block_units_ = b.units;
    sin_a_ = _mm512_set1_ps(sin_a), cos_a_ = _mm512_set1_ps(cos_a);
    dir_cos_ = dir_cos_loop_[b.loop], dir_sin_ = dir_sin_loop_[b.loop];
  }

  // Units j .. j + 15 of the block: all sixteen (kFull), or those below its unit count.
  template <bool kFull>
  HESAI_AVX512_TARGET Sixteen at(std::size_t j) const noexcept {
    Sixteen s;
    const std::size_t left = units_ - j;
    s.count = kFull ? 16 : left;
    s.lanes = kFull ? __mmask16{0xFFFF} : static_cast<__mmask16>((1u << left) - 1);
    const std::size_t span = s.count * kUnitBytes;
    const __mmask64 byte_lanes = span >= 64 ? ~__mmask64{0} : (__mmask64{1} << span) - 1;
    s.bytes = _mm512_maskz_loadu_epi8(byte_lanes, block_units_ + j * kUnitBytes);
    if constexpr (kUnitBytes == 3) s.bytes = _mm512_permutexvar_epi32(lanes_of_three_, s.bytes);
    s.raw = _mm512_shuffle_epi8(s.bytes, distance_);
    s.r = _mm512_mul_ps(_mm512_cvtepi32_ps(s.raw), unit_m_);
    const __m512 dc = _mm512_maskz_loadu_ps(s.lanes, dir_cos_ + j);
    const __m512 ds = _mm512_maskz_loadu_ps(s.lanes, dir_sin_ + j);
    s.x = _mm512_mul_ps(s.r, _mm512_add_ps(_mm512_mul_ps(sin_a_, dc), _mm512_mul_ps(cos_a_, ds)));
    s.y = _mm512_mul_ps(s.r, _mm512_sub_ps(_mm512_mul_ps(cos_a_, dc), _mm512_mul_ps(sin_a_, ds)));
    s.z = _mm512_mul_ps(s.r, _mm512_maskz_loadu_ps(s.lanes, sin_el_ + j));
    s.keep = _mm512_mask_cmpgt_epi32_mask(s.lanes, s.raw, below_);
    return s;
  }

 private:
  std::size_t units_;
  const float* sin_el_;
  const float* dir_cos_loop_[2];
  const float* dir_sin_loop_[2];
  __m512i distance_, lanes_of_three_;
  __m512 unit_m_;
  __m512i below_;
  // The block's.
  const std::uint8_t* block_units_ = nullptr;
  const float* dir_cos_ = nullptr;
  const float* dir_sin_ = nullptr;
  __m512 sin_a_, cos_a_;
};

// 128-bit lane `lane` of v (a constant once the loops are unrolled).
HESAI_AVX512_TARGET inline __m128i lane_of(__m512i v, unsigned lane) noexcept {
  switch (lane) {
    case 0: return _mm512_castsi512_si128(v);
    case 1: return _mm512_extracti32x4_epi32(v, 1);
    case 2: return _mm512_extracti32x4_epi32(v, 2);
    default: return _mm512_extracti32x4_epi32(v, 3);
  }
}

HESAI_AVX512_TARGET inline __m512i lane_indices() noexcept {
  return _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
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
  const BlockSinCos sc = block_sin_cos(k);
  std::size_t n = count;
  for (std::size_t b = 0; b < blocks; ++b) {
    const BlockRef& kb = k.block[b];
    sixteen_units.start(kb, sc.sin[b], sc.cos[b]);
    const __m512i offset = _mm512_set1_epi32(kb.offset_ns);
    const __m128i ret = _mm_set1_epi8(static_cast<char>(return_index(k.returns, b)));
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
  const BlockSinCos sc = block_sin_cos(k);
  std::uint8_t* const base = reinterpret_cast<std::uint8_t*>(out);
  std::size_t n = count;
  for (std::size_t b = 0; b < blocks; ++b) {
    const BlockRef& kb = k.block[b];
    sixteen_units.start(kb, sc.sin[b], sc.cos[b]);
    const __m512 block_deg = _mm512_set1_ps(static_cast<float>(k.block_azimuth[b]) * 0.01f);
    const __m512i block_time = _mm512_set1_epi64(static_cast<long long>(k.time_ns + kb.offset_ns));
    // Channel j + 1 in byte 1 and the return index in byte 2 of lane j; the block byte at byte 4
    // of each unit's 8 trailing bytes.
    __m512i channel_return =
        _mm512_or_si512(_mm512_slli_epi32(_mm512_add_epi32(lane_indices(), _mm512_set1_epi32(1)), 8),
                        _mm512_set1_epi32(static_cast<int>(return_index(k.returns, b)) << 16));
    const __m512i block = _mm512_set1_epi64(static_cast<long long>(b) << 32);
    const float* const azimuth_deg = k.azimuth_deg[kb.loop];
    const std::int32_t* const fire_ns = k.fire_ns[kb.loop];
    // A step of sixteen units (kFull) or the block's last, of fewer.
    const auto step = [&](std::size_t j, auto full) HESAI_AVX512_TARGET {
      constexpr bool kFull = decltype(full)::value;
      const Sixteen s = sixteen_units.template at<kFull>(j);
      // The scalar loop's operations in its order (block_points.h, write_points).
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

// Which vector code `path` runs on this CPU.
enum class Isa { none, avx2, avx512 };
Isa isa_for(DecodePath path) noexcept {
  if (path == DecodePath::portable || !x86_has(X86Feature::avx2)) return Isa::none;
  if (path == DecodePath::best && x86_has(X86Feature::avx512)) return Isa::avx512;
  return Isa::avx2;
}

}  // namespace

bool columns_simd_available() noexcept { return x86_has(X86Feature::avx2); }
const char* columns_simd_name() noexcept {
  switch (isa_for(DecodePath::best)) {
    case Isa::avx512: return "avx512";
    case Isa::avx2: return "avx2";
    case Isa::none: break;
  }
  return "none";
}

bool points_simd(const PacketConstants& k, DecodePath path, Point* out, std::size_t& count) noexcept {
  switch (isa_for(path)) {
    case Isa::avx512:
      if (k.unit_bytes == 4) points_avx512<4>(k, out, count);
      else points_avx512<3>(k, out, count);
      return true;
    case Isa::avx2:
      if (k.units % 8 != 0) return false;
      points_avx2(k, out, count);
      return true;
    case Isa::none: break;
  }
  return false;
}

bool columns_simd(const PacketConstants& k, DecodePath path, const PointColumns out, std::size_t& count) noexcept {
  switch (isa_for(path)) {
    case Isa::avx512:
      if (k.unit_bytes == 4) columns_avx512<4>(k, out, count);
      else columns_avx512<3>(k, out, count);
      return true;
    case Isa::avx2:
      if (k.units % 8 != 0) return false;
      columns_avx2(k, out, count);
      return true;
    case Isa::none: break;
  }
  return false;
}

}  // namespace hesai::detail

#endif  // HESAI_COLUMNS_AVX2
