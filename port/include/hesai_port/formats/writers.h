// Point-cloud output: CSV rows, binary PCD, binary PLY and a bird's-eye PNG.
//
// Every file format is written byte by byte in little-endian order, so a big-endian host writes
// the same files. Writers report failures as a WriteResult with a message naming the file and
// the cause (never an exception).
//
// CSV columns (a contract; the header line is exactly this):
//   frame,packet,block,channel,return,azimuth_deg,elevation_deg,distance_m,x,y,z,intensity,time_ns
//   frame, packet, block, channel (1-based), return (Point::return_index), intensity and time_ns
//   (ns since the Unix epoch) are integers; azimuth_deg and elevation_deg have 3 decimals
//   (0.001 deg); distance_m, x, y, z have 4 decimals (0.1 mm, finer than the 2.5-4 mm distance
//   unit, and as fine as a float holds at 100 m). A value that rounds to zero prints without sign.
//
// PCD (PCL's format, v0.7, binary), one 27-byte record per point:
//   FIELDS x y z intensity ring return timestamp
//   SIZE 4 4 4 4 2 1 8
//   TYPE F F F F U U F
//   x, y, z in metres; intensity as float (0..255; pcl::PointXYZI expects float); ring = channel
//   (1-based, uint16 as in the ROS lidar drivers); return = Point::return_index; timestamp in
//   seconds since the Unix epoch as a double (resolution 0.24 us at today's dates).
//
// PLY (binary_little_endian 1.0), one element "vertex", one 23-byte record per point:
//   float x, y, z (metres), uchar intensity, uchar ring (channel), uchar return,
//   double timestamp (seconds since the Unix epoch).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "hesai/point.h"
#include "hesai_port/formats/png.h"

namespace hesai {
namespace port {

/// Outcome of a writer call: ok, or a message that names the file and the cause.
class [[nodiscard]] WriteResult {
 public:
  WriteResult() = default;
  /// A failure with `message` ("cannot open 'out.csv': No such file or directory").
  static WriteResult failure(std::string message, int os_error = 0) {
    WriteResult r;
    r.ok_ = false;
    r.message_ = std::move(message);
    r.os_error_ = os_error;
    return r;
  }
  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  /// Empty when ok.
  const std::string& message() const { return message_; }
  /// errno of the failed system call; 0 when the failure was not the OS's.
  int os_error() const { return os_error_; }

 private:
  bool ok_ = true;
  std::string message_;
  int os_error_ = 0;
};

/// Writes one CSV row per point (see the column contract above). Output is built in memory
/// and written in blocks of about 1 MiB. Not copyable; closes on destruction (errors then lost:
/// call close() to see them).
class CsvWriter {
 public:
  /// The header line, without its line feed.
  static constexpr const char* kHeader =
      "frame,packet,block,channel,return,azimuth_deg,elevation_deg,distance_m,x,y,z,intensity,time_ns,sensor";

  CsvWriter() = default;
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  /// Creates (truncates) `path` and writes the header line.
  WriteResult open(const std::string& path);
  /// Writes to an open stream (stdout, a pipe) that stays the caller's: close() flushes it but
  /// does not fclose it. `name` is used in messages.
  WriteResult open(std::FILE* stream, const std::string& name = "stream");
  /// One row; `sensor` is the last column as it is written (a CSV field, quoted by the caller
  /// where it must be; at most kMaxSensorBytes). Rows go out in blocks; a failed block write is
  /// reported here or by close().
  WriteResult write(const Point& p, std::uint32_t frame, std::uint64_t packet, const std::string& sensor);
  /// `count` rows of the same frame, packet and sensor.
  WriteResult write(const Point* points, std::size_t count, std::uint32_t frame, std::uint64_t packet,
                    const std::string& sensor);
  /// The longest `sensor` field write() takes.
  static constexpr std::size_t kMaxSensorBytes = 1024;
  /// Writes what is buffered (the stream's own buffer is flushed too).
  WriteResult flush();
  /// Flushes and closes; reports a write error of any earlier block.
  WriteResult close();

  bool is_open() const { return stream_ != nullptr; }
  /// Rows written since open (header not counted).
  std::uint64_t rows() const { return rows_; }

 private:
  WriteResult write_buffer();

  std::FILE* stream_ = nullptr;
  bool owned_ = false;
  std::string name_;
  std::vector<char> buffer_;
  std::size_t used_ = 0;
  std::uint64_t rows_ = 0;
  WriteResult sticky_;  // the first write failure, reported until close
};

/// Formats one CSV row (no line feed) into `out`, which must hold kCsvMaxRow chars; returns its
/// length. The building block of CsvWriter, exposed for callers with their own buffering.
inline constexpr std::size_t kCsvMaxRow = 640;
std::size_t format_csv_row(char* out, const Point& p, std::uint32_t frame, std::uint64_t packet);

/// The PCD header for `n` points (see the layout above), ending with "DATA binary\n". The count
/// is printed with at least `digits` digits, zero-padded (PCL and other readers parse "0042" as 42).
std::string pcd_header(std::uint64_t n, int digits = 0);
/// Bytes of one PCD record (x, y, z, intensity: 4 each; ring 2; return 1; timestamp 8).
inline constexpr std::size_t kPcdPointBytes = 27;
/// Writes `points` as a binary PCD file (unorganised: WIDTH n, HEIGHT 1).
WriteResult write_pcd(const std::string& path, const Point* points, std::size_t count);
WriteResult write_pcd(const std::string& path, const std::vector<Point>& points);

/// The PLY header for `n` vertices, ending with "end_header\n"; the count zero-padded to `digits`.
std::string ply_header(std::uint64_t n, int digits = 0);
/// Bytes of one PLY vertex (x, y, z: float; intensity, ring, return: uchar; timestamp: double).
inline constexpr std::size_t kPlyPointBytes = 23;
/// Writes `points` as a binary little-endian PLY file of one vertex element.
WriteResult write_ply(const std::string& path, const Point* points, std::size_t count);
WriteResult write_ply(const std::string& path, const std::vector<Point>& points);

/// File format of a CloudWriter.
enum class CloudFormat : std::uint8_t { pcd, ply };

/// Writes one PCD or PLY file point by point, in memory bounded by one 1 MiB block whatever the
/// number of points. The header goes out first with the count as kStreamCountDigits zero-padded
/// digits, and close() rewrites it with the final count. So the destination must be seekable (a
/// regular file; /dev/null): open() refuses a pipe, FIFO, socket or terminal with os_error()
/// ESPIPE. Not copyable; closes on destruction (errors then lost: call close() to see them).
class CloudWriter {
 public:
  /// Digits of the count in the header: every 64-bit count fits.
  static constexpr int kStreamCountDigits = 20;

  CloudWriter();
  ~CloudWriter();
  CloudWriter(const CloudWriter&) = delete;
  CloudWriter& operator=(const CloudWriter&) = delete;

  /// Creates (truncates) `path` and writes the header for a count of 0.
  WriteResult open(const std::string& path, CloudFormat format);
  /// One record. A failed block write is kept and reported by close().
  void write(const Point& p);
  /// `count` records, as many write(p) calls.
  void write(const Point* points, std::size_t count);
  /// Writes what is buffered, rewrites the header with count() and closes; reports any failure.
  WriteResult close();

  bool is_open() const;
  /// Points written since open.
  std::uint64_t count() const { return count_; }

 private:
  struct File;
  std::unique_ptr<File> file_;
  CloudFormat format_ = CloudFormat::pcd;
  std::uint64_t count_ = 0;
};

/// What colours the points of the bird's-eye view.
enum class ColorBy : std::uint8_t {
  intensity,  ///< Point::intensity (the reflectivity byte)
  height,     ///< Point::z, metres
};

/// Options of the bird's-eye PNG. The view looks down the sensor's Z axis: +x to the right,
/// +y (azimuth 0) up, the sensor at the image centre.
struct PngOptions {
  std::uint32_t width = 1024;   ///< pixels, 64..16384
  std::uint32_t height = 1024;  ///< pixels, 64..16384
  float range_m = 60.0f;        ///< half the shorter image side covers this many metres (> 0)
  ColorBy color_by = ColorBy::intensity;
  /// Values mapped to the two ends of the colour scale (clamped beyond). Both NaN (the default)
  /// means 0..255 for intensity and -3..+3 m for height.
  float color_min = std::numeric_limits<float>::quiet_NaN();
  float color_max = std::numeric_limits<float>::quiet_NaN();
  std::uint32_t point_radius_px = 0;  ///< 0: one pixel per point; r: a (2r+1)-pixel square
  bool range_rings = true;  ///< faint circles every scale step around the sensor
  bool scale_bar = true;    ///< bottom-left bar with ticks and a length label ("20m")
  bool legend = true;       ///< right-hand colour bar with its end values
  PngDeflate deflate = PngDeflate::fixed_huffman;
};

/// Background colour of the bird's-eye view (R, G, B).
inline constexpr std::uint8_t kBackground[3] = {12, 14, 20};

/// Colour of value t in [0, 1] on the view's scale (clamped): a piecewise-linear ramp through
/// blue (40, 70, 230) at 0, cyan (0, 190, 230) at 0.25, green (60, 210, 70) at 0.5,
/// yellow (250, 220, 30) at 0.75 and red (240, 40, 30) at 1.
void color_ramp(float t, std::uint8_t rgb[3]);

/// The bird's-eye view built point by point, in the image's memory (a float per pixel) whatever
/// the number of points: reset() with the options, add() the points, render() the image.
class BirdseyeView {
 public:
  /// Starts an empty view. False (and `error` says why) for invalid options: add() then does
  /// nothing and render() gives an empty image.
  bool reset(const PngOptions& options, std::string* error = nullptr);
  /// Each pixel keeps the largest colour value (intensity or z) of the points that fall on it;
  /// points with non-finite x/y are skipped.
  void add(const Point* points, std::size_t count);
  void add(const Point& p) { add(&p, 1); }
  /// Removes the points, keeps the options.
  void clear();
  /// The image: background, range rings, the points, the sensor, scale bar and legend.
  RgbImage render() const;
  const PngOptions& options() const { return options_; }

 private:
  PngOptions options_;
  double lo_ = 0, hi_ = 255;  // colour values at the two ends of the scale
  double ppm_ = 0;            // pixels per metre
  double cx_ = 0, cy_ = 0;    // the sensor's position in the image, pixels
  std::vector<float> value_;  // per pixel, row by row; empty until a valid reset()
};

/// Draws the bird's-eye view of `points` into an image. Each pixel shows the largest colour
/// value (intensity or z) of the points that fall on it; points with non-finite x/y are skipped.
/// Invalid options give an empty image and `error` says why.
RgbImage render_birdseye(const Point* points, std::size_t count, const PngOptions& options, std::string* error = nullptr);

/// Renders and writes the bird's-eye PNG of a view.
WriteResult write_png(const std::string& path, const BirdseyeView& view);
/// Renders and writes the bird's-eye PNG.
WriteResult write_png(const std::string& path, const Point* points, std::size_t count, const PngOptions& options = {});
WriteResult write_png(const std::string& path, const std::vector<Point>& points, const PngOptions& options = {});

/// Writes `bytes` to `path` (create/truncate), reporting open, write and close failures.
WriteResult write_file(const std::string& path, const std::uint8_t* bytes, std::size_t size);

}  // namespace port
}  // namespace hesai
