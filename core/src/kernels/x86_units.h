// The x86-64 vector kernels' shared parts (internal to the core; x86_columns.cpp and
// x86_points.cpp): the target attributes, and the loads that turn a block's units into lanes of
// x, y, z and the kept mask: eight units a step for AVX2 (EightUnits), sixteen for AVX-512
// (SixteenUnits). Compiled with function-level target attributes, so that the library needs no
// -m flags; chosen at run time from CPUID (vector_isa.h). Empty on other targets.
#pragma once

#include "vector_kernels.h"

#if defined(HESAI_KERNELS_X86)

#include <immintrin.h>

#include <cstddef>
#include <type_traits>

// GCC 12 warns inside its own AVX-512 headers at every use of an intrinsic that starts from an
// undefined vector (GCC bug 105593, fixed in GCC 13): nothing here is uninitialised.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ < 13
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#define HESAI_AVX2_TARGET __attribute__((target("avx2,popcnt")))
#define HESAI_AVX512_TARGET __attribute__((target("avx512f,avx512bw,avx512dq,avx512vl,avx2,popcnt")))

namespace hesai::kernels {


HESAI_AVX2_TARGET inline __m128i load16(const std::int8_t* p) noexcept {
  return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
}

// Eight units of a block, as both AVX2 loops read them: fields, position (the scalar loop's
// operations in its order, scalar_loops.h unit_xyz) and which are kept.
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
// scalar_loops.h unit_xyz), which lanes hold units and which are kept.
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

// block_sin_cos (vector_kernels.h) for every block at once, sixteen lanes, by the operations of
// sin_cos_centideg in its order (the same bits): the whole degrees and hundredths by multiplying
// (exact below 36000, which validate() guarantees of every block azimuth), the table entries by
// two-register permutations (gathers measured slower), the quadrant's swap and signs
// by blends and sign flips. The scalar form took about 40 instructions a block, as many as an
// XT16 block's sixteen units take in the columns loop.
constexpr bool divisions_by_multiplication_exact() {
  for (unsigned x = 0; x < 36000; ++x)
    if ((x * 5243u) >> 19 != x / 100u || (x / 100u * 729u) >> 16 != x / 100u / 90u) return false;
  return true;
}
static_assert(divisions_by_multiplication_exact(), "x / 100 and x / 90 by multiplication");

// detail::kSinWholeDegrees padded to 96 entries (six registers), so that it is read whole.
struct SinTable {
  alignas(64) float v[96];
};
constexpr SinTable sin_table() {
  SinTable t{};
  for (std::size_t i = 0; i < detail::kSinWholeDegrees.size(); ++i) t.v[i] = detail::kSinWholeDegrees[i];
  return t;
}
inline constexpr SinTable kSinTable = sin_table();

// kSinWholeDegrees[i] for i in 0..90 in each lane: three two-register permutations (entries 0..31,
// 32..63, 64..95) and the one that i >> 5 names.
HESAI_AVX512_TARGET inline __m512 whole_degree_sines(__m512i i) noexcept {
  const float* t = kSinTable.v;
  const __m512 r0 = _mm512_permutex2var_ps(_mm512_load_ps(t), i, _mm512_load_ps(t + 16));
  const __m512 r1 = _mm512_permutex2var_ps(_mm512_load_ps(t + 32), i, _mm512_load_ps(t + 48));
  const __m512 r2 = _mm512_permutex2var_ps(_mm512_load_ps(t + 64), i, _mm512_load_ps(t + 80));
  const __m512 r = _mm512_mask_blend_ps(_mm512_cmpge_epi32_mask(i, _mm512_set1_epi32(32)), r0, r1);
  return _mm512_mask_blend_ps(_mm512_cmpge_epi32_mask(i, _mm512_set1_epi32(64)), r, r2);
}

HESAI_AVX512_TARGET inline BlockSinCos block_sin_cos_avx512(const PacketConstants& k) noexcept {
  const __mmask16 m = static_cast<__mmask16>((1u << k.blocks) - 1);  // k.blocks <= kMaxBlocks
  const __m512i centideg = _mm512_cvtepu16_epi32(_mm256_maskz_loadu_epi16(m, k.block_azimuth));
  const __m512i deg = _mm512_srli_epi32(_mm512_mullo_epi32(centideg, _mm512_set1_epi32(5243)), 19);
  const __m512i hundredths = _mm512_sub_epi32(centideg, _mm512_mullo_epi32(deg, _mm512_set1_epi32(100)));
  const __m512 f = _mm512_mul_ps(_mm512_cvtepi32_ps(hundredths), _mm512_set1_ps(static_cast<float>(kPi / 18000.0)));
  const __m512 f2 = _mm512_mul_ps(f, f);
  const __m512 sin_f = _mm512_sub_ps(f, _mm512_mul_ps(_mm512_mul_ps(f, f2), _mm512_set1_ps(1.0f / 6)));
  const __m512 cos_f = _mm512_add_ps(_mm512_sub_ps(_mm512_set1_ps(1.0f), _mm512_mul_ps(f2, _mm512_set1_ps(0.5f))),
                                     _mm512_mul_ps(_mm512_mul_ps(f2, f2), _mm512_set1_ps(1.0f / 24)));
  const __m512i q = _mm512_srli_epi32(_mm512_mullo_epi32(deg, _mm512_set1_epi32(729)), 16);
  const __m512i d = _mm512_sub_epi32(deg, _mm512_mullo_epi32(q, _mm512_set1_epi32(90)));
  const __m512 sin_d = whole_degree_sines(d), cos_d = whole_degree_sines(_mm512_sub_epi32(_mm512_set1_epi32(90), d));
  const __m512 s = _mm512_add_ps(_mm512_mul_ps(sin_d, cos_f), _mm512_mul_ps(cos_d, sin_f));
  const __m512 c = _mm512_sub_ps(_mm512_mul_ps(cos_d, cos_f), _mm512_mul_ps(sin_d, sin_f));
  // Quadrant (q & 3): 0 (s, c), 1 (c, -s), 2 (-s, -c), 3 (-c, s).
  const __mmask16 swap = _mm512_test_epi32_mask(q, _mm512_set1_epi32(1));
  const __mmask16 negate_sin = _mm512_test_epi32_mask(q, _mm512_set1_epi32(2));
  const __mmask16 negate_cos = _mm512_test_epi32_mask(_mm512_xor_si512(q, _mm512_srli_epi32(q, 1)), _mm512_set1_epi32(1));
  const __m512 sign = _mm512_set1_ps(-0.0f);
  const __m512 sin_a = _mm512_mask_blend_ps(swap, s, c), cos_a = _mm512_mask_blend_ps(swap, c, s);
  BlockSinCos out;
  _mm512_mask_storeu_ps(out.sin, m, _mm512_mask_xor_ps(sin_a, negate_sin, sin_a, sign));
  _mm512_mask_storeu_ps(out.cos, m, _mm512_mask_xor_ps(cos_a, negate_cos, cos_a, sign));
  return out;
}

HESAI_AVX512_TARGET inline __m512i lane_indices() noexcept {
  return _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
}

}  // namespace hesai::kernels

#endif  // HESAI_KERNELS_X86
