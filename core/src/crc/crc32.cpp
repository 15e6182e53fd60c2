// CRC-32/MPEG-2: the table and slicing paths, the dispatcher, and compile-time proofs of every
// path against the bitwise definition.
#include "hesai/crc32.h"

#include "../base/compiler.h"
#include "crc32_fold.h"
#include "hesai/bytes.h"

namespace hesai {
namespace {

// kCrc32Mpeg2Slices KiB of flash; table 0 is the byte table of the table path.
constexpr std::array<std::array<std::uint32_t, 256>, kCrc32Mpeg2Slices> kSlicing =
    crc32_mpeg2_make_slicing_tables();

constexpr std::uint32_t table_update(std::uint32_t crc, const std::uint8_t* p, std::size_t n) noexcept {
  for (std::size_t i = 0; i < n; ++i) crc = (crc << 8) ^ kSlicing[0][(crc >> 24) ^ p[i]];
  return crc;
}

// The lookups of one big-endian word w whose first byte is followed by `after` more bytes of the
// step: byte j of the word uses slicing table after - j. Two pairs, combined as a tree.
// A big-endian word, always inlined (load_be32 is a call at -Os): ldr + rev on ARMv7-M.
[[maybe_unused]] HESAI_ALWAYS_INLINE constexpr std::uint32_t be32(const std::uint8_t* p) noexcept {
  return static_cast<std::uint32_t>(p[0]) << 24 | static_cast<std::uint32_t>(p[1]) << 16 |
         static_cast<std::uint32_t>(p[2]) << 8 | static_cast<std::uint32_t>(p[3]);
}

// `t[k]` is slicing table k: ConstTables (the constants), or RegisterTables below.
struct ConstTables {
  constexpr const std::uint32_t* operator[](std::size_t k) const noexcept { return kSlicing[k].data(); }
};

template <typename Tables>
HESAI_ALWAYS_INLINE constexpr std::uint32_t word_lookup(const Tables& t, std::uint32_t w, std::size_t after) noexcept {
  return (t[after][w >> 24] ^ t[after - 1][(w >> 16) & 0xFFu]) ^
         (t[after - 2][(w >> 8) & 0xFFu] ^ t[after - 3][w & 0xFFu]);
}

// One step over `step` bytes (a multiple of 4, at most kCrc32Mpeg2Slices), read as big-endian
// words with shifts (no aligned or host-order loads). The register is xored into the first word;
// byte j of the step, followed by step - 1 - j more bytes, contributes slicing table step - 1 - j.
// Only the first word depends on the register: the other words' lookups run while it waits for
// the previous step. That one chain (xor, lookup, xor) per step is what bounds the speed, so
// more bytes per step is faster. (Unused with HESAI_CRC_SLICING 1, the byte table alone.) Both
// always inlined, so that `step` and `after` are constants and every table address folds: at -Os
// GCC kept them as calls with run-time table arithmetic, 11 instructions a byte on a Cortex-M4F.
template <typename Tables>
[[maybe_unused]] HESAI_ALWAYS_INLINE constexpr std::uint32_t slicing_step(const Tables& t, std::uint32_t crc,
                                                                         const std::uint8_t* p, std::size_t step) noexcept {
  std::uint32_t ahead = 0;
  for (std::size_t w = 4; w < step; w += 4) ahead ^= word_lookup(t, be32(p + w), step - 1 - w);
  return word_lookup(t, crc ^ be32(p), step - 1) ^ ahead;
}

template <typename Tables = ConstTables>
constexpr std::uint32_t slicing_update(std::uint32_t crc, const std::uint8_t* p, std::size_t n,
                                       const Tables& t = Tables{}) noexcept {
  constexpr std::size_t kStep = kCrc32Mpeg2Slices;
  static_assert(kStep == 1 || kStep % 4 == 0, "whole words per step, or the byte table alone");
  if constexpr (kStep >= 4) {
    for (; n >= kStep; p += kStep, n -= kStep) crc = slicing_step(t, crc, p, kStep);
    // The rest (short packet sections such as the QT128 tail): a step of 8 and one of 4 where
    // they fit, as the same tables serve any step, then single bytes.
    if (kStep > 8 && n >= 8) {
      crc = slicing_step(t, crc, p, 8);
      p += 8;
      n -= 8;
    }
    if (kStep > 4 && n >= 4) {
      crc = slicing_step(t, crc, p, 4);
      p += 4;
      n -= 4;
    }
  }
  return table_update(crc, p, n);
}

#if HESAI_GNU && defined(__thumb2__) && HESAI_CRC_SLICING >= 4
// Thumb-2 (ARMv7-M, ARMv7-A): every table's address in a register of its own. With the constant
// addresses GCC reaches tables 1-3 of each 4 KiB as base + offset, an add before each of those
// lookups; an empty asm hides that the addresses are related, so each lookup is one
// register-indexed load (QT128 validate on a Cortex-M4F: 7 235 -> 6 869 instructions).
struct RegisterTables {
  const std::uint32_t* t[kCrc32Mpeg2Slices];
  RegisterTables() noexcept {
    for (std::size_t k = 0; k < kCrc32Mpeg2Slices; ++k) {
      t[k] = kSlicing[k].data();
      __asm__("" : "+r"(t[k]));
    }
  }
  const std::uint32_t* operator[](std::size_t k) const noexcept { return t[k]; }
};
std::uint32_t slicing_run(std::uint32_t crc, const std::uint8_t* p, std::size_t n) noexcept {
  return slicing_update(crc, p, n, RegisterTables{});
}
#else
std::uint32_t slicing_run(std::uint32_t crc, const std::uint8_t* p, std::size_t n) noexcept {
  return slicing_update(crc, p, n);
}
#endif

// Short sections (below crc32_fold::kMinBytes; the QT128's CRC2 over 12 bytes and CRC3 over 30)
// on x86-64: each step any length from 4 to kCrc32Mpeg2Slices bytes, byte j of a k-byte step by
// table k - 1 - j (the register xored into its first 4 bytes, as slicing_step), so that 30 bytes
// are 2 dependent steps (14, then 16) where slicing_update takes 5 (16, 8, 4, then 2 single
// bytes) and 12 bytes one where it takes 2. The steps' lookups are as many; the chain is shorter.
// Measured: CRC2 and CRC3 were 18.5 of the QT128C2X validate's 82 ns.
[[maybe_unused]] constexpr std::uint32_t any_step(std::uint32_t crc, const std::uint8_t* p, std::size_t k) noexcept {
  std::uint32_t r = 0;
  for (std::size_t j = 0; j < k; ++j) {
    const std::uint32_t b = p[j] ^ (j < 4 ? (crc >> (24 - 8 * j)) & 0xFFu : 0u);
    r ^= kSlicing[k - 1 - j][b];
  }
  return r;
}
// any_step with k a constant (4..16; each unrolled into independent lookups), chosen by a switch.
template <std::size_t K>
HESAI_ALWAYS_INLINE constexpr std::uint32_t step_of(std::uint32_t crc, const std::uint8_t* p) noexcept {
  return any_step(crc, p, K);
}
[[maybe_unused]] constexpr std::uint32_t any_step_switch(std::uint32_t crc, const std::uint8_t* p, std::size_t k) noexcept {
  switch (k) {  // k < kCrc32Mpeg2Slices
    case 4: return step_of<4>(crc, p);
    case 5: return step_of<5>(crc, p);
    case 6: return step_of<6>(crc, p);
    case 7: return step_of<7>(crc, p);
    default: break;
  }
  if constexpr (kCrc32Mpeg2Slices == 16) {
    switch (k) {
      case 8: return step_of<8>(crc, p);
      case 9: return step_of<9>(crc, p);
      case 10: return step_of<10>(crc, p);
      case 11: return step_of<11>(crc, p);
      case 12: return step_of<12>(crc, p);
      case 13: return step_of<13>(crc, p);
      case 14: return step_of<14>(crc, p);
      case 15: return step_of<15>(crc, p);
      default: break;
    }
  }
  return any_step(crc, p, k);
}
[[maybe_unused]] constexpr std::uint32_t short_update(std::uint32_t crc, const std::uint8_t* p, std::size_t n) noexcept {
  constexpr std::size_t kStep = kCrc32Mpeg2Slices;
  if constexpr (kStep >= 8) {
    if (n < 4) return table_update(crc, p, n);
    // What is over whole steps first: r bytes, or, when r is 1..3, r + 4 and then kStep - 4.
    const std::size_t r = n % kStep;
    if (r != 0 && r < 4) {
      crc = any_step_switch(crc, p, r + 4);
      crc = any_step(crc, p + r + 4, kStep - 4);
      p += r + kStep;
      n -= r + kStep;
    } else if (r != 0) {
      crc = any_step_switch(crc, p, r);
      p += r;
      n -= r;
    }
    for (; n != 0; p += kStep, n -= kStep) crc = any_step(crc, p, kStep);
    return crc;
  }
  return slicing_update(crc, p, n);
}

// ---- Compile-time proofs ----

constexpr std::uint8_t kCheck[9] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
static_assert(crc32_mpeg2_bitwise(kCrc32Mpeg2Init, kCheck, 9) == 0x0376E6E7u, "check value, definition");
static_assert(table_update(kCrc32Mpeg2Init, kCheck, 9) == 0x0376E6E7u, "check value, table");
static_assert(slicing_update(kCrc32Mpeg2Init, kCheck, 9) == 0x0376E6E7u, "check value, slicing");

// A pseudo-random message long enough for the four-way fold loop, its tail and the slicing tail.
struct Sample {
  std::uint8_t bytes[300] = {};
  constexpr Sample() {
    std::uint32_t s = 0x12345678u;
    for (std::uint8_t& b : bytes) {
      s = s * 1664525u + 1013904223u;  // LCG (Numerical Recipes)
      b = static_cast<std::uint8_t>(s >> 24);
    }
  }
};
constexpr Sample kSample{};
constexpr std::size_t kSampleSize = sizeof kSample.bytes;
constexpr std::uint32_t kSampleCrc = crc32_mpeg2_bitwise(kCrc32Mpeg2Init, kSample.bytes, kSampleSize);
static_assert(slicing_update(kCrc32Mpeg2Init, kSample.bytes, kSampleSize) == kSampleCrc, "slicing");

// The short path at every length up to 80, from two registers.
constexpr bool short_update_exact() {
  for (std::size_t n = 0; n <= 80; ++n) {
    if (short_update(kCrc32Mpeg2Init, kSample.bytes, n) != crc32_mpeg2_bitwise(kCrc32Mpeg2Init, kSample.bytes, n))
      return false;
    if (short_update(0x89ABCDEFu, kSample.bytes + 7, n) != crc32_mpeg2_bitwise(0x89ABCDEFu, kSample.bytes + 7, n))
      return false;
  }
  return true;
}
static_assert(short_update_exact(), "short sections, 0..80 B");

// The folding schemes and their constants, proven on the software models of the kernels (wide:
// the 512-bit one).
constexpr std::uint32_t model_update(std::uint32_t crc, const std::uint8_t* p, std::size_t n, bool wide = false) {
  const std::size_t folded = n & ~std::size_t{15};
  crc = wide ? crc32_fold::model_fold_blocks_512(crc, p, n) : crc32_fold::model_fold_blocks(crc, p, n);
  return slicing_update(crc, p + folded, n - folded);
}
static_assert(model_update(kCrc32Mpeg2Init, kSample.bytes, kSampleSize) == kSampleCrc, "folding, 300 B");
static_assert(model_update(kCrc32Mpeg2Init, kSample.bytes, 64) ==
                  crc32_mpeg2_bitwise(kCrc32Mpeg2Init, kSample.bytes, 64),
              "folding, 64 B");
static_assert(model_update(kCrc32Mpeg2Init, kSample.bytes, 143) ==
                  crc32_mpeg2_bitwise(kCrc32Mpeg2Init, kSample.bytes, 143),
              "folding, 143 B");
static_assert(model_update(0x89ABCDEFu, kSample.bytes + 3, 200) ==
                  crc32_mpeg2_bitwise(0x89ABCDEFu, kSample.bytes + 3, 200),
              "folding from any register");
// The 512-bit scheme: the 300-byte sample, one window, and one window and 31 bytes.
static_assert(model_update(kCrc32Mpeg2Init, kSample.bytes, kSampleSize, true) == kSampleCrc, "512-bit folding, 300 B");
static_assert(model_update(kCrc32Mpeg2Init, kSample.bytes, 256, true) ==
                  crc32_mpeg2_bitwise(kCrc32Mpeg2Init, kSample.bytes, 256),
              "512-bit folding, 256 B");
static_assert(model_update(0x89ABCDEFu, kSample.bytes + 5, 287, true) ==
                  crc32_mpeg2_bitwise(0x89ABCDEFu, kSample.bytes + 5, 287),
              "512-bit folding from any register");

// Folding by the widest kernel this CPU has (`widest`: the 512-bit one where there is one; else
// the 128-bit one), the last 0..15 bytes by slicing.
std::uint32_t hardware_update(std::uint32_t crc, const std::uint8_t* p, std::size_t n, bool widest) noexcept {
#if HESAI_CRC32_ALT
  (void)widest;
  return hesai_crc32_mpeg2_alt(crc, p, n);  // callers pass n >= 1
#else
#if defined(HESAI_CRC32_FOLD_X86) || defined(HESAI_CRC32_FOLD_ARM)
  if (n >= crc32_fold::kMinBytes && crc32_fold::fold_available()) {
    const std::size_t folded = n & ~std::size_t{15};
#if defined(HESAI_CRC32_FOLD_X86)
    if (widest && n >= crc32_fold::kMinBytes512 && crc32_fold::fold512_available())
      crc = crc32_fold::fold_blocks_512(crc, p, n);
    else
#endif
      crc = crc32_fold::fold_blocks(crc, p, n);
    p += folded;
    n -= folded;
  }
#endif
  (void)widest;
#if defined(HESAI_CRC32_FOLD_X86)
  return short_update(crc, p, n);
#else
  return slicing_run(crc, p, n);
#endif
#endif
}

}  // namespace

bool crc32_hardware_available() noexcept {
#if HESAI_CRC32_ALT
  return true;
#elif defined(HESAI_CRC32_FOLD_X86) || defined(HESAI_CRC32_FOLD_ARM)
  return crc32_fold::fold_available();
#else
  return false;
#endif
}

const char* crc32_path_name() noexcept {
#if HESAI_CRC32_ALT
  return "alt";
#elif defined(HESAI_CRC32_FOLD_X86)
  if (crc32_fold::fold_available()) return crc32_fold::fold512_available() ? "vpclmulqdq" : "pclmulqdq";
#elif defined(HESAI_CRC32_FOLD_ARM)
  if (crc32_fold::fold_available()) return "pmull";
#endif
  return kCrc32Mpeg2Slices == 1 ? "table" : "slicing";
}

std::uint32_t crc32_mpeg2_update(CrcPath path, std::uint32_t crc, ByteView data) noexcept {
  if (data.size == 0) return crc;  // data.data may be null
  switch (path) {
    case CrcPath::bitwise: return crc32_mpeg2_bitwise(crc, data.data, data.size);
    case CrcPath::table: return table_update(crc, data.data, data.size);
    case CrcPath::slicing: return slicing_run(crc, data.data, data.size);
    case CrcPath::hardware: return hardware_update(crc, data.data, data.size, true);
    case CrcPath::hardware_128: return hardware_update(crc, data.data, data.size, false);
  }
  return hardware_update(crc, data.data, data.size, true);
}

std::uint32_t crc32_mpeg2_update(std::uint32_t crc, ByteView data) noexcept {
  if (data.size == 0) return crc;
  return hardware_update(crc, data.data, data.size, true);
}

std::uint32_t crc32_mpeg2(ByteView data) noexcept { return crc32_mpeg2_update(kCrc32Mpeg2Init, data); }

}  // namespace hesai
