// CRC-32/MPEG-2 folding with PCLMULQDQ, and with 512-bit VPCLMULQDQ where the CPU has it, on
// x86-64 (see crc32_fold.h for the mathematics).
// Compiled with a function-level target attribute so that the library itself needs no -m flags;
// the path is chosen at run time from CPUID. Empty on other targets.
#include "crc32_fold.h"

#if defined(HESAI_CRC32_FOLD_X86)

#include <immintrin.h>

#include "../base/cpu_x86.h"

#define HESAI_CLMUL_TARGET __attribute__((target("pclmul,sse4.1,ssse3")))
#define HESAI_VPCLMUL_TARGET \
  __attribute__((target("vpclmulqdq,avx512f,avx512bw,avx512dq,avx512vl,avx2,pclmul,sse4.1,ssse3")))

// GCC 12 warns inside its own AVX-512 headers at every use of an intrinsic that starts from an
// undefined vector (GCC bug 105593, fixed in GCC 13): nothing here is uninitialised.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ < 13
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

namespace hesai::crc32_fold {
namespace {

constexpr long long as_ll(std::uint64_t v) noexcept { return static_cast<long long>(v); }

// 16 bytes as a 128-bit big-endian number: byte 0's top bit becomes bit 127.
HESAI_CLMUL_TARGET inline __m128i load_be128(const std::uint8_t* p, __m128i reverse) noexcept {
  __m128i v;
  __builtin_memcpy(&v, p, sizeof v);  // unaligned load; a builtin even under -ffreestanding
  return _mm_shuffle_epi8(v, reverse);
}

// a * x^T mod P, up to 95 bits: k holds x^T mod P (low qword) and x^(T+64) mod P (high qword).
HESAI_CLMUL_TARGET inline __m128i fold(__m128i a, __m128i k) noexcept {
  return _mm_xor_si128(_mm_clmulepi64_si128(a, k, 0x00), _mm_clmulepi64_si128(a, k, 0x11));
}

// r * x^32 mod P.
HESAI_CLMUL_TARGET inline std::uint32_t reduce(__m128i r) noexcept {
  const __m128i k = _mm_set_epi64x(as_ll(kReduce64), as_ll(kReduce96));
  __m128i t = _mm_clmulepi64_si128(r, k, 0x01);                        // high qword * x^96
  t = _mm_xor_si128(t, _mm_slli_si128(_mm_move_epi64(r), 4));          // + low qword * x^32
  __m128i u = _mm_clmulepi64_si128(t, k, 0x11);                        // bits 64..95 * x^64
  u = _mm_xor_si128(u, _mm_move_epi64(t));                             // < 64 bits
  const __m128i b = _mm_set_epi64x(as_ll(kPoly33), as_ll(kBarrettMu));
  __m128i q = _mm_clmulepi64_si128(_mm_srli_epi64(u, 32), b, 0x00);    // (u >> 32) * mu
  q = _mm_srli_epi64(q, 32);                                           // floor(u / P)
  const __m128i r32 = _mm_xor_si128(u, _mm_clmulepi64_si128(q, b, 0x10));  // u - q * P
  return static_cast<std::uint32_t>(_mm_cvtsi128_si32(r32));
}

}  // namespace

bool fold_available() noexcept { return detail::x86_has(detail::X86Feature::clmul); }

HESAI_CLMUL_TARGET std::uint32_t fold_blocks(std::uint32_t crc, const std::uint8_t* p, std::size_t n) noexcept {
  HESAI_ASSERT(n >= kMinBytes);
  const __m128i reverse = _mm_set_epi8(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m128i k512 = _mm_set_epi64x(as_ll(kFold576), as_ll(kFold512));
  const __m128i k128 = _mm_set_epi64x(as_ll(kFold192), as_ll(kFold128));

  __m128i x0 = load_be128(p, reverse);
  __m128i x1 = load_be128(p + 16, reverse);
  __m128i x2 = load_be128(p + 32, reverse);
  __m128i x3 = load_be128(p + 48, reverse);
  x0 = _mm_xor_si128(x0, _mm_set_epi32(static_cast<int>(crc), 0, 0, 0));  // register -> first 4 bytes
  p += 64;
  n -= 64;
  for (; n >= 64; p += 64, n -= 64) {
    x0 = _mm_xor_si128(fold(x0, k512), load_be128(p, reverse));
    x1 = _mm_xor_si128(fold(x1, k512), load_be128(p + 16, reverse));
    x2 = _mm_xor_si128(fold(x2, k512), load_be128(p + 32, reverse));
    x3 = _mm_xor_si128(fold(x3, k512), load_be128(p + 48, reverse));
  }
  x1 = _mm_xor_si128(fold(x0, k128), x1);
  x2 = _mm_xor_si128(fold(x1, k128), x2);
  x3 = _mm_xor_si128(fold(x2, k128), x3);
  for (; n >= 16; p += 16, n -= 16) x3 = _mm_xor_si128(fold(x3, k128), load_be128(p, reverse));
  return reduce(x3);
}

namespace {

// ---- 512 bits at a time (VPCLMULQDQ): four 128-bit lanes per register, as four fold() at once.

HESAI_VPCLMUL_TARGET inline __m512i load_be512(const std::uint8_t* p, __m512i reverse) noexcept {
  return _mm512_shuffle_epi8(_mm512_loadu_si512(p), reverse);  // each 16-byte lane big-endian
}

// Each lane a * x^T mod P (up to 95 bits), k holding that lane's x^T and x^(T+64) mod P.
HESAI_VPCLMUL_TARGET inline __m512i fold4(__m512i a, __m512i k) noexcept {
  return _mm512_xor_si512(_mm512_clmulepi64_epi128(a, k, 0x00), _mm512_clmulepi64_epi128(a, k, 0x11));
}

// Lanes 4q .. 4q + 3 of the window's kLaneFolds.
HESAI_VPCLMUL_TARGET inline __m512i lane_folds(unsigned q) noexcept {
  const std::uint64_t* lo = kLaneFolds.lo + 4 * q;
  const std::uint64_t* hi = kLaneFolds.hi + 4 * q;
  return _mm512_set_epi64(as_ll(hi[3]), as_ll(lo[3]), as_ll(hi[2]), as_ll(lo[2]), as_ll(hi[1]), as_ll(lo[1]),
                          as_ll(hi[0]), as_ll(lo[0]));
}

}  // namespace

bool fold512_available() noexcept { return detail::x86_has(detail::X86Feature::vpclmul); }

HESAI_VPCLMUL_TARGET std::uint32_t fold_blocks_512(std::uint32_t crc, const std::uint8_t* p, std::size_t n) noexcept {
  HESAI_ASSERT(n >= kMinBytes512);
  const __m128i reverse128 = _mm_set_epi8(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m512i reverse = _mm512_broadcast_i32x4(reverse128);
  const __m512i k2048 = _mm512_set_epi64(as_ll(kFold2112), as_ll(kFold2048), as_ll(kFold2112), as_ll(kFold2048),
                                         as_ll(kFold2112), as_ll(kFold2048), as_ll(kFold2112), as_ll(kFold2048));
  __m512i x0 = load_be512(p, reverse);
  __m512i x1 = load_be512(p + 64, reverse);
  __m512i x2 = load_be512(p + 128, reverse);
  __m512i x3 = load_be512(p + 192, reverse);
  // The register -> the first 4 bytes (the top of lane 0).
  x0 = _mm512_xor_si512(x0, _mm512_zextsi128_si512(_mm_set_epi32(static_cast<int>(crc), 0, 0, 0)));
  p += 256;
  n -= 256;
  for (; n >= 256; p += 256, n -= 256) {
    x0 = _mm512_xor_si512(fold4(x0, k2048), load_be512(p, reverse));
    x1 = _mm512_xor_si512(fold4(x1, k2048), load_be512(p + 64, reverse));
    x2 = _mm512_xor_si512(fold4(x2, k2048), load_be512(p + 128, reverse));
    x3 = _mm512_xor_si512(fold4(x3, k2048), load_be512(p + 192, reverse));
  }
  // Every lane to the end of the window, summed into one 128-bit accumulator.
  const __m512i sum = _mm512_xor_si512(_mm512_xor_si512(fold4(x0, lane_folds(0)), fold4(x1, lane_folds(1))),
                                       _mm512_xor_si512(fold4(x2, lane_folds(2)), fold4(x3, lane_folds(3))));
  const __m256i half = _mm256_xor_si256(_mm512_castsi512_si256(sum), _mm512_extracti64x4_epi64(sum, 1));
  __m128i r = _mm_xor_si128(_mm256_castsi256_si128(half), _mm256_extracti128_si256(half, 1));
  const __m128i k128 = _mm_set_epi64x(as_ll(kFold192), as_ll(kFold128));
  for (; n >= 16; p += 16, n -= 16) r = _mm_xor_si128(fold(r, k128), load_be128(p, reverse128));
  return reduce(r);
}

}  // namespace hesai::crc32_fold

#endif  // HESAI_CRC32_FOLD_X86
