// CRC-32/MPEG-2 folding with PMULL on AArch64 (see crc32_fold.h for the mathematics). Compiled in
// when the target has the crypto/AES extension (-march=armv8-a+crypto or later); empty otherwise.
// (The ARMv8 CRC32 instructions compute the reflected CRC-32 and CRC-32C, not this CRC.)
#include "crc32_fold.h"

#if defined(HESAI_CRC32_FOLD_ARM)

#include <arm_neon.h>

namespace hesai::crc32_fold {
namespace {

// 16 bytes as a 128-bit big-endian number: byte 0's top bit becomes bit 127 (lane 1, bit 63).
inline uint64x2_t load_be128(const std::uint8_t* p) noexcept {
  const uint8x16_t v = vrev64q_u8(vld1q_u8(p));     // each half big-endian
  return vreinterpretq_u64_u8(vextq_u8(v, v, 8));  // first half on top
}

// Carry-less product of lane A of a and lane B of b.
template <int A, int B>
inline uint64x2_t clmul(uint64x2_t a, uint64x2_t b) noexcept {
  return vreinterpretq_u64_p128(
      vmull_p64(vgetq_lane_p64(vreinterpretq_p64_u64(a), A), vgetq_lane_p64(vreinterpretq_p64_u64(b), B)));
}

// a * x^T mod P, up to 95 bits: k holds x^T mod P (lane 0) and x^(T+64) mod P (lane 1).
inline uint64x2_t fold(uint64x2_t a, uint64x2_t k) noexcept {
  const uint64x2_t hi = vreinterpretq_u64_p128(vmull_high_p64(vreinterpretq_p64_u64(a), vreinterpretq_p64_u64(k)));
  return veorq_u64(clmul<0, 0>(a, k), hi);
}

inline uint64x2_t pair(std::uint64_t hi, std::uint64_t lo) noexcept {
  return vcombine_u64(vcreate_u64(lo), vcreate_u64(hi));
}

inline uint64x2_t low_qword(uint64x2_t v) noexcept { return vsetq_lane_u64(0, v, 1); }

// r * x^32 mod P.
inline std::uint32_t reduce(uint64x2_t r) noexcept {
  const uint64x2_t k = pair(kReduce64, kReduce96);
  const uint64x2_t zero = vdupq_n_u64(0);
  uint64x2_t t = clmul<1, 0>(r, k);                                              // high qword * x^96
  const uint64x2_t lo32 = vreinterpretq_u64_u8(vextq_u8(vreinterpretq_u8_u64(zero),
                                                        vreinterpretq_u8_u64(low_qword(r)), 12));
  t = veorq_u64(t, lo32);                                                        // + low qword * x^32
  uint64x2_t u = veorq_u64(clmul<1, 1>(t, k), low_qword(t));                     // < 64 bits
  const uint64x2_t b = pair(kPoly33, kBarrettMu);
  const uint64x2_t q_mu = clmul<0, 0>(vshrq_n_u64(u, 32), b);                   // (u >> 32) * mu
  const uint64x2_t q = vshrq_n_u64(q_mu, 32);                                    // floor(u / P)
  u = veorq_u64(u, clmul<0, 1>(q, b));                                           // u - q * P
  return static_cast<std::uint32_t>(vgetq_lane_u64(u, 0));
}

}  // namespace

bool fold_available() noexcept { return true; }

std::uint32_t fold_blocks(std::uint32_t crc, const std::uint8_t* p, std::size_t n) noexcept {
  HESAI_ASSERT(n >= kMinBytes);
  const uint64x2_t k512 = pair(kFold576, kFold512);
  const uint64x2_t k128 = pair(kFold192, kFold128);

  uint64x2_t x0 = veorq_u64(load_be128(p), pair(static_cast<std::uint64_t>(crc) << 32, 0));
  uint64x2_t x1 = load_be128(p + 16);
  uint64x2_t x2 = load_be128(p + 32);
  uint64x2_t x3 = load_be128(p + 48);
  p += 64;
  n -= 64;
  for (; n >= 64; p += 64, n -= 64) {
    x0 = veorq_u64(fold(x0, k512), load_be128(p));
    x1 = veorq_u64(fold(x1, k512), load_be128(p + 16));
    x2 = veorq_u64(fold(x2, k512), load_be128(p + 32));
    x3 = veorq_u64(fold(x3, k512), load_be128(p + 48));
  }
  x1 = veorq_u64(fold(x0, k128), x1);
  x2 = veorq_u64(fold(x1, k128), x2);
  x3 = veorq_u64(fold(x2, k128), x3);
  for (; n >= 16; p += 16, n -= 16) x3 = veorq_u64(fold(x3, k128), load_be128(p));
  return reduce(x3);
}

}  // namespace hesai::crc32_fold

#endif  // HESAI_CRC32_FOLD_ARM
