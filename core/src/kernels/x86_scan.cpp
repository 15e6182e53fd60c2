// The unit scan (blockage markers, repeated dual returns, distances beyond the rated range) by
// AVX2, eight units a step, for the AVX2 and AVX-512 paths alike: the scalar scan's counts and bits
// (sensors/block_points.h scan_units, the reference tests/kernels/test_scan.cpp compares it with)
// without a branch on the units. Empty on other targets.
#include "vector_kernels.h"

#if defined(HESAI_KERNELS_X86)

#include "kernel_counters.h"
#include "x86_units.h"

namespace hesai::kernels {
namespace {

// Byte shuffles of one 16-byte load holding four units (the first at byte `first`, `stride` bytes
// apart): each unit's distance and intensity (bytes 0..2) into the low three bytes of a 32-bit
// lane, byte 3 cleared. -1 clears.
struct ScanShuffle {
  std::int8_t byte[16];
};
constexpr ScanShuffle scan_shuffle(int first, int stride) {
  ScanShuffle u{};
  for (int i = 0; i < 16; ++i) u.byte[i] = -1;
  for (int i = 0; i < 4; ++i)
    for (int b = 0; b < 3; ++b) u.byte[4 * i + b] = static_cast<std::int8_t>(first + i * stride + b);
  return u;
}
// [unit_bytes == 4][half], read as EightUnits reads them (kSecond).
constexpr ScanShuffle kScanShuffle[2][2] = {{scan_shuffle(0, 3), scan_shuffle(4, 3)}, {scan_shuffle(0, 4), scan_shuffle(0, 4)}};

// Units p[0..7]: distance | intensity << 16 in each lane.
HESAI_AVX2_TARGET inline __m256i unit_keys(const std::uint8_t* p, std::size_t second, __m128i lo, __m128i hi) noexcept {
  const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
  const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + second));
  return _mm256_inserti128_si256(_mm256_castsi128_si256(_mm_shuffle_epi8(a, lo)), _mm_shuffle_epi8(b, hi), 1);
}

HESAI_AVX2_TARGET inline unsigned lanes(__m256i mask) noexcept {
  return static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(mask)));
}

HESAI_AVX2_TARGET void scan_avx2(const ScanConstants& k, ScanOutput& out) noexcept {
  const std::size_t four = k.unit_bytes == 4 ? 1 : 0, step = 8 * k.unit_bytes, second = kSecond[four];
  const __m128i lo = load16(kScanShuffle[four][0].byte), hi = load16(kScanShuffle[four][1].byte);
  const __m256i distance_bits = _mm256_set1_epi32(0xFFFF), one = _mm256_set1_epi32(1);
  const __m256i limit = _mm256_set1_epi32(static_cast<int>(k.limit));
  const __m256i below = _mm256_set1_epi32(static_cast<int>(k.min_distance) - 1);
  std::uint32_t blockage = 0, beyond = 0, duplicates = 0;
  for (std::size_t b = 0; b < k.blocks; ++b) {
    const std::uint8_t* u = k.block[b].units;
    // The second return of a firing: compared with the first, unit by unit.
    const bool second_return = k.dual && b % 2 == 1;
    const std::uint8_t* first = second_return ? k.block[b - 1].units : nullptr;
    std::uint8_t* const row = second_return ? out.repeated[b / 2] : nullptr;
    for (std::size_t j = 0; j < k.units; j += 8, u += step) {
      const __m256i key = unit_keys(u, second, lo, hi);
      const __m256i distance = _mm256_and_si256(key, distance_bits);
      beyond += static_cast<std::uint32_t>(__builtin_popcount(lanes(_mm256_cmpgt_epi32(distance, limit))));
      if (k.markers) {  // the same for every unit of the packet
        unsigned m = lanes(_mm256_cmpeq_epi32(distance, one));
        blockage += static_cast<std::uint32_t>(__builtin_popcount(m));
        for (; m != 0; m &= m - 1) ++out.blockage_by_channel[j + static_cast<std::size_t>(__builtin_ctz(m))];
      }
      if (second_return) {
        const __m256i key0 = unit_keys(first, second, lo, hi);
        first += step;
        const __m256i kept = _mm256_cmpgt_epi32(_mm256_and_si256(key0, distance_bits), below);
        const unsigned m = lanes(_mm256_and_si256(_mm256_cmpeq_epi32(key0, key), kept));
        duplicates += static_cast<std::uint32_t>(__builtin_popcount(m));
        if (row != nullptr) row[j / 8] = static_cast<std::uint8_t>(row[j / 8] | m);
      }
    }
  }
  out.blockage += blockage;
  out.beyond += beyond;
  out.duplicates += duplicates;
}

}  // namespace

bool scan_vector(const ScanConstants& k, VectorIsa isa, ScanOutput& out) noexcept {
  if (isa != VectorIsa::avx2 && isa != VectorIsa::avx512) return false;
  if (k.units % 8 != 0 || k.units > kMaxChannels || k.blocks > kMaxBlocks || (k.unit_bytes != 3 && k.unit_bytes != 4))
    return false;
  HESAI_COUNT_KERNEL(avx2_scan);
  scan_avx2(k, out);
  return true;
}

}  // namespace hesai::kernels

#endif  // HESAI_KERNELS_X86
