// CRC-32 as zlib, PNG and MCAP compute it (IEEE 802.3, reflected).
#include "hesai_port/base/crc32_ieee.h"

#include <array>

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

constexpr std::uint32_t crc_update(std::uint32_t crc, const std::uint8_t* p, std::size_t n) {
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i) crc = kCrcTable[(crc ^ p[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

constexpr std::uint32_t crc_of_text(const char* s) {
  std::uint32_t crc = ~0u;
  for (; *s != '\0'; ++s) crc = kCrcTable[(crc ^ static_cast<std::uint8_t>(*s)) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}
// The check value of the CRC catalogue's CRC-32/ISO-HDLC (the zlib CRC).
static_assert(crc_of_text("123456789") == 0xCBF43926u, "CRC-32 (IEEE) table");

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

std::uint32_t crc32_ieee(const void* data, std::size_t size, std::uint32_t crc) {
  return crc_update(crc, static_cast<const std::uint8_t*>(data), size);
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
