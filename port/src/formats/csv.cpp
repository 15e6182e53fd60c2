// The CSV writer and its number formatting. Column contract: hesai_port/formats/writers.h.
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <system_error>

#include "hesai/bytes.h"
#include "hesai_port/formats/writers.h"
#include "le_store.h"
#include "output_file.h"

namespace hesai {
namespace port {
namespace {

// ---- number formatting for CSV ----
//
// Every number of a row is written by one digit writer: two digits at a time from a table, and
// numbers below 10^4 (nearly every field: angles, metres, the integer part of a fixed-point
// field) without a branch, as one 4-byte word shifted by the count of leading zeros. Writers may
// store up to 4 bytes past the end they return: a row is built where kCsvMaxRow bytes are free,
// several hundred more than the longest row.

// The two ASCII digits of each value 0..99 as a little-endian 16-bit word (first digit in the
// low byte): stored with store4 they come out in order on every host.
struct DigitPairs {
  std::uint16_t w[100];
};
constexpr DigitPairs make_digit_pairs() {
  DigitPairs t{};
  for (int i = 0; i < 100; ++i) t.w[i] = static_cast<std::uint16_t>(('0' + i / 10) | ('0' + i % 10) << 8);
  return t;
}
constexpr DigitPairs kDigitPairs = make_digit_pairs();
static_assert(kDigitPairs.w[0] == 0x3030 && kDigitPairs.w[42] == 0x3234 && kDigitPairs.w[99] == 0x3939, "00 42 99");

// Bytes 0-3 of w to p[0..3], byte 0 first: one word store on a little-endian host (GCC does not
// always merge store_le32's four byte stores into one).
inline void store4(char* p, std::uint32_t w) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  std::memcpy(p, &w, sizeof w);
#else
  store_le32(reinterpret_cast<std::uint8_t*>(p), w);
#endif
}

// The four digits of v < 10^4, leading zeros kept, as a little-endian word.
inline std::uint32_t digits4(std::uint32_t v) {
  return static_cast<std::uint32_t>(kDigitPairs.w[v / 100u]) | static_cast<std::uint32_t>(kDigitPairs.w[v % 100u]) << 16;
}

// v < 10^4 in 1-4 digits; stores 4 bytes, returns the end of the digits.
inline char* put_small(char* p, std::uint32_t v) {
  const std::uint32_t n = 1u + static_cast<std::uint32_t>(v >= 10u) + static_cast<std::uint32_t>(v >= 100u) +
                          static_cast<std::uint32_t>(v >= 1000u);
  store4(p, digits4(v) >> (8u * (4u - n)));  // the leading zeros shifted out
  return p + n;
}

// Exactly 8 digits of v < 10^8, leading zeros kept.
inline void put_8digits(char* p, std::uint32_t v) {
  store4(p, digits4(v / 10000u));
  store4(p + 4, digits4(v % 10000u));
}

char* put_u32(char* p, std::uint32_t v) {
  if (v < 10000u) return put_small(p, v);
  if (v < 100000000u) {
    p = put_small(p, v / 10000u);
    store4(p, digits4(v % 10000u));
    return p + 4;
  }
  p = put_small(p, v / 100000000u);  // at most 42
  put_8digits(p, v % 100000000u);
  return p + 8;
}

char* put_u64(char* p, std::uint64_t v) {
  if (v <= 0xFFFFFFFFu) return put_u32(p, static_cast<std::uint32_t>(v));
  // 10 to 20 digits: the part above the last 8, then the last 8; time_ns (19 digits) is
  // 3 + 8 + 8.
  const std::uint64_t high = v / 100000000u;
  if (high < 100000000u) {
    p = put_u32(p, static_cast<std::uint32_t>(high));
  } else {
    p = put_small(p, static_cast<std::uint32_t>(high / 100000000u));  // at most 1844
    put_8digits(p, static_cast<std::uint32_t>(high % 100000000u));
    p += 8;
  }
  put_8digits(p, static_cast<std::uint32_t>(v % 100000000u));
  return p + 8;
}

char* put_i64(char* p, std::int64_t v) {
  if (v >= 0) return put_u64(p, static_cast<std::uint64_t>(v));
  *p++ = '-';
  return put_u64(p, 0 - static_cast<std::uint64_t>(v));  // INT64_MIN too
}

// Each byte value's 1-3 digits as a little-endian word, their count in the top byte: one load
// and one store write a uint8 field (block, channel, return, intensity).
struct ByteText {
  std::uint32_t w[256];
};
constexpr ByteText make_byte_text() {
  ByteText t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    const std::uint32_t n = i < 10 ? 1 : i < 100 ? 2 : 3;
    std::uint32_t w = n << 24;
    for (std::uint32_t k = 0, v = i; k < n; ++k, v /= 10) w |= ('0' + v % 10) << (8 * (n - 1 - k));
    t.w[i] = w;
  }
  return t;
}
constexpr ByteText kByteText = make_byte_text();
static_assert(kByteText.w[7] == 0x01000037 && kByteText.w[42] == 0x02003234 && kByteText.w[255] == 0x03353532,
              "7, 42, 255");

// Stores 4 bytes, returns the end of the 1-3 digits.
inline char* put_u8(char* p, std::uint8_t v) {
  const std::uint32_t w = kByteText.w[v];
  store4(p, w);
  return p + (w >> 24);
}

// The digits of u / 10^D, '.', and the D decimals of u % 10^D (D = 3 or 4).
template <int D>
char* put_scaled(char* p, std::uint64_t u) {
  static_assert(D == 3 || D == 4, "3 or 4 decimals");
  constexpr std::uint32_t kScale = D == 3 ? 1000u : 10000u;
  const std::uint64_t whole = u / kScale;
  const auto frac = static_cast<std::uint32_t>(u % kScale);
  if (whole < 10000u) {
    p = put_small(p, static_cast<std::uint32_t>(whole));
  } else {
    p = put_u64(p, whole);
  }
  // '.' and the decimals: for 3, the 4 digits of frac < 1000 with their leading '0' replaced.
  if (D == 3) {
    store4(p, (digits4(frac) & 0xFFFFFF00u) | static_cast<std::uint32_t>('.'));
  } else {
    *p = '.';
    store4(p + 1, digits4(frac));
  }
  return p + 1 + D;
}

// The rare values of put_fixed: |v * 10^D| >= 2^51, inf and NaN. For |v * 10^D| < 4e18 the
// scaled double is rounded by llrint (default rounding mode: to nearest, ties to even, as printf);
// beyond that, and for inf/NaN, std::to_chars writes the float's exact digits ("inf", "-nan").
template <int D>
[[gnu::noinline]] char* put_fixed_wide(char* p, char* end, float v, double scaled) {
  if (scaled > -4.0e18 && scaled < 4.0e18) {  // false for NaN
    const std::int64_t r = std::llrint(scaled);  // |r| >= 2^51: never zero
    if (r < 0) *p++ = '-';
    return put_scaled<D>(p, r < 0 ? 0 - static_cast<std::uint64_t>(r) : static_cast<std::uint64_t>(r));
  }
  const std::to_chars_result r = std::to_chars(p, end, v, std::chars_format::fixed, D);
  if (r.ec != std::errc()) return p;  // cannot happen: kCsvMaxRow leaves room for FLT_MAX
  return r.ptr;
}

// Fixed-point with D decimals, rounded to nearest with ties to even as printf rounds; a value
// that rounds to zero loses its minus sign.
// v = m * 2^e with |m| < 2^24, so v * 10^D = m * 5^D * 2^(e+D) has a significand below
// 2^24 * 5^4 < 2^34: the double product is exact, and rounding it once to an integer gives
// printf's digits. For |x| < 2^51, x + 1.5 * 2^52 lies in [2^52, 2^53), where doubles are the
// integers, so the addition rounds x to an integer in the default rounding mode (ties to even:
// 1.5 * 2^52 is even) and the subtraction is exact: no call to llrint (a libm call where errno
// must be kept).
template <int D>
char* put_fixed(char* p, char* end, float v) {
  constexpr double kScale = D == 3 ? 1000.0 : 10000.0;
  constexpr double kRound = 0x1.8p52;
  const double scaled = static_cast<double>(v) * kScale;
  if (!(std::fabs(scaled) < 0x1p51)) return put_fixed_wide<D>(p, end, v, scaled);  // and NaN
  const auto r = static_cast<std::int64_t>((scaled + kRound) - kRound);
  *p = '-';
  p += r < 0 ? 1 : 0;  // -0.00004 gives r == 0: no sign
  return put_scaled<D>(p, static_cast<std::uint64_t>(r < 0 ? -r : r));
}

}  // namespace

// ---- CSV ----

namespace {

// The fields of a row after frame and packet: ",block,channel,...,time_ns". `end` is where the
// kCsvMaxRow bytes of the row's space end.
char* put_point_fields(char* q, char* end, const Point& p) {
  *q++ = ',';
  q = put_u8(q, p.block);
  *q++ = ',';
  q = put_u8(q, p.channel);
  *q++ = ',';
  q = put_u8(q, p.return_index);
  *q++ = ',';
  q = put_fixed<3>(q, end, p.azimuth_deg);
  *q++ = ',';
  q = put_fixed<3>(q, end, p.elevation_deg);
  *q++ = ',';
  q = put_fixed<4>(q, end, p.distance_m);
  *q++ = ',';
  q = put_fixed<4>(q, end, p.x);
  *q++ = ',';
  q = put_fixed<4>(q, end, p.y);
  *q++ = ',';
  q = put_fixed<4>(q, end, p.z);
  *q++ = ',';
  q = put_u8(q, p.intensity);
  *q++ = ',';
  return put_i64(q, p.time_ns);
}

// "frame,packet": at most 10 + 1 + 20 chars.
constexpr std::size_t kCsvPrefixBytes = 32;
std::size_t put_row_prefix(char* out, std::uint32_t frame, std::uint64_t packet) {
  char* q = put_u32(out, frame);
  *q++ = ',';
  return static_cast<std::size_t>(put_u64(q, packet) - out);
}

}  // namespace

std::size_t format_csv_row(char* out, const Point& p, std::uint32_t frame, std::uint64_t packet) {
  const std::size_t n = put_row_prefix(out, frame, packet);
  return static_cast<std::size_t>(put_point_fields(out + n, out + kCsvMaxRow, p) - out);
}

CsvWriter::~CsvWriter() {
  if (stream_ != nullptr) (void)close();
}

WriteResult CsvWriter::open(const std::string& path) {
  if (stream_ != nullptr) return WriteResult::failure("CsvWriter: '" + name_ + "' is still open");
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) {
    const int err = errno;
    return WriteResult::failure(os_message("cannot open", path, err), err);
  }
  WriteResult r = open(f, path);
  owned_ = true;
  return r;
}

WriteResult CsvWriter::open(std::FILE* stream, const std::string& name) {
  if (stream_ != nullptr) return WriteResult::failure("CsvWriter: '" + name_ + "' is still open");
  if (stream == nullptr) return WriteResult::failure("CsvWriter: no stream for '" + name + "'");
  stream_ = stream;
  owned_ = false;
  name_ = name;
  buffer_.resize(kBlockBytes);
  used_ = 0;
  rows_ = 0;
  sticky_ = WriteResult();
  const std::size_t n = std::strlen(kHeader);
  std::memcpy(buffer_.data(), kHeader, n);
  buffer_[n] = '\n';
  used_ = n + 1;
  return {};
}

WriteResult CsvWriter::write_buffer() {
  if (used_ != 0 && sticky_.ok() && std::fwrite(buffer_.data(), 1, used_, stream_) != used_) {
    const int err = errno;
    sticky_ = WriteResult::failure(os_message("cannot write", name_, err), err);
  }
  used_ = 0;
  return sticky_;
}

WriteResult CsvWriter::write(const Point& p, std::uint32_t frame, std::uint64_t packet, const std::string& sensor) {
  return write(&p, 1, frame, packet, sensor);
}

WriteResult CsvWriter::write(const Point* points, std::size_t count, std::uint32_t frame, std::uint64_t packet,
                             const std::string& sensor) {
  if (stream_ == nullptr) return WriteResult::failure("CsvWriter: not open");
  if (sensor.size() > kMaxSensorBytes) return WriteResult::failure("CsvWriter: a sensor field of more than 1024 bytes");
  // Frame and packet are the same in every row: formatted once, copied as 32 bytes a row (the
  // row's space is kCsvMaxRow: the copy's tail is overwritten by the fields).
  char prefix[kCsvPrefixBytes] = {};
  const std::size_t prefix_bytes = put_row_prefix(prefix, frame, packet);
  // Locals, not the members: every char stored could alias used_ and force a reload.
  char* const base = buffer_.data();
  const std::size_t capacity = buffer_.size();
  const std::size_t room = kCsvMaxRow + 2 + sensor.size();
  std::size_t used = used_;
  for (std::size_t i = 0; i < count; ++i) {
    if (capacity - used < room) {
      used_ = used;
      (void)write_buffer();
      used = 0;
    }
    char* const row = base + used;
    std::memcpy(row, prefix, kCsvPrefixBytes);
    char* q = put_point_fields(row + prefix_bytes, row + kCsvMaxRow, points[i]);
    *q++ = ',';
    std::memcpy(q, sensor.data(), sensor.size());
    q += sensor.size();
    *q++ = '\n';
    used = static_cast<std::size_t>(q - base);
  }
  used_ = used;
  rows_ += count;
  return sticky_;
}

WriteResult CsvWriter::flush() {
  if (stream_ == nullptr) return WriteResult::failure("CsvWriter: not open");
  (void)write_buffer();
  if (sticky_.ok() && std::fflush(stream_) != 0) {
    const int err = errno;
    sticky_ = WriteResult::failure(os_message("cannot write", name_, err), err);
  }
  return sticky_;
}

WriteResult CsvWriter::close() {
  if (stream_ == nullptr) return WriteResult::failure("CsvWriter: not open");
  (void)write_buffer();
  if (owned_) {
    if (std::fclose(stream_) != 0 && sticky_.ok()) {
      const int err = errno;
      sticky_ = WriteResult::failure(os_message("cannot close", name_, err), err);
    }
  } else if (std::fflush(stream_) != 0 && sticky_.ok()) {
    const int err = errno;
    sticky_ = WriteResult::failure(os_message("cannot write", name_, err), err);
  }
  stream_ = nullptr;
  owned_ = false;
  buffer_.clear();
  buffer_.shrink_to_fit();
  WriteResult r = sticky_;
  sticky_ = WriteResult();
  return r;
}

}  // namespace port
}  // namespace hesai
