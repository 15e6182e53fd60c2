// Carry-less multiplication folding for CRC-32/MPEG-2 (private to the core).
//
// Polynomials over GF(2) are bit masks here: bit i is the coefficient of x^i. With the init value
// xored into the first four bytes, the CRC of a message M (first byte's top bit = highest degree)
// is M(x) * x^32 mod P(x). Reading 16 bytes big-endian gives a 128-bit polynomial A with the same
// bit order. A block followed by T more bits of message contributes A * x^T; writing A = H*x^64 + L,
//   A * x^T == H * (x^(T+64) mod P) + L * (x^T mod P)   (mod P),
// a 95-bit value that is xored into the block T bits later ("folding"). Four accumulators fold
// across 512 bits, one across 128. The 512-bit kernel (VPCLMULQDQ, x86-64) folds sixteen 128-bit
// lanes across 2048 bits, then each lane by its distance from the end of its 256-byte window
// into one accumulator. The last 128-bit accumulator R is reduced to R * x^32 mod P
// with two more folds (x^96, x^64) and a Barrett step (mu = floor(x^64 / P)). Every constant is
// computed below from the polynomial; crc32.cpp proves the scheme against the definition at
// compile time with the software model at the end of this file.
#pragma once

#include <cstddef>
#include <cstdint>

#include "../base/compiler.h"
#include "hesai/bytes.h"
#include "hesai/crc32.h"

// With HESAI_CRC32_ALT the platform's function replaces the folding kernels.
#if HESAI_CRC32_ALT
#elif defined(__x86_64__) && HESAI_GNU
#define HESAI_CRC32_FOLD_X86 1  // PCLMULQDQ, chosen at run time by CPUID (GNU target attributes)
#elif defined(__aarch64__) && (defined(__ARM_FEATURE_CRYPTO) || defined(__ARM_FEATURE_AES)) && \
    !defined(__ARM_BIG_ENDIAN)
#define HESAI_CRC32_FOLD_ARM 1  // PMULL (ACLE intrinsics), chosen at compile time
#endif

namespace hesai::crc32_fold {

/// Inputs shorter than this take the slicing path (folding needs four 16-byte blocks).
inline constexpr std::size_t kMinBytes = 64;

/// x^k mod P.
constexpr std::uint32_t xpow_mod(unsigned k) noexcept {
  std::uint32_t r = 1;  // x^0
  for (unsigned i = 0; i < k; ++i) r = (r & 0x80000000u) != 0 ? (r << 1) ^ kCrc32Mpeg2Poly : r << 1;
  return r;
}

/// P with its x^32 term (33 bits).
inline constexpr std::uint64_t kPoly33 = (std::uint64_t{1} << 32) | kCrc32Mpeg2Poly;

/// floor(x^64 / P) by long division (33 bits).
constexpr std::uint64_t barrett_mu() noexcept {
  std::uint64_t q = 0;
  std::uint64_t window = 0;  // bit j: coefficient of x^(pos + j) of the running remainder
  for (int pos = 64; pos >= 0; --pos) {
    window = (window << 1) | (pos == 64 ? 1u : 0u);
    if ((window >> 32) & 1u) {
      window ^= kPoly33;
      q |= std::uint64_t{1} << pos;
    }
  }
  return q;
}

inline constexpr std::uint64_t kFold512 = xpow_mod(512);  ///< low half, four accumulators apart
inline constexpr std::uint64_t kFold576 = xpow_mod(576);  ///< high half, four accumulators apart
inline constexpr std::uint64_t kFold128 = xpow_mod(128);  ///< low half, next block
inline constexpr std::uint64_t kFold192 = xpow_mod(192);  ///< high half, next block
inline constexpr std::uint64_t kReduce96 = xpow_mod(96);  ///< R*x^32: high 64 bits times x^96
inline constexpr std::uint64_t kReduce64 = xpow_mod(64);  ///< then bits 64..95 times x^64
inline constexpr std::uint64_t kBarrettMu = barrett_mu();
static_assert(kBarrettMu >> 32 == 1, "mu has degree 64 - 32");

/// The 512-bit kernel: four 64-byte accumulators, 256 bytes (2048 bits) apart.
inline constexpr std::size_t kMinBytes512 = 256;
inline constexpr std::uint64_t kFold2048 = xpow_mod(2048);
inline constexpr std::uint64_t kFold2112 = xpow_mod(2112);
/// Lane L (0..15, 16 bytes each) of the last 256-byte window times x^(128 (15 - L)): [L] holds
/// x^(128 (15 - L)) mod P and x^(128 (15 - L) + 64) mod P.
struct LaneFolds {
  std::uint64_t lo[16], hi[16];
};
constexpr LaneFolds lane_folds() noexcept {
  LaneFolds f{};
  for (unsigned lane = 0; lane < 16; ++lane) {
    f.lo[lane] = xpow_mod(128 * (15 - lane));
    f.hi[lane] = xpow_mod(128 * (15 - lane) + 64);
  }
  return f;
}
inline constexpr LaneFolds kLaneFolds = lane_folds();  // computed at compile time

#if defined(HESAI_CRC32_FOLD_X86) || defined(HESAI_CRC32_FOLD_ARM)
/// True when this CPU can run fold_blocks (x86-64: CPUID, cached; AArch64: always).
bool fold_available() noexcept;
/// Feeds the first (n & ~15) bytes at `p` into `crc` and returns the register; n >= kMinBytes.
std::uint32_t fold_blocks(std::uint32_t crc, const std::uint8_t* p, std::size_t n) noexcept;
#endif
#if defined(HESAI_CRC32_FOLD_X86)
/// True when this CPU can run fold_blocks_512 (VPCLMULQDQ with AVX-512; CPUID, cached).
bool fold512_available() noexcept;
/// As fold_blocks, sixteen 128-bit lanes at a time; n >= kMinBytes512.
std::uint32_t fold_blocks_512(std::uint32_t crc, const std::uint8_t* p, std::size_t n) noexcept;
#endif

// ---- Software model of the kernels: same steps, plain integers, constexpr. ----

struct U128 {
  std::uint64_t lo = 0;
  std::uint64_t hi = 0;
};

constexpr U128 xor128(U128 a, U128 b) noexcept { return {a.lo ^ b.lo, a.hi ^ b.hi}; }

/// Carry-less product of two 64-bit polynomials.
constexpr U128 clmul(std::uint64_t a, std::uint64_t b) noexcept {
  U128 r;
  for (unsigned i = 0; i < 64; ++i) {
    if ((b >> i) & 1u) {
      r.lo ^= a << i;
      if (i != 0) r.hi ^= a >> (64 - i);
    }
  }
  return r;
}

constexpr U128 model_load(const std::uint8_t* p) noexcept { return {load_be64(p + 8), load_be64(p)}; }

constexpr U128 model_fold(U128 a, std::uint64_t k_lo, std::uint64_t k_hi) noexcept {
  return xor128(clmul(a.lo, k_lo), clmul(a.hi, k_hi));
}

/// R * x^32 mod P.
constexpr std::uint32_t model_reduce(U128 r) noexcept {
  U128 t = clmul(r.hi, kReduce96);                        // degree < 95
  t = xor128(t, U128{r.lo << 32, r.lo >> 32});            // + L * x^32, degree < 96
  U128 u = clmul(t.hi, kReduce64);                        // bits 64..95 times x^64, degree < 63
  u.lo ^= t.lo;                                           // degree < 64
  const std::uint64_t q = clmul(u.lo >> 32, kBarrettMu).lo >> 32;  // floor(u / P)
  return static_cast<std::uint32_t>(u.lo ^ clmul(q, kPoly33).lo);  // u - q * P
}

/// What fold_blocks computes, for compile-time proof.
constexpr std::uint32_t model_fold_blocks(std::uint32_t crc, const std::uint8_t* p, std::size_t n) noexcept {
  U128 x[4] = {model_load(p), model_load(p + 16), model_load(p + 32), model_load(p + 48)};
  x[0].hi ^= static_cast<std::uint64_t>(crc) << 32;  // the register enters as the first 4 bytes
  p += 64;
  n -= 64;
  for (; n >= 64; p += 64, n -= 64) {
    for (int i = 0; i < 4; ++i) x[i] = xor128(model_fold(x[i], kFold512, kFold576), model_load(p + 16 * i));
  }
  U128 r = x[0];
  for (int i = 1; i < 4; ++i) r = xor128(model_fold(r, kFold128, kFold192), x[i]);
  for (; n >= 16; p += 16, n -= 16) r = xor128(model_fold(r, kFold128, kFold192), model_load(p));
  return model_reduce(r);
}

/// What fold_blocks_512 computes (n >= kMinBytes512), lane by lane, for compile-time proof.
constexpr std::uint32_t model_fold_blocks_512(std::uint32_t crc, const std::uint8_t* p, std::size_t n) noexcept {
  U128 x[16] = {};
  for (int i = 0; i < 16; ++i) x[i] = model_load(p + 16 * i);
  x[0].hi ^= static_cast<std::uint64_t>(crc) << 32;
  p += 256;
  n -= 256;
  for (; n >= 256; p += 256, n -= 256) {
    for (int i = 0; i < 16; ++i) x[i] = xor128(model_fold(x[i], kFold2048, kFold2112), model_load(p + 16 * i));
  }
  U128 r{};
  for (unsigned i = 0; i < 16; ++i) r = xor128(r, model_fold(x[i], kLaneFolds.lo[i], kLaneFolds.hi[i]));
  for (; n >= 16; p += 16, n -= 16) r = xor128(model_fold(r, kFold128, kFold192), model_load(p));
  return model_reduce(r);
}

}  // namespace hesai::crc32_fold
