// CRC-32/MPEG-2: polynomial 0x04C11DB7, initial value 0xFFFFFFFF, not reflected (most significant
// bit first), no final xor. Check value: "123456789" -> 0x0376E6E7. The QT128C2X guards its body,
// functional-safety section and tail with it (stored as u32 little-endian after each).
//
// Contract: every function is reentrant and thread-safe (constant tables in flash,
// kCrc32Mpeg2Slices KiB of them, see HESAI_CRC_SLICING in hesai/config.h); a Crc32Mpeg2 is 4 bytes,
// one per message. Cost: linear in the length, no allocation.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/bytes.h"
#include "hesai/config.h"

#if HESAI_CRC32_ALT
/// The platform's CRC-32/MPEG-2 (hesai/config.h, HESAI_CRC32_ALT): feeds `size` >= 1 bytes into the
/// register `crc` and returns the new register.
extern "C" std::uint32_t hesai_crc32_mpeg2_alt(std::uint32_t crc, const std::uint8_t* data, std::size_t size) noexcept;
#endif

namespace hesai {

/// Generator polynomial, x^32 implied (x^32 + x^26 + x^23 + ... + x + 1).
inline constexpr std::uint32_t kCrc32Mpeg2Poly = 0x04C11DB7u;
/// Register value before the first byte; also the CRC of the empty message.
inline constexpr std::uint32_t kCrc32Mpeg2Init = 0xFFFFFFFFu;

/// The definition, one bit at a time: feeds `n` bytes at `p` (most significant bit of each byte
/// first) into the register `crc` and returns the new register. The reference for every other path.
constexpr std::uint32_t crc32_mpeg2_bitwise(std::uint32_t crc, const std::uint8_t* p, std::size_t n) noexcept {
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= static_cast<std::uint32_t>(p[i]) << 24;
    for (int bit = 0; bit < 8; ++bit) {
      crc = (crc & 0x80000000u) != 0 ? (crc << 1) ^ kCrc32Mpeg2Poly : crc << 1;
    }
  }
  return crc;
}

/// Byte table, built from the polynomial: entry b is the register that a byte b yields from a
/// zero register. One step: crc = (crc << 8) ^ table[(crc >> 24) ^ byte].
constexpr std::array<std::uint32_t, 256> crc32_mpeg2_make_table() noexcept {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t b = 0; b < 256; ++b) {
    const std::uint8_t byte = static_cast<std::uint8_t>(b);
    t[b] = crc32_mpeg2_bitwise(0, &byte, 1);
  }
  return t;
}

/// Number of slicing tables, 1 KiB each (HESAI_CRC_SLICING in hesai/config.h: 16 on 64-bit
/// targets, 8 on 32-bit ones, or 4 or 1 where flash is scarce): the slicing path consumes this many
/// bytes per step. With 1 it is the byte table.
inline constexpr std::size_t kCrc32Mpeg2Slices = HESAI_CRC_SLICING;

/// Slicing tables: table k, entry b is the register that byte b followed by k zero bytes yields
/// from a zero register (table 0 is the byte table, the only one the table path uses).
constexpr std::array<std::array<std::uint32_t, 256>, kCrc32Mpeg2Slices> crc32_mpeg2_make_slicing_tables() noexcept {
  std::array<std::array<std::uint32_t, 256>, kCrc32Mpeg2Slices> t{};
  t[0] = crc32_mpeg2_make_table();
  for (std::size_t k = 1; k < kCrc32Mpeg2Slices; ++k) {
    for (std::size_t b = 0; b < 256; ++b) {
      const std::uint32_t prev = t[k - 1][b];
      t[k][b] = (prev << 8) ^ t[0][prev >> 24];  // one more zero byte
    }
  }
  return t;
}

/// Feeds `data` into the register `crc` (start from kCrc32Mpeg2Init) with the fastest path this
/// CPU has (carry-less multiply folding when available and the input is long, else slicing).
/// Split input gives the same result as one call over the whole.
std::uint32_t crc32_mpeg2_update(std::uint32_t crc, ByteView data) noexcept;

/// CRC-32/MPEG-2 of `data`: crc32_mpeg2_update(kCrc32Mpeg2Init, data).
std::uint32_t crc32_mpeg2(ByteView data) noexcept;

/// Implementations, selectable for tests and benchmarks. All give the same result.
enum class CrcPath : std::uint8_t {
  bitwise,   ///< the definition, 8 shifts per byte
  table,     ///< one 256-entry table lookup per byte
  slicing,   ///< slicing-by-kCrc32Mpeg2Slices: a table lookup per byte, one dependent step per 16, 8 or 4 bytes (1: as table)
  hardware,  ///< carry-less multiply folding: 512-bit VPCLMULQDQ (x86-64 with AVX-512, 256 bytes
             ///< and more), else PCLMULQDQ (x86-64) or PMULL (AArch64); slicing when unavailable or short
  hardware_128,  ///< the 128-bit PCLMULQDQ/PMULL folding even where VPCLMULQDQ is present (tests, benchmarks)
};

/// crc32_mpeg2_update through one chosen path.
std::uint32_t crc32_mpeg2_update(CrcPath path, std::uint32_t crc, ByteView data) noexcept;

/// True when CrcPath::hardware really uses carry-less multiplication on this CPU
/// (x86-64: detected once by CPUID; AArch64: chosen at compile time by __ARM_FEATURE_CRYPTO/AES),
/// or the platform's function (HESAI_CRC32_ALT).
bool crc32_hardware_available() noexcept;

/// The code crc32_mpeg2() runs on this CPU for inputs of 256 bytes and more: "vpclmulqdq"
/// (512-bit folding, x86-64 with AVX-512), "pclmulqdq" (x86-64), "pmull" (AArch64), "slicing"
/// (kCrc32Mpeg2Slices tables), "table" (HESAI_CRC_SLICING 1) or "alt" (the platform's function,
/// HESAI_CRC32_ALT). A static string.
const char* crc32_path_name() noexcept;

/// Streaming CRC-32/MPEG-2 over pieces of a message. No heap; copy freely.
class Crc32Mpeg2 {
 public:
  /// Feeds the next piece of the message.
  void update(ByteView data) noexcept { crc_ = crc32_mpeg2_update(crc_, data); }
  /// CRC of everything fed since construction or reset().
  constexpr std::uint32_t value() const noexcept { return crc_; }
  /// Starts a new message.
  constexpr void reset() noexcept { crc_ = kCrc32Mpeg2Init; }

 private:
  std::uint32_t crc_ = kCrc32Mpeg2Init;
};

}  // namespace hesai
