// CRC-32 as zlib, PNG and MCAP compute it (IEEE 802.3, reflected): the portable paths (a byte at
// a time; slicing-by-16, or by 8 on 32-bit targets), the choice of path, and the combination.
// The CPU kernels: crc32_ieee_x86.cpp (PCLMULQDQ), crc32_ieee_arm.cpp (ARMv8 CRC32).
#include "hesai_port/base/crc32_ieee.h"

#include <array>

#include "crc32_ieee_kernels.h"

namespace hesai::port {
namespace {

// CRC-32 (IEEE): the reflected polynomial, one table entry per byte value.
constexpr std::uint32_t kCrcPoly = 0xEDB88320u;

constexpr std::array<std::uint32_t, 256> make_crc_table() {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) != 0 ? (c >> 1) ^ kCrcPoly : c >> 1;
    t[i] = c;
  }
  return t;
}
constexpr std::array<std::uint32_t, 256> kCrcTable = make_crc_table();

// The register (the complemented CRC) a byte at a time.
std::uint32_t bytewise(std::uint32_t reg, const std::uint8_t* p, std::size_t n) noexcept {
  for (std::size_t i = 0; i < n; ++i) reg = kCrcTable[(reg ^ p[i]) & 0xFFu] ^ (reg >> 8);
  return reg;
}

constexpr std::uint32_t crc_of_text(const char* s) {
  std::uint32_t crc = ~0u;
  for (; *s != '\0'; ++s) crc = kCrcTable[(crc ^ static_cast<std::uint8_t>(*s)) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}
// The check value of the CRC catalogue's CRC-32/ISO-HDLC (the zlib CRC).
static_assert(crc_of_text("123456789") == 0xCBF43926u, "CRC-32 (IEEE) table");

// Slicing: table k, entry b is the register that byte b followed by k zero bytes gives from a
// zero register (table 0 is the byte table). 16 tables (16 KiB) on 64-bit targets, 8 on 32-bit.
constexpr std::size_t kSlices = sizeof(void*) >= 8 ? 16 : 8;
using SlicingTables = std::array<std::array<std::uint32_t, 256>, kSlices>;
constexpr SlicingTables make_slicing_tables() {
  SlicingTables t{};
  t[0] = kCrcTable;
  for (std::size_t k = 1; k < kSlices; ++k) {
    for (std::size_t b = 0; b < 256; ++b) t[k][b] = (t[k - 1][b] >> 8) ^ kCrcTable[t[k - 1][b] & 0xFFu];
  }
  return t;
}
constexpr SlicingTables kSlicing = make_slicing_tables();
// Byte 0x80 then a zero byte: the register after "\x80\0" is table 1's entry 0x80.
static_assert(kSlicing[1][0x80] == ((kCrcTable[0x80] >> 8) ^ kCrcTable[kCrcTable[0x80] & 0xFFu]));

// Little-endian 32-bit load from bytes, whatever the CPU's byte order (s390x is big-endian);
// compilers fold it into one load (a byte-reversed one on big-endian targets).
inline std::uint32_t load_le32(const std::uint8_t* p) noexcept {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

// The four bytes of w (first byte lowest), each through the table `k`, `k - 1`, `k - 2`, `k - 3`.
inline std::uint32_t slice4(std::uint32_t w, std::size_t k) noexcept {
  return kSlicing[k][w & 0xFFu] ^ kSlicing[k - 1][(w >> 8) & 0xFFu] ^ kSlicing[k - 2][(w >> 16) & 0xFFu] ^
         kSlicing[k - 3][w >> 24];
}

// A step of 8 bytes: the register is xored into the first four.
inline std::uint32_t step8(std::uint32_t reg, const std::uint8_t* p, std::size_t top) noexcept {
  return slice4(reg ^ load_le32(p), top) ^ slice4(load_le32(p + 4), top - 4);
}

// S bytes a step (one dependent chain: xor, table loads, xor), then 8, then a byte at a time.
template <std::size_t S>
std::uint32_t slicing_steps(std::uint32_t reg, const std::uint8_t* p, std::size_t n) noexcept {
  if constexpr (S == 16) {
    for (; n >= 16; p += 16, n -= 16) {
      reg = slice4(reg ^ load_le32(p), 15) ^ slice4(load_le32(p + 4), 11) ^ slice4(load_le32(p + 8), 7) ^
            slice4(load_le32(p + 12), 3);
    }
  }
  for (; n >= 8; p += 8, n -= 8) reg = step8(reg, p, 7);
  return bytewise(reg, p, n);
}

struct PathInfo {
  Crc32IeeePath best;
  bool pclmul;
};

// The one place that chooses: the CPU's kernel where it has one, else slicing.
PathInfo path_info() noexcept {
#if defined(HESAI_CRC32_IEEE_PCLMUL)
  const bool pclmul = crc32_ieee_kernels::pclmul_available();
  return {pclmul ? Crc32IeeePath::pclmul : Crc32IeeePath::slicing, pclmul};
#elif defined(HESAI_CRC32_IEEE_ARMV8)
  return {Crc32IeeePath::armv8, false};
#else
  return {Crc32IeeePath::slicing, false};
#endif
}

// The register through `path` (already known to be available).
std::uint32_t run(Crc32IeeePath path, std::uint32_t reg, const std::uint8_t* p, std::size_t n) noexcept {
  switch (path) {
    case Crc32IeeePath::bytewise: return bytewise(reg, p, n);
    case Crc32IeeePath::slicing: break;
    case Crc32IeeePath::pclmul:
#if defined(HESAI_CRC32_IEEE_PCLMUL)
      if (n >= crc32_ieee_kernels::kPclmulMinBytes) {
        const std::size_t blocks = n & ~std::size_t{15};
        reg = crc32_ieee_kernels::pclmul_blocks(reg, p, blocks);
        p += blocks;
        n -= blocks;
      }
#endif
      break;
    case Crc32IeeePath::armv8:
#if defined(HESAI_CRC32_IEEE_ARMV8)
      return crc32_ieee_kernels::armv8(reg, p, n);
#else
      break;
#endif
  }
  return crc32_ieee_kernels::slicing(reg, p, n);
}

// a * b modulo the CRC polynomial, both in the reflected representation (bit 31 is x^0).
constexpr std::uint32_t mult_mod_poly(std::uint32_t a, std::uint32_t b) {
  std::uint32_t product = 0;
  for (std::uint32_t m = 1u << 31; m != 0; m >>= 1) {
    if ((a & m) != 0) product ^= b;
    b = (b & 1u) != 0 ? (b >> 1) ^ kCrcPoly : b >> 1;  // b * x
  }
  return product;
}

}  // namespace

std::uint32_t crc32_ieee_kernels::slicing(std::uint32_t reg, const std::uint8_t* p, std::size_t n) noexcept {
  return slicing_steps<kSlices>(reg, p, n);
}

bool crc32_ieee_available(Crc32IeeePath path) noexcept {
  switch (path) {
    case Crc32IeeePath::bytewise:
    case Crc32IeeePath::slicing: return true;
    case Crc32IeeePath::pclmul: return path_info().pclmul;
    case Crc32IeeePath::armv8: return path_info().best == Crc32IeeePath::armv8;
  }
  return false;
}

Crc32IeeePath crc32_ieee_best_path() noexcept {
  static const Crc32IeeePath best = path_info().best;
  return best;
}

const char* crc32_ieee_path_name(Crc32IeeePath path) noexcept {
  switch (path) {
    case Crc32IeeePath::bytewise: return "bytewise";
    case Crc32IeeePath::slicing: return "slicing";
    case Crc32IeeePath::pclmul: return "pclmul";
    case Crc32IeeePath::armv8: return "armv8";
  }
  return "?";
}

std::uint32_t crc32_ieee(const void* data, std::size_t size, std::uint32_t crc) {
  return ~run(crc32_ieee_best_path(), ~crc, static_cast<const std::uint8_t*>(data), size);
}

std::uint32_t crc32_ieee(Crc32IeeePath path, const void* data, std::size_t size, std::uint32_t crc) {
  if (!crc32_ieee_available(path)) path = Crc32IeeePath::slicing;
  return ~run(path, ~crc, static_cast<const std::uint8_t*>(data), size);
}

std::uint32_t crc32_ieee_combine(std::uint32_t crc_a, std::uint32_t crc_b, std::uint64_t size_b) {
  // Appending B's bytes multiplies A's CRC register by x^(8 size_b): x^8, squared per bit of size_b.
  std::uint32_t shift = 1u << 31;        // x^0
  std::uint32_t square = 1u << (31 - 8);  // x^8
  for (; size_b != 0; size_b >>= 1) {
    if ((size_b & 1u) != 0) shift = mult_mod_poly(shift, square);
    square = mult_mod_poly(square, square);
  }
  return mult_mod_poly(shift, crc_a) ^ crc_b;
}

}  // namespace hesai::port
