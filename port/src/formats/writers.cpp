// CSV, PCD and PLY writers. Layouts and column contracts: hesai_port/formats/writers.h.
#include "hesai_port/formats/writers.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <system_error>

#include "hesai/bytes.h"

namespace hesai {
namespace port {
namespace {

constexpr std::size_t kBlockBytes = 1u << 20;

std::string os_message(const char* what, const std::string& name, int err) {
  return std::string(what) + " '" + name + "': " + std::strerror(err);
}

// ---- number formatting for CSV ----
//
// Every number of a row is written by one digit writer: two digits at a time from a 200-byte
// table, right to left into a field whose length is known first. Writers may store a few bytes
// past the end they return (the uint8 fields store 4): a row is built where kCsvMaxRow bytes are
// free, several hundred more than the longest row.

struct DigitPairs {
  char c[200];
};
constexpr DigitPairs make_digit_pairs() {
  DigitPairs t{};
  for (int i = 0; i < 100; ++i) {
    t.c[2 * i] = static_cast<char>('0' + i / 10);
    t.c[2 * i + 1] = static_cast<char>('0' + i % 10);
  }
  return t;
}
constexpr DigitPairs kDigitPairs = make_digit_pairs();
static_assert(kDigitPairs.c[0] == '0' && kDigitPairs.c[85] == '2' && kDigitPairs.c[199] == '9', "00, 42, 99");

// The two digits of v < 100.
inline void put2(char* p, std::uint32_t v) { std::memcpy(p, kDigitPairs.c + 2 * v, 2); }

// Number of decimal digits of v (1 for 0).
inline int digit_count(std::uint32_t v) {
  if (v < 100) return v < 10 ? 1 : 2;
  if (v < 10000) return v < 1000 ? 3 : 4;
  if (v < 1000000) return v < 100000 ? 5 : 6;
  if (v < 100000000) return v < 10000000 ? 7 : 8;
  return v < 1000000000 ? 9 : 10;
}

// Exactly n digits of v < 10^n, leading zeros kept.
inline void put_digits(char* p, std::uint32_t v, int n) {
  char* q = p + n;
  while (q - p >= 2) {
    q -= 2;
    put2(q, v % 100u);
    v /= 100u;
  }
  if (q != p) *p = static_cast<char>('0' + v);
}

// Exactly 9 digits of v < 10^9 as two independent chains (5 and 4 digits), not one of 9.
inline void put_9digits(char* p, std::uint32_t v) {
  put_digits(p, v / 10000u, 5);
  put_digits(p + 5, v % 10000u, 4);
}

char* put_u32(char* p, std::uint32_t v) {
  const int n = digit_count(v);
  put_digits(p, v, n);
  return p + n;
}

char* put_u64(char* p, std::uint64_t v) {
  if (v <= 0xFFFFFFFFu) return put_u32(p, static_cast<std::uint32_t>(v));
  // 10 to 20 digits: the part above the last 9 (at most 11 digits), then the last 9.
  std::uint64_t high = v / 1000000000u;
  if (high > 0xFFFFFFFFu) {
    p = put_u32(p, static_cast<std::uint32_t>(high / 1000000000u));  // at most 18
    put_9digits(p, static_cast<std::uint32_t>(high % 1000000000u));
    p += 9;
  } else {
    p = put_u32(p, static_cast<std::uint32_t>(high));
  }
  put_9digits(p, static_cast<std::uint32_t>(v % 1000000000u));
  return p + 9;
}

char* put_i64(char* p, std::int64_t v) {
  if (v >= 0) return put_u64(p, static_cast<std::uint64_t>(v));
  *p++ = '-';
  return put_u64(p, 0 - static_cast<std::uint64_t>(v));  // INT64_MIN too
}

// Each byte value as its digits, padded to 4 chars, and the digit count in the last char:
// one 4-byte copy writes a uint8 field.
struct ByteText {
  char c[256][4];
};
constexpr ByteText make_byte_text() {
  ByteText t{};
  for (int i = 0; i < 256; ++i) {
    const int n = i < 10 ? 1 : i < 100 ? 2 : 3;
    for (int k = n - 1, v = i; k >= 0; --k, v /= 10) t.c[i][k] = static_cast<char>('0' + v % 10);
    t.c[i][3] = static_cast<char>(n);
  }
  return t;
}
constexpr ByteText kByteText = make_byte_text();
static_assert(kByteText.c[7][0] == '7' && kByteText.c[7][3] == 1 && kByteText.c[255][2] == '5' &&
                  kByteText.c[255][3] == 3,
              "7, 255");

// A uint8 field; stores 4 chars, returns the end of its 1-3 digits.
inline char* put_u8(char* p, std::uint8_t v) {
  std::memcpy(p, kByteText.c[v], 4);
  return p + kByteText.c[v][3];
}

// The digits of u / 10^D, '.', and the D decimals of u % 10^D (D = 3 or 4).
template <int D>
char* put_scaled(char* p, std::uint64_t u) {
  static_assert(D == 3 || D == 4, "3 or 4 decimals");
  constexpr std::uint32_t kScale = D == 3 ? 1000u : 10000u;
  const std::uint64_t whole = u / kScale;
  const auto frac = static_cast<std::uint32_t>(u % kScale);
  p = whole <= 0xFFFFFFFFu ? put_u32(p, static_cast<std::uint32_t>(whole)) : put_u64(p, whole);
  *p = '.';
  put_digits(p + 1, frac, D);
  return p + 1 + D;
}

// The rare values of put_fixed: |v * 10^D| >= 2^51, inf and NaN. For |v * 10^D| < 4e18 the
// scaled double is rounded by llrint (default rounding mode: to nearest, ties to even, as printf);
// beyond that, and for inf/NaN, std::to_chars writes the float's exact digits ("inf", "-nan").
template <int D>
char* put_fixed_wide(char* p, char* end, float v, double scaled) {
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
// 1.5 * 2^52 is even) and the subtraction is exact; no call to llrint, which is a libm call
// where errno must be kept.
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

// ---- little-endian record fields ----

void put_f32(std::uint8_t*& p, float v) {
  std::uint32_t u = 0;
  static_assert(sizeof u == sizeof v, "IEEE-754 binary32 float");
  std::memcpy(&u, &v, sizeof u);
  store_le32(p, u);
  p += 4;
}
void put_f64(std::uint8_t*& p, double v) {
  std::uint64_t u = 0;
  static_assert(sizeof u == sizeof v, "IEEE-754 binary64 double");
  std::memcpy(&u, &v, sizeof u);
  store_le32(p, static_cast<std::uint32_t>(u));
  store_le32(p + 4, static_cast<std::uint32_t>(u >> 32));
  p += 8;
}

// Seconds since the epoch as a double, rounded once (time_ns itself does not fit a double).
double seconds(std::int64_t time_ns) {
  std::int64_t s = time_ns / 1000000000;
  std::int64_t ns = time_ns % 1000000000;
  if (ns < 0) {
    ns += 1000000000;
    --s;
  }
  return static_cast<double>(s) + static_cast<double>(ns) * 1e-9;
}

// A file written in large blocks; reports the first failure.
class FileSink {
 public:
  ~FileSink() {
    if (f_ != nullptr) std::fclose(f_);
  }
  WriteResult open(const std::string& path) {
    name_ = path;
    f_ = std::fopen(path.c_str(), "wb");
    if (f_ == nullptr) {
      const int err = errno;
      return WriteResult::failure(os_message("cannot open", path, err), err);
    }
    buffer_.resize(kBlockBytes);
    return {};
  }
  // Space for n bytes at the end of the buffer (n <= kBlockBytes).
  std::uint8_t* reserve(std::size_t n) {
    if (buffer_.size() - used_ < n) drain();
    return buffer_.data() + used_;
  }
  void commit(std::size_t n) { used_ += n; }
  // Fails with ESPIPE unless the file can be rewound (a pipe, FIFO, socket or terminal cannot).
  WriteResult check_seekable() {
    if (ftello(f_) < 0) {
      const int err = errno;
      return WriteResult::failure("cannot write '" + name_ + "': " + std::strerror(err) +
                                      " (PCD and PLY headers hold the point count, written at the end: give a file)",
                                  err);
    }
    return {};
  }
  // Writes what is buffered, then overwrites the first n bytes of the file with `data`.
  void rewrite_start(const void* data, std::size_t n) {
    drain();
    if (!result_.ok()) return;
    if (fseeko(f_, 0, SEEK_SET) != 0 || std::fwrite(data, 1, n, f_) != n) {
      const int err = errno;
      result_ = WriteResult::failure(os_message("cannot write", name_, err), err);
    }
  }
  void append(const void* data, std::size_t n) {
    const auto* b = static_cast<const std::uint8_t*>(data);
    while (n > 0) {
      if (used_ == buffer_.size()) drain();
      const std::size_t k = n < buffer_.size() - used_ ? n : buffer_.size() - used_;
      std::memcpy(buffer_.data() + used_, b, k);
      used_ += k;
      b += k;
      n -= k;
    }
  }
  WriteResult close() {
    drain();
    const int rc = std::fclose(f_);
    f_ = nullptr;
    if (rc != 0 && result_.ok()) {
      const int err = errno;
      result_ = WriteResult::failure(os_message("cannot close", name_, err), err);
    }
    return result_;
  }

 private:
  void drain() {
    if (used_ != 0 && result_.ok() && std::fwrite(buffer_.data(), 1, used_, f_) != used_) {
      const int err = errno;
      result_ = WriteResult::failure(os_message("cannot write", name_, err), err);
    }
    used_ = 0;
  }

  std::FILE* f_ = nullptr;
  std::string name_;
  std::vector<std::uint8_t> buffer_;
  std::size_t used_ = 0;
  WriteResult result_;
};

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

// ---- PCD and PLY ----

namespace {

std::string count_text(std::uint64_t n, int digits) {
  std::string t = std::to_string(n);
  if (t.size() < static_cast<std::size_t>(digits)) t.insert(0, static_cast<std::size_t>(digits) - t.size(), '0');
  return t;
}

void encode_pcd(std::uint8_t* q, const Point& pt) {
  put_f32(q, pt.x);
  put_f32(q, pt.y);
  put_f32(q, pt.z);
  put_f32(q, static_cast<float>(pt.intensity));
  store_le16(q, pt.channel);
  q += 2;
  *q++ = pt.return_index;
  put_f64(q, seconds(pt.time_ns));
}

void encode_ply(std::uint8_t* q, const Point& pt) {
  put_f32(q, pt.x);
  put_f32(q, pt.y);
  put_f32(q, pt.z);
  *q++ = pt.intensity;
  *q++ = pt.channel;
  *q++ = pt.return_index;
  put_f64(q, seconds(pt.time_ns));
}

// The whole file when the count is known before the first point.
WriteResult write_cloud(const std::string& path, const std::string& header, const Point* points, std::size_t count,
                        std::size_t record_bytes, void (*encode)(std::uint8_t*, const Point&)) {
  FileSink sink;
  WriteResult r = sink.open(path);
  if (!r) return r;
  sink.append(header.data(), header.size());
  for (std::size_t i = 0; i < count; ++i) {
    encode(sink.reserve(record_bytes), points[i]);
    sink.commit(record_bytes);
  }
  return sink.close();
}

}  // namespace

std::string pcd_header(std::uint64_t n, int digits) {
  const std::string count = count_text(n, digits);
  return "# .PCD v0.7 - Point Cloud Data file format\n"
         "VERSION 0.7\n"
         "FIELDS x y z intensity ring return timestamp\n"
         "SIZE 4 4 4 4 2 1 8\n"
         "TYPE F F F F U U F\n"
         "COUNT 1 1 1 1 1 1 1\n"
         "WIDTH " + count + "\n"
         "HEIGHT 1\n"
         "VIEWPOINT 0 0 0 1 0 0 0\n"
         "POINTS " + count + "\n"
         "DATA binary\n";
}

WriteResult write_pcd(const std::string& path, const Point* points, std::size_t count) {
  return write_cloud(path, pcd_header(count), points, count, kPcdPointBytes, encode_pcd);
}

WriteResult write_pcd(const std::string& path, const std::vector<Point>& points) {
  return write_pcd(path, points.data(), points.size());
}

std::string ply_header(std::uint64_t n, int digits) {
  return "ply\n"
         "format binary_little_endian 1.0\n"
         "comment hesai point cloud: metres; ring = channel; timestamp = s since 1970-01-01 UTC\n"
         "element vertex " + count_text(n, digits) + "\n"
         "property float x\n"
         "property float y\n"
         "property float z\n"
         "property uchar intensity\n"
         "property uchar ring\n"
         "property uchar return\n"
         "property double timestamp\n"
         "end_header\n";
}

WriteResult write_ply(const std::string& path, const Point* points, std::size_t count) {
  return write_cloud(path, ply_header(count), points, count, kPlyPointBytes, encode_ply);
}

WriteResult write_ply(const std::string& path, const std::vector<Point>& points) {
  return write_ply(path, points.data(), points.size());
}

// ---- CloudWriter ----

struct CloudWriter::File {
  FileSink sink;
};

CloudWriter::CloudWriter() = default;

CloudWriter::~CloudWriter() {
  if (file_) (void)close();
}

bool CloudWriter::is_open() const { return file_ != nullptr; }

namespace {
std::string stream_header(CloudFormat format, std::uint64_t n) {
  return format == CloudFormat::pcd ? pcd_header(n, CloudWriter::kStreamCountDigits)
                                    : ply_header(n, CloudWriter::kStreamCountDigits);
}
}  // namespace

WriteResult CloudWriter::open(const std::string& path, CloudFormat format) {
  if (file_) return WriteResult::failure("CloudWriter: a file is still open");
  auto file = std::make_unique<File>();
  WriteResult r = file->sink.open(path);
  if (r) r = file->sink.check_seekable();
  if (!r) return r;  // the FileSink closes the file
  format_ = format;
  count_ = 0;
  const std::string header = stream_header(format_, 0);
  file->sink.append(header.data(), header.size());
  file_ = std::move(file);
  return {};
}

void CloudWriter::write(const Point& p) { write(&p, 1); }

void CloudWriter::write(const Point* points, std::size_t count) {
  if (!file_) return;
  const std::size_t n = format_ == CloudFormat::pcd ? kPcdPointBytes : kPlyPointBytes;
  void (*const encode)(std::uint8_t*, const Point&) = format_ == CloudFormat::pcd ? encode_pcd : encode_ply;
  FileSink& sink = file_->sink;
  for (std::size_t i = 0; i < count; ++i) {
    encode(sink.reserve(n), points[i]);
    sink.commit(n);
  }
  count_ += count;
}

WriteResult CloudWriter::close() {
  if (!file_) return WriteResult::failure("CloudWriter: not open");
  const std::string header = stream_header(format_, count_);
  file_->sink.rewrite_start(header.data(), header.size());
  const WriteResult r = file_->sink.close();
  file_.reset();
  return r;
}

// ---- whole files ----

WriteResult write_file(const std::string& path, const std::uint8_t* bytes, std::size_t size) {
  FileSink sink;
  WriteResult r = sink.open(path);
  if (!r) return r;
  sink.append(bytes, size);
  return sink.close();
}

}  // namespace port
}  // namespace hesai
