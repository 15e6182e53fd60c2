// SHA-256 (FIPS 180-4): a portable compression function and, where the CPU has them, the
// SHA instructions (x86-64 SHA-NI chosen at run time, ARMv8 SHA-2 chosen at compile time).
#include "hesai/sha256.h"

#include <cstring>

#include "../base/compiler.h"
#include "hesai/ct.h"

// With HESAI_SHA256_ALT the platform's function replaces the instructions.
#if HESAI_SHA256_ALT
#elif defined(__x86_64__) && HESAI_GNU
#define HESAI_SHA256_X86 1
#include <immintrin.h>

#include "../base/cpu_x86.h"
#elif (defined(__ARM_FEATURE_SHA2) || defined(__ARM_FEATURE_CRYPTO)) && !defined(__ARM_BIG_ENDIAN)
#define HESAI_SHA256_ARM 1
#include <arm_neon.h>
#endif

namespace hesai {
namespace {

// FIPS 180-4 section 4.2.2: the first 32 bits of the fractional parts of the cube roots of the
// first 64 primes.
constexpr std::uint32_t kK[64] = {
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
    0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
    0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
    0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2,
};

// FIPS 180-4 section 5.3.3: the first 32 bits of the fractional parts of the square roots of
// the first 8 primes.
constexpr std::uint32_t kInitialState[8] = {
    0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a, 0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19,
};

constexpr std::uint32_t rotr(std::uint32_t x, unsigned n) { return (x >> n) | (x << (32 - n)); }

// One round of FIPS 180-4 section 6.2.2 step 3. Instead of shifting the eight working
// variables, the caller rotates the arguments: after the round, `h` holds the new `a` and `d`
// the new `e`. Always inlined: as a call (-Os) it would force the eight variables into memory.
HESAI_ALWAYS_INLINE inline void one_round(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t& d, std::uint32_t e,
                      std::uint32_t f, std::uint32_t g, std::uint32_t& h, std::uint32_t k_plus_w) noexcept {
  const std::uint32_t t1 = h + (rotr(e, 6) ^ rotr(e, 11) ^ rotr(e, 25)) + ((e & f) ^ (~e & g)) + k_plus_w;
  const std::uint32_t t2 = (rotr(a, 2) ^ rotr(a, 13) ^ rotr(a, 22)) + ((a & b) ^ (a & c) ^ (b & c));
  d += t1;
  h = t1 + t2;
}

// FIPS 180-4 section 6.2.2, with the message schedule kept in a ring of 16 words.
void compress_portable(std::uint32_t state[8], const std::uint8_t* p, std::size_t nblocks) noexcept {
  std::uint32_t w[16];
  for (; nblocks > 0; --nblocks, p += kSha256BlockSize) {
    for (std::size_t t = 0; t < 16; ++t) w[t] = load_be32(p + 4 * t);
    std::uint32_t a = state[0], b = state[1], c = state[2], d = state[3];
    std::uint32_t e = state[4], f = state[5], g = state[6], h = state[7];
    // W[t] for t >= 16: s1(W[t-2]) + W[t-7] + s0(W[t-15]) + W[t-16], written over W[t-16].
    auto schedule = [&w](std::size_t t) HESAI_ALWAYS_INLINE {
      if (t >= 16) {
        const std::uint32_t w15 = w[(t + 1) & 15], w2 = w[(t + 14) & 15];
        w[t & 15] += (rotr(w15, 7) ^ rotr(w15, 18) ^ (w15 >> 3)) + w[(t + 9) & 15] +
                     (rotr(w2, 17) ^ rotr(w2, 19) ^ (w2 >> 10));
      }
      return kK[t] + w[t & 15];
    };
    for (std::size_t t = 0; t < 64; t += 8) {
      one_round(a, b, c, d, e, f, g, h, schedule(t));
      one_round(h, a, b, c, d, e, f, g, schedule(t + 1));
      one_round(g, h, a, b, c, d, e, f, schedule(t + 2));
      one_round(f, g, h, a, b, c, d, e, schedule(t + 3));
      one_round(e, f, g, h, a, b, c, d, schedule(t + 4));
      one_round(d, e, f, g, h, a, b, c, schedule(t + 5));
      one_round(c, d, e, f, g, h, a, b, schedule(t + 6));
      one_round(b, c, d, e, f, g, h, a, schedule(t + 7));
    }
    state[0] += a;
    state[1] += b;
    state[2] += c;
    state[3] += d;
    state[4] += e;
    state[5] += f;
    state[6] += g;
    state[7] += h;
  }
  secure_wipe(w, sizeof w);  // the schedule holds message words (HMAC: key material)
}

#if defined(HESAI_SHA256_X86)

#define HESAI_SHA_NI __attribute__((target("sha,sse4.1,ssse3")))

HESAI_SHA_NI inline __m128i load128(const void* p) noexcept {
  __m128i v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
HESAI_SHA_NI inline void store128(void* p, __m128i v) noexcept { std::memcpy(p, &v, sizeof v); }

// SHA-NI keeps the state in two vectors, ABEF and CDGH (variable names list lanes 3..0, so
// abef holds A in lane 3 and F in lane 0).

// Rounds 4g..4g+3 on schedule words w = W[4g..4g+3]. Each sha256rnds2 runs two rounds and
// returns the new ABEF; the old ABEF is then the new CDGH, so the two swap roles in between.
HESAI_SHA_NI inline void rounds4(__m128i& abef, __m128i& cdgh, __m128i w, std::size_t g) noexcept {
  const __m128i wk = _mm_add_epi32(w, load128(&kK[4 * g]));
  cdgh = _mm_sha256rnds2_epu32(cdgh, abef, wk);
  abef = _mm_sha256rnds2_epu32(abef, cdgh, _mm_shuffle_epi32(wk, 0x0E));
}

// The next four schedule words from the last sixteen (w0 oldest):
// W[t] = s1(W[t-2]) + W[t-7] + s0(W[t-15]) + W[t-16].
HESAI_SHA_NI inline __m128i schedule4(__m128i w0, __m128i w1, __m128i w2, __m128i w3) noexcept {
  const __m128i t = _mm_add_epi32(_mm_sha256msg1_epu32(w0, w1), _mm_alignr_epi8(w3, w2, 4));
  return _mm_sha256msg2_epu32(t, w3);
}

HESAI_SHA_NI void compress_x86(std::uint32_t state[8], const std::uint8_t* p,
                               std::size_t nblocks) noexcept {
  const __m128i bswap32 = _mm_set_epi8(12, 13, 14, 15, 8, 9, 10, 11, 4, 5, 6, 7, 0, 1, 2, 3);
  const __m128i cdab = _mm_shuffle_epi32(load128(state), 0xB1);
  const __m128i efgh = _mm_shuffle_epi32(load128(state + 4), 0x1B);
  __m128i abef = _mm_alignr_epi8(cdab, efgh, 8);
  __m128i cdgh = _mm_blend_epi16(efgh, cdab, 0xF0);

  for (; nblocks > 0; --nblocks, p += kSha256BlockSize) {
    const __m128i abef0 = abef, cdgh0 = cdgh;
    __m128i w0 = _mm_shuffle_epi8(load128(p), bswap32);
    __m128i w1 = _mm_shuffle_epi8(load128(p + 16), bswap32);
    __m128i w2 = _mm_shuffle_epi8(load128(p + 32), bswap32);
    __m128i w3 = _mm_shuffle_epi8(load128(p + 48), bswap32);
    for (std::size_t g = 0; g < 16; g += 4) {
      if (g != 0) w0 = schedule4(w0, w1, w2, w3);
      rounds4(abef, cdgh, w0, g);
      if (g != 0) w1 = schedule4(w1, w2, w3, w0);
      rounds4(abef, cdgh, w1, g + 1);
      if (g != 0) w2 = schedule4(w2, w3, w0, w1);
      rounds4(abef, cdgh, w2, g + 2);
      if (g != 0) w3 = schedule4(w3, w0, w1, w2);
      rounds4(abef, cdgh, w3, g + 3);
    }
    abef = _mm_add_epi32(abef, abef0);
    cdgh = _mm_add_epi32(cdgh, cdgh0);
  }

  const __m128i feba = _mm_shuffle_epi32(abef, 0x1B);
  const __m128i dchg = _mm_shuffle_epi32(cdgh, 0xB1);
  store128(state, _mm_blend_epi16(feba, dchg, 0xF0));   // dcba
  store128(state + 4, _mm_alignr_epi8(dchg, feba, 8));  // hgfe
}

#elif defined(HESAI_SHA256_ARM)

// ARMv8 SHA-2: the state stays {A, B, C, D} and {E, F, G, H}.

// Rounds 4g..4g+3 on schedule words w = W[4g..4g+3].
inline void rounds4(uint32x4_t& abcd, uint32x4_t& efgh, uint32x4_t w, std::size_t g) noexcept {
  const uint32x4_t wk = vaddq_u32(w, vld1q_u32(&kK[4 * g]));
  const uint32x4_t abcd_in = abcd;
  abcd = vsha256hq_u32(abcd, efgh, wk);
  efgh = vsha256h2q_u32(efgh, abcd_in, wk);
}

// The next four schedule words from the last sixteen (w0 oldest).
inline uint32x4_t schedule4(uint32x4_t w0, uint32x4_t w1, uint32x4_t w2, uint32x4_t w3) noexcept {
  return vsha256su1q_u32(vsha256su0q_u32(w0, w1), w2, w3);
}

inline uint32x4_t load_be32x4(const std::uint8_t* p) noexcept {
  return vreinterpretq_u32_u8(vrev32q_u8(vld1q_u8(p)));
}

void compress_arm(std::uint32_t state[8], const std::uint8_t* p, std::size_t nblocks) noexcept {
  uint32x4_t abcd = vld1q_u32(state), efgh = vld1q_u32(state + 4);
  for (; nblocks > 0; --nblocks, p += kSha256BlockSize) {
    const uint32x4_t abcd0 = abcd, efgh0 = efgh;
    uint32x4_t w0 = load_be32x4(p), w1 = load_be32x4(p + 16);
    uint32x4_t w2 = load_be32x4(p + 32), w3 = load_be32x4(p + 48);
    for (std::size_t g = 0; g < 16; g += 4) {
      if (g != 0) w0 = schedule4(w0, w1, w2, w3);
      rounds4(abcd, efgh, w0, g);
      if (g != 0) w1 = schedule4(w1, w2, w3, w0);
      rounds4(abcd, efgh, w1, g + 1);
      if (g != 0) w2 = schedule4(w2, w3, w0, w1);
      rounds4(abcd, efgh, w2, g + 2);
      if (g != 0) w3 = schedule4(w3, w0, w1, w2);
      rounds4(abcd, efgh, w3, g + 3);
    }
    abcd = vaddq_u32(abcd, abcd0);
    efgh = vaddq_u32(efgh, efgh0);
  }
  vst1q_u32(state, abcd);
  vst1q_u32(state + 4, efgh);
}

#endif

Sha256Path usable(Sha256Path path) noexcept {
  return path == Sha256Path::hardware && sha256_hardware_available() ? Sha256Path::hardware
                                                                       : Sha256Path::portable;
}

}  // namespace

bool sha256_hardware_available() noexcept {
#if HESAI_SHA256_ALT
  return true;
#elif defined(HESAI_SHA256_X86)
  return detail::x86_has(detail::X86Feature::sha_ni);
#elif defined(HESAI_SHA256_ARM)
  return true;
#else
  return false;
#endif
}

Sha256Path sha256_best_path() noexcept { return usable(Sha256Path::hardware); }

const char* sha256_path_name() noexcept {
  if (sha256_best_path() == Sha256Path::portable) return "portable";
#if HESAI_SHA256_ALT
  return "alt";
#elif defined(HESAI_SHA256_ARM)
  return "armv8-sha2";
#else
  return "sha-ni";
#endif
}

void sha256_compress(Sha256Path path, std::uint32_t state[8], const std::uint8_t* blocks,
                     std::size_t nblocks) noexcept {
  if (nblocks == 0) return;
#if HESAI_SHA256_ALT
  if (path == Sha256Path::hardware) return hesai_sha256_compress_alt(state, blocks, nblocks);
#elif defined(HESAI_SHA256_X86)
  if (usable(path) == Sha256Path::hardware) return compress_x86(state, blocks, nblocks);
#elif defined(HESAI_SHA256_ARM)
  if (path == Sha256Path::hardware) return compress_arm(state, blocks, nblocks);
#else
  (void)path;
#endif
  compress_portable(state, blocks, nblocks);
}

Sha256::Sha256() noexcept : Sha256(sha256_best_path()) {}

Sha256::Sha256(Sha256Path path) noexcept : path_(usable(path)) { reset(); }

Sha256::~Sha256() {
  secure_wipe(state_, sizeof state_);
  secure_wipe(block_, sizeof block_);
}

void Sha256::reset(Sha256Path path) noexcept {
  path_ = usable(path);
  reset();
}

void Sha256::reset() noexcept {
  std::memcpy(state_, kInitialState, sizeof state_);
  length_ = 0;
  secure_wipe(block_, sizeof block_);
}

void Sha256::update(ByteView data) noexcept {
  const std::uint8_t* p = data.data;
  std::size_t n = data.size;
  if (n == 0) return;
  std::size_t used = static_cast<std::size_t>(length_ % kSha256BlockSize);
  length_ += n;
  if (used != 0) {  // top up the buffered block first
    const std::size_t take = n < kSha256BlockSize - used ? n : kSha256BlockSize - used;
    std::memcpy(block_ + used, p, take);
    p += take;
    n -= take;
    if (used + take < kSha256BlockSize) return;
    sha256_compress(path_, state_, block_, 1);
  }
  const std::size_t whole = n / kSha256BlockSize;
  sha256_compress(path_, state_, p, whole);  // whole blocks straight from the input
  p += whole * kSha256BlockSize;
  n -= whole * kSha256BlockSize;
  if (n != 0) std::memcpy(block_, p, n);
}

// FIPS 180-4 section 5.1.1: append 0x80, zeros to 56 mod 64, then the length in bits (64-bit
// big-endian).
void Sha256::finish(std::uint8_t out[kSha256Size]) noexcept {
  std::size_t used = static_cast<std::size_t>(length_ % kSha256BlockSize);
  block_[used++] = 0x80;
  if (used > kSha256BlockSize - 8) {
    std::memset(block_ + used, 0, kSha256BlockSize - used);
    sha256_compress(path_, state_, block_, 1);
    used = 0;
  }
  std::memset(block_ + used, 0, kSha256BlockSize - 8 - used);
  store_be64(block_ + kSha256BlockSize - 8, length_ << 3);
  sha256_compress(path_, state_, block_, 1);
  for (std::size_t i = 0; i < 8; ++i) store_be32(out + 4 * i, state_[i]);
  reset();
}

void sha256(ByteView data, std::uint8_t out[kSha256Size]) noexcept {
  Sha256 h;
  h.update(data);
  h.finish(out);
}

}  // namespace hesai
