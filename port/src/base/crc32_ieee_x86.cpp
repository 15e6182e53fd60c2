// CRC-32 (IEEE, reflected) folding with PCLMULQDQ on x86-64: four 128-bit accumulators 512 bits
// apart, then one, then 64 and 32 bits and a Barrett reduction (Gopal et al., "Fast CRC
// Computation for Generic Polynomials Using PCLMULQDQ Instruction", Intel 2009, the bit-reflected
// form; the steps of zlib's and Chromium's crc32_simd.c). Compiled with function-level target
// attributes, so the library needs no -m flags; crc32_ieee.cpp calls it where CPUID says it runs.
// Empty on other targets.
#include "crc32_ieee_kernels.h"

#if defined(HESAI_CRC32_IEEE_PCLMUL)

#include <cpuid.h>
#include <immintrin.h>

#define HESAI_CLMUL_TARGET __attribute__((target("pclmul,sse4.1,ssse3")))

namespace hesai::port::crc32_ieee_kernels {
namespace {

// Polynomials as bit masks, bit i the coefficient of x^i (the unreflected form).
constexpr std::uint32_t kPoly = 0x04C11DB7u;

// x^k mod P.
constexpr std::uint32_t xpow_mod(unsigned k) noexcept {
  std::uint32_t r = 1;
  for (unsigned i = 0; i < k; ++i) r = (r & 0x80000000u) != 0 ? (r << 1) ^ kPoly : r << 1;
  return r;
}

constexpr std::uint64_t reflect(std::uint64_t v, unsigned bits) noexcept {
  std::uint64_t r = 0;
  for (unsigned i = 0; i < bits; ++i) r |= ((v >> i) & 1u) << (bits - 1 - i);
  return r;
}

// The folding constant for a distance of e bits in the reflected domain: x^e mod P, reflected,
// times x (one bit of shift that the reflected carry-less product needs).
constexpr std::uint64_t fold_constant(unsigned e) noexcept { return reflect(xpow_mod(e), 32) << 1; }

// floor(x^64 / P) by long division (33 bits), for the Barrett step.
constexpr std::uint64_t barrett_mu() noexcept {
  constexpr std::uint64_t poly33 = (std::uint64_t{1} << 32) | kPoly;
  std::uint64_t rem = 0, q = 0;  // the dividend x^64 enters bit by bit, highest first
  for (int pos = 64; pos >= 0; --pos) {
    rem = (rem << 1) | (pos == 64 ? 1u : 0u);
    if ((rem >> 32) & 1u) {
      rem ^= poly33;
      q |= std::uint64_t{1} << pos;
    }
  }
  return q;
}

// In the reflected order a register's low qword holds the earlier bytes (the higher powers).
constexpr std::uint64_t kK1 = fold_constant(4 * 128 + 32);  // fold by 512 bits: the low qword's
constexpr std::uint64_t kK2 = fold_constant(4 * 128 - 32);  // fold by 512 bits: the high qword's
constexpr std::uint64_t kK3 = fold_constant(128 + 32);      // fold by 128 bits: the low qword's
constexpr std::uint64_t kK4 = fold_constant(128 - 32);      // fold by 128 bits: the high qword's; 128 -> 96
constexpr std::uint64_t kK5 = fold_constant(64);            // 96 -> 64 bits
constexpr std::uint64_t kMu = reflect(barrett_mu(), 33);
constexpr std::uint64_t kPolyReflected = reflect((std::uint64_t{1} << 32) | kPoly, 33);
// The constants the paper and zlib publish, derived here from the polynomial.
static_assert(kK1 == 0x154442BD4u && kK2 == 0x1C6E41596u, "512-bit fold constants");
static_assert(kK3 == 0x1751997D0u && kK4 == 0x0CCAA009Eu, "128-bit fold constants");
static_assert(kK5 == 0x163CD6124u, "64-bit fold constant");
static_assert(kMu == 0x1F7011641u && kPolyReflected == 0x1DB710641u, "Barrett constants");

constexpr long long as_ll(std::uint64_t v) noexcept { return static_cast<long long>(v); }

HESAI_CLMUL_TARGET inline __m128i load128(const std::uint8_t* p) noexcept {
  __m128i v;
  __builtin_memcpy(&v, p, sizeof v);  // unaligned load
  return v;
}

// a * x^T, a's low qword by k's low, high by k's high (k = constants for distance T).
HESAI_CLMUL_TARGET inline __m128i fold(__m128i a, __m128i k) noexcept {
  return _mm_xor_si128(_mm_clmulepi64_si128(a, k, 0x00), _mm_clmulepi64_si128(a, k, 0x11));
}

}  // namespace

bool pclmul_available() noexcept {
  static const bool available = [] {
    unsigned a = 0, b = 0, c = 0, d = 0;
    if (__get_cpuid(1, &a, &b, &c, &d) == 0) return false;
    return (c & bit_PCLMUL) != 0 && (c & bit_SSSE3) != 0 && (c & bit_SSE4_1) != 0;
  }();
  return available;
}

HESAI_CLMUL_TARGET std::uint32_t pclmul_blocks(std::uint32_t reg, const std::uint8_t* p, std::size_t n) noexcept {
  // n >= 64 and a multiple of 16 (the caller's contract).
  const __m128i k1k2 = _mm_set_epi64x(as_ll(kK2), as_ll(kK1));
  const __m128i k3k4 = _mm_set_epi64x(as_ll(kK4), as_ll(kK3));
  __m128i x1 = _mm_xor_si128(load128(p), _mm_cvtsi32_si128(static_cast<int>(reg)));  // register -> first 4 bytes
  __m128i x2 = load128(p + 16);
  __m128i x3 = load128(p + 32);
  __m128i x4 = load128(p + 48);
  p += 64;
  n -= 64;
  for (; n >= 64; p += 64, n -= 64) {
    x1 = _mm_xor_si128(fold(x1, k1k2), load128(p));
    x2 = _mm_xor_si128(fold(x2, k1k2), load128(p + 16));
    x3 = _mm_xor_si128(fold(x3, k1k2), load128(p + 32));
    x4 = _mm_xor_si128(fold(x4, k1k2), load128(p + 48));
  }
  x1 = _mm_xor_si128(fold(x1, k3k4), x2);
  x1 = _mm_xor_si128(fold(x1, k3k4), x3);
  x1 = _mm_xor_si128(fold(x1, k3k4), x4);
  for (; n >= 16; p += 16, n -= 16) x1 = _mm_xor_si128(fold(x1, k3k4), load128(p));

  // 128 -> 96 bits: the low qword (earlier bytes) folded onto the high one.
  const __m128i mask32 = _mm_setr_epi32(-1, 0, -1, 0);
  __m128i t = _mm_clmulepi64_si128(x1, k3k4, 0x10);
  x1 = _mm_xor_si128(_mm_srli_si128(x1, 8), t);
  // 96 -> 64 bits.
  const __m128i k5 = _mm_set_epi64x(0, as_ll(kK5));
  t = _mm_srli_si128(x1, 4);
  x1 = _mm_xor_si128(_mm_clmulepi64_si128(_mm_and_si128(x1, mask32), k5, 0x00), t);
  // Barrett reduction to 32 bits.
  const __m128i poly = _mm_set_epi64x(as_ll(kMu), as_ll(kPolyReflected));
  t = _mm_clmulepi64_si128(_mm_and_si128(x1, mask32), poly, 0x10);
  t = _mm_clmulepi64_si128(_mm_and_si128(t, mask32), poly, 0x00);
  x1 = _mm_xor_si128(x1, t);
  return static_cast<std::uint32_t>(_mm_extract_epi32(x1, 1));
}

}  // namespace hesai::port::crc32_ieee_kernels

#endif  // HESAI_CRC32_IEEE_PCLMUL
