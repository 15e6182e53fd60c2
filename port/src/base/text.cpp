// Text from elsewhere made safe to print (hesai_port/base/text.h).
#include "hesai_port/base/text.h"

#include <cstdint>

namespace hesai::port {
namespace {

constexpr char kHex[] = "0123456789abcdef";

void append_escape(std::string& out, const char* prefix, unsigned value) {
  out += prefix;
  out += kHex[(value >> 4) & 0xF];
  out += kHex[value & 0xF];
}

// The length of the well-formed UTF-8 sequence at s[at] (Unicode 15, table 3-7), with its code
// point in `cp`; 0 when the bytes there are not one.
std::size_t utf8_sequence(std::string_view s, std::size_t at, std::uint32_t& cp) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(s[at + i]); };
  const unsigned char b0 = byte(0);
  if (b0 < 0x80) {
    cp = b0;
    return 1;
  }
  // The sequence's length by its first byte, and the range of its second byte (no overlong
  // forms, no surrogates, nothing above U+10FFFF).
  std::size_t n = 0;
  unsigned char lo = 0x80, hi = 0xBF;
  if (b0 >= 0xC2 && b0 <= 0xDF) {
    n = 2;
  } else if (b0 >= 0xE0 && b0 <= 0xEF) {
    n = 3;
    if (b0 == 0xE0) lo = 0xA0;
    if (b0 == 0xED) hi = 0x9F;
  } else if (b0 >= 0xF0 && b0 <= 0xF4) {
    n = 4;
    if (b0 == 0xF0) lo = 0x90;
    if (b0 == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (n > s.size() - at) return 0;
  if (byte(1) < lo || byte(1) > hi) return 0;
  for (std::size_t i = 2; i < n; ++i)
    if (byte(i) < 0x80 || byte(i) > 0xBF) return 0;
  cp = b0 & (n == 2 ? 0x1Fu : n == 3 ? 0x0Fu : 0x07u);
  for (std::size_t i = 1; i < n; ++i) cp = (cp << 6) | (byte(i) & 0x3Fu);
  return n;
}

}  // namespace

std::string terminal_text(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (const char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c < 0x7F && c != '\\') out += ch;
    else append_escape(out, "\\x", c);
  }
  return out;
}

std::string json_string(std::string_view s) {
  std::string out = "\"";
  out.reserve(s.size() + 2);
  for (std::size_t at = 0; at < s.size();) {
    std::uint32_t cp = 0;
    const std::size_t n = utf8_sequence(s, at, cp);
    if (n == 0) {  // not UTF-8: the byte's value
      append_escape(out, "\\u00", static_cast<unsigned char>(s[at]));
      ++at;
      continue;
    }
    if (cp == '"' || cp == '\\') {
      out += '\\';
      out += static_cast<char>(cp);
    } else if (cp < 0x20 || (cp >= 0x7F && cp <= 0x9F)) {
      append_escape(out, "\\u00", cp);
    } else {
      out.append(s.data() + at, n);
    }
    at += n;
  }
  return out + "\"";
}

}  // namespace hesai::port
