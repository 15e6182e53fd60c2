// CSV, PCD and PLY writers. Layouts and column contracts: hesai_port/formats/writers.h.
#include "hesai_port/formats/writers.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <system_error>

#include "hesai/bytes.h"
#include "le_store.h"

namespace hesai {
namespace port {
namespace {

constexpr std::size_t kBlockBytes = 1u << 20;

std::string os_message(const char* what, const std::string& name, int err) {
  return std::string(what) + " '" + name + "': " + std::strerror(err);
}

// ---- number formatting for CSV ----

char* put_uint(char* p, char* end, std::uint64_t v) { return std::to_chars(p, end, v).ptr; }

// Exactly 9 digits of v < 10^9, leading zeros kept: four independent pairs and one digit in
// 32-bit arithmetic (not one chain of 64-bit divisions).
void put_9digits(char* p, std::uint32_t v) {
  const std::uint32_t top = v / 100000000u;
  v %= 100000000u;
  const std::uint32_t hi = v / 10000u, lo = v % 10000u;
  const std::uint32_t d[4] = {hi / 100u, hi % 100u, lo / 100u, lo % 100u};
  p[0] = static_cast<char>('0' + top);
  for (int i = 0; i < 4; ++i) {
    p[1 + 2 * i] = static_cast<char>('0' + d[i] / 10u);
    p[2 + 2 * i] = static_cast<char>('0' + d[i] % 10u);
  }
}

// A signed integer; one of 10 digits or more (time_ns: 19) as its leading part and the last 9.
char* put_int(char* p, char* end, std::int64_t v) {
  if (v < 1000000000) return std::to_chars(p, end, v).ptr;  // negative or short: as before
  const auto u = static_cast<std::uint64_t>(v);
  p = std::to_chars(p, end, u / 1000000000u).ptr;
  put_9digits(p, static_cast<std::uint32_t>(u % 1000000000u));
  return p + 9;
}

// Fixed-point with `decimals` (0..4) decimals, rounded to nearest with ties to even as printf
// rounds; a value that rounds to zero loses its minus sign.
// Fast path: v = m * 2^e with |m| < 2^24, so v * 10^d = m * 5^d * 2^(e+d) has a significand below
// 2^24 * 5^4 < 2^34 and is exact in a double; rounding that exact product once (llrint, the
// default rounding mode) gives printf's digits. std::to_chars is 4-5x slower; it remains for
// values whose scaled magnitude does not fit an int64 (and for inf/NaN).
char* put_fixed(char* p, char* end, float v, int decimals) {
  static constexpr std::int64_t kScale[] = {1, 10, 100, 1000, 10000};
  const double scaled = static_cast<double>(v) * static_cast<double>(kScale[decimals]);
  if (scaled > -4.0e18 && scaled < 4.0e18) {  // false for NaN
    const std::int64_t r = std::llrint(scaled);
    if (r < 0) *p++ = '-';
    const std::uint64_t u = r < 0 ? 0 - static_cast<std::uint64_t>(r) : static_cast<std::uint64_t>(r);
    const auto scale = static_cast<std::uint64_t>(kScale[decimals]);
    p = put_uint(p, end, u / scale);
    if (decimals == 0) return p;
    *p++ = '.';
    std::uint64_t frac = u % scale;
    for (int i = decimals; i > 0; --i, frac /= 10) p[i - 1] = static_cast<char>('0' + frac % 10);
    return p + decimals;
  }
  const std::to_chars_result r = std::to_chars(p, end, v, std::chars_format::fixed, decimals);
  if (r.ec != std::errc()) return p;  // cannot happen: kCsvMaxRow leaves room for FLT_MAX
  return r.ptr;  // |v| >= 4e14 or inf/NaN: never rounds to zero
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
  // Bytes free at the end of the buffer (at least n after reserve(n)).
  std::size_t room() const { return buffer_.size() - used_; }
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

std::size_t format_csv_row(char* out, const Point& p, std::uint32_t frame, std::uint64_t packet) {
  char* const end = out + kCsvMaxRow;
  char* q = out;
  q = put_uint(q, end, frame);
  *q++ = ',';
  q = put_uint(q, end, packet);
  *q++ = ',';
  q = put_uint(q, end, p.block);
  *q++ = ',';
  q = put_uint(q, end, p.channel);
  *q++ = ',';
  q = put_uint(q, end, p.return_index);
  *q++ = ',';
  q = put_fixed(q, end, p.azimuth_deg, 3);
  *q++ = ',';
  q = put_fixed(q, end, p.elevation_deg, 3);
  *q++ = ',';
  q = put_fixed(q, end, p.distance_m, 4);
  *q++ = ',';
  q = put_fixed(q, end, p.x, 4);
  *q++ = ',';
  q = put_fixed(q, end, p.y, 4);
  *q++ = ',';
  q = put_fixed(q, end, p.z, 4);
  *q++ = ',';
  q = put_uint(q, end, p.intensity);
  *q++ = ',';
  q = put_int(q, end, p.time_ns);
  return static_cast<std::size_t>(q - out);
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
  for (std::size_t i = 0; i < count; ++i) {
    if (buffer_.size() - used_ < kCsvMaxRow + 2 + sensor.size()) (void)write_buffer();
    const std::size_t n = format_csv_row(buffer_.data() + used_, points[i], frame, packet);
    used_ += n;
    buffer_[used_++] = ',';
    std::memcpy(buffer_.data() + used_, sensor.data(), sensor.size());
    used_ += sensor.size();
    buffer_[used_++] = '\n';
  }
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

// The records, field by field (writers.h), each a fixed-size little-endian store. A Point's x, y
// and z are three consecutive floats, the records' first 12 bytes.
static_assert(offsetof(Point, y) == offsetof(Point, x) + 4 && offsetof(Point, z) == offsetof(Point, x) + 8,
              "Point::x, y, z consecutive");

inline void store_xyz(std::uint8_t* q, const Point& pt) {
  if constexpr (kLittleEndianHost) {
    std::memcpy(q, &pt.x, 12);
  } else {
    store_le(q, pt.x);
    store_le(q + 4, pt.y);
    store_le(q + 8, pt.z);
  }
}

struct PcdRecord {
  static constexpr std::size_t kBytes = kPcdPointBytes;
  static void encode(std::uint8_t* q, const Point& pt) {
    store_xyz(q, pt);
    store_le(q + 12, static_cast<float>(pt.intensity));
    store_le(q + 16, static_cast<std::uint16_t>(pt.channel));
    q[18] = pt.return_index;
    store_le(q + 19, seconds(pt.time_ns));
  }
};
static_assert(12 + 4 + 2 + 1 + 8 == kPcdPointBytes, "PCD record");

struct PlyRecord {
  static constexpr std::size_t kBytes = kPlyPointBytes;
  static void encode(std::uint8_t* q, const Point& pt) {
    store_xyz(q, pt);
    q[12] = pt.intensity;
    q[13] = pt.channel;
    q[14] = pt.return_index;
    store_le(q + 15, seconds(pt.time_ns));
  }
};
static_assert(12 + 3 + 8 == kPlyPointBytes, "PLY record");

// `count` records into the sink's buffer: as many as its block has room for in one loop, then
// the block goes to the file.
template <typename Record>
void put_records(FileSink& sink, const Point* points, std::size_t count) {
  while (count > 0) {
    std::uint8_t* q = sink.reserve(Record::kBytes);
    std::size_t n = sink.room() / Record::kBytes;
    if (n > count) n = count;
    for (std::size_t i = 0; i < n; ++i) Record::encode(q + i * Record::kBytes, points[i]);
    sink.commit(n * Record::kBytes);
    points += n;
    count -= n;
  }
}

// The whole file when the count is known before the first point.
template <typename Record>
WriteResult write_cloud(const std::string& path, const std::string& header, const Point* points, std::size_t count) {
  FileSink sink;
  WriteResult r = sink.open(path);
  if (!r) return r;
  sink.append(header.data(), header.size());
  put_records<Record>(sink, points, count);
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
  return write_cloud<PcdRecord>(path, pcd_header(count), points, count);
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
  return write_cloud<PlyRecord>(path, ply_header(count), points, count);
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
  if (format_ == CloudFormat::pcd) put_records<PcdRecord>(file_->sink, points, count);
  else put_records<PlyRecord>(file_->sink, points, count);
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
