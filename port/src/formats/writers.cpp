// PCD and PLY writers (CSV: csv.cpp). Layouts: hesai_port/formats/writers.h.
#include "hesai_port/formats/writers.h"

#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstring>

#include "hesai/bytes.h"
#include "le_store.h"
#include "output_file.h"

namespace hesai {
namespace port {
namespace {
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
