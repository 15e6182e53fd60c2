// Helpers for the SHA-256 / HMAC / HKDF tests: hex vectors and byte views.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hesai/bytes.h"

namespace hesai_test {

using Bytes = std::vector<std::uint8_t>;

/// Bytes from a hex string as printed in the RFCs ("0b0b..."); spaces are skipped.
inline Bytes from_hex(const std::string& hex) {
  auto nibble = [](char c) -> std::uint8_t {
    if (c >= '0' && c <= '9') return static_cast<std::uint8_t>(c - '0');
    if (c >= 'a' && c <= 'f') return static_cast<std::uint8_t>(c - 'a' + 10);
    return static_cast<std::uint8_t>(c - 'A' + 10);
  };
  Bytes out;
  std::string digits;
  for (char c : hex)
    if (c != ' ') digits += c;
  for (std::size_t i = 0; i + 1 < digits.size(); i += 2)
    out.push_back(static_cast<std::uint8_t>(nibble(digits[i]) << 4 | nibble(digits[i + 1])));
  return out;
}

inline Bytes from_text(const std::string& s) { return Bytes(s.begin(), s.end()); }

inline hesai::ByteView view(const Bytes& b) { return {b.data(), b.size()}; }
inline hesai::ByteView view(const Bytes& b, std::size_t off, std::size_t n) { return {b.data() + off, n}; }

/// Lower-case hex of `n` bytes, for readable failure messages.
inline std::string to_hex(const std::uint8_t* p, std::size_t n) {
  static const char digits[] = "0123456789abcdef";
  std::string s;
  for (std::size_t i = 0; i < n; ++i) {
    s += digits[p[i] >> 4];
    s += digits[p[i] & 15];
  }
  return s;
}
inline std::string to_hex(const Bytes& b) { return to_hex(b.data(), b.size()); }

/// Deterministic test bytes (xorshift32), so failures reproduce.
inline Bytes pseudo_random_bytes(std::size_t n, std::uint32_t seed) {
  Bytes out(n);
  std::uint32_t x = seed ? seed : 1;
  for (auto& b : out) {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    b = static_cast<std::uint8_t>(x >> 24);
  }
  return out;
}

}  // namespace hesai_test
