#include "hesai/gps.h"

namespace hesai {

using namespace gps_wire;

namespace {

/// Pandar40 us time at a PPS is (minute * 60 + second) * 1e6 (Pandar40 manual, Section 3.2.2,
/// "Example of GPS Data Packet UDP Data Analysis", us Time): below one hour.
constexpr std::uint32_t kUsPerHour = 3600000000u;

bool all_fill(const std::uint8_t* p, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    if (p[i] != kFill) return false;
  }
  return true;
}

bool is_digit(std::uint8_t c) { return c >= '0' && c <= '9'; }

/// Two ASCII digits, units digit first ("lower byte first"): 0x30 0x32 -> 20.
bool digit_pair(const std::uint8_t* p, std::uint8_t& out) {
  if (!is_digit(p[0]) || !is_digit(p[1])) return false;
  out = static_cast<std::uint8_t>((p[1] - '0') * 10 + (p[0] - '0'));
  return true;
}

/// Value of an ASCII hex digit (either case), or -1.
int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

/// Length of the sentence at the start of an NMEA field: up to 2 bytes after the first '*'.
/// 0 when there is no '*' with two bytes after it inside the field, or when a byte of the
/// sentence is not printable ASCII (0x20..0x7E; this covers the NUL and 0xDF fill bytes).
std::size_t sentence_length(const std::uint8_t* f, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    if (f[i] < 0x20 || f[i] > 0x7E) return 0;
    if (f[i] == '*') {
      if (2 >= n - i) return 0;  // fewer than 2 bytes after '*' in the field
      if (f[i + 1] < 0x20 || f[i + 1] > 0x7E || f[i + 2] < 0x20 || f[i + 2] > 0x7E) return 0;
      return i + 3;
    }
  }
  return 0;
}

/// The NMEA 0183 checksum: XOR of the characters between '$' and '*', written as two hex digits.
bool nmea_checksum_matches(const char* s, std::size_t len) {
  if (len < 4 || s[0] != '$' || s[len - 3] != '*') return false;
  std::uint8_t x = 0;
  for (std::size_t i = 1; i < len - 3; ++i) x = static_cast<std::uint8_t>(x ^ static_cast<std::uint8_t>(s[i]));
  const int hi = hex_value(s[len - 2]);
  const int lo = hex_value(s[len - 1]);
  return hi >= 0 && lo >= 0 && x == hi * 16 + lo;
}

bool valid_status(std::uint8_t c, GpsLayout layout) {
  if (c == 'A' || c == 'V' || c == 0) return true;
  // Pandar64 with GPGGA selected: the status comes from the sentence, whose only status field is
  // the fix quality 0..9 (Pandar64 manual, Section 3.2.2.2).
  return layout == GpsLayout::pandar64 && is_digit(c);
}

}  // namespace

bool is_gps_packet(ByteView payload) noexcept {
  return payload.size == kPacketSize && payload[kHeader] == kMagic0 && payload[kHeader + 1] == kMagic1;
}

Error parse_gps_packet(ByteView payload, GpsPacket& out) noexcept {
  if (payload.size != kPacketSize) return Error::bad_length;
  const std::uint8_t* p = payload.data;
  if (p[kHeader] != kMagic0 || p[kHeader + 1] != kMagic1) return Error::bad_magic;

  // Bytes 102..505 are filler in both layouts; 95..101 too in a Pandar40 packet only.
  if (!all_fill(p + kFill64, kFillSize64)) return Error::bad_magic;
  GpsPacket g;
  g.layout = all_fill(p + kFill40, kFill64 - kFill40) ? GpsLayout::pandar40 : GpsLayout::pandar64;
  const std::size_t nmea_size = g.layout == GpsLayout::pandar40 ? kNmeaSize40 : kNmeaSize64;

  std::uint8_t yy = 0;
  if (!digit_pair(p + kYear, yy) || !digit_pair(p + kMonth, g.time.month) || !digit_pair(p + kDay, g.time.day) ||
      !digit_pair(p + kHour, g.time.hour) || !digit_pair(p + kMinute, g.time.minute) ||
      !digit_pair(p + kSecond, g.time.second)) {
    return Error::bad_gps_field;
  }
  g.time.year = 2000 + yy;
  if (!is_valid(g.time)) return Error::bad_gps_field;

  if (g.layout == GpsLayout::pandar40) {
    g.us_time = load_le32(p + kWord14);
    if (g.us_time >= kUsPerHour) return Error::bad_gps_field;
  }

  if (!valid_status(p[kStatus], g.layout)) return Error::bad_gps_field;
  g.location_status = static_cast<char>(p[kStatus]);
  if (p[kPpsLock] > 1) return Error::bad_gps_field;
  g.pps_locked = p[kPpsLock] == 1;

  const std::size_t len = sentence_length(p + kNmea, nmea_size);
  for (std::size_t i = 0; i < len; ++i) g.nmea[i] = static_cast<char>(p[kNmea + i]);
  g.nmea[len] = '\0';
  g.nmea_length = static_cast<std::uint8_t>(len);
  g.nmea_checksum_ok = nmea_checksum_matches(g.nmea, len);

  out = g;
  return Error::ok;
}

}  // namespace hesai
