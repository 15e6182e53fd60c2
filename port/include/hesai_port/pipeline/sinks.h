// Where decoded points go: CSV rows and PCD/PLY records written as they come, or bird's-eye PNG
// views; one file for the whole input, or one per sensor and frame; or an MCAP file of one ROS 2
// PointCloud2 message per sensor and frame, on one topic per sensor.
//
// Sensors are kept apart in every output: the CSV's last column `sensor` is the sensor's label
// ("192.168.1.201:2368", a bag's topic); --per-frame files are frame_<token>_<n>; MCAP topics and
// frame ids take the token in place of {sensor}. The token is a ROS 2 name token: "ip_" and the
// address with '_' for '.' (IPv6: "ip6_" and its groups), then "_PORT" for a later sensor at an
// address already named; a bag's topic gives its last token; "source_N" without a label.
#pragma once

#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "hesai_port/base/status.h"
#include "hesai_port/formats/mcap.h"
#include "hesai_port/formats/pointcloud2.h"
#include "hesai_port/formats/writers.h"
#include "hesai_port/pipeline/pipeline.h"

namespace hesai::port {

/// Output options of decode and listen.
struct OutputOptions {
  std::string format = "csv";  ///< csv | pcd | ply | png | mcap
  std::string out;             ///< --out PATH ("-" for stdout, CSV only); a directory with --per-frame
  bool per_frame = false;      ///< one file per sensor and frame: frame_<sensor>_000001.pcd ...
  float png_range_m = 60;      ///< --png-range: metres from the centre to the image edge
  bool png_height = false;     ///< --png-color height (default intensity)
  /// --topic: MCAP channel of the PointCloud2 messages; {sensor} is each sensor's name token.
  std::string topic = "/hesai/{sensor}/points";
  std::string frame_id = "hesai_{sensor}";  ///< --frame-id: their header.frame_id
  std::string ros_distro = "humble";        ///< --ros-distro: the bag's rosbag2 metadata record
};

/// `text` with every "{sensor}" replaced by `token`.
std::string with_sensor(const std::string& text, const std::string& token);

/// Writes the points in the chosen format. open() checks the destination before any decoding.
class OutputSink : public Sink {
 public:
  explicit OutputSink(const OutputOptions& o);
  /// Prepares the destination: creates the --per-frame directory, opens the CSV file or the PCD/PLY
  /// file (written as a stream, its header's count rewritten by close()). Status::usage: no --out
  /// where one is needed, a pipe for PCD/PLY; Status::input: the output cannot be created.
  Status open();
  void sensor_added(std::uint32_t sensor, const std::string& label) override;
  void receive_time(std::uint64_t ns) override { receive_ns_ = ns; }
  void points(const PointRun& run) override;
  void frame_closed(const FrameInfo& frame, std::uint32_t sensor) override;
  bool wants_return_types() const override { return format_ == Format::mcap; }
  /// Writes what is still held (the single PNG), closes the file. Status::input when a write failed.
  /// Memory: the open frames' points or PNG views with --per-frame, and the open frames' encoded
  /// PointCloud2 data for MCAP (32 bytes a point; two frames near a cut, where a packet gives
  /// points to both); otherwise a block of output or the PNG's pixels, whatever the number of points.
  Status close();
  /// Files written so far.
  const std::vector<std::string>& files() const { return files_; }
  std::uint64_t points_written() const { return points_written_; }

 private:
  // What --per-frame holds of a frame until it closes.
  struct Frame {
    std::vector<Point> points;           // CSV, PCD, PLY
    std::vector<std::uint64_t> packets;  // packet index of each point (CSV)
    PointCloud2Data cloud;               // MCAP: the message's data, encoded as the points come
    BirdseyeView png;                    // PNG
  };
  // What each sensor's outputs need.
  struct SensorOut {
    std::string label;  // the CSV's `sensor` column (quoted where CSV needs it)
    std::string token;  // {sensor}: a ROS 2 name token
    std::uint16_t channel = 0;  // MCAP: its topic's channel
    std::string frame_id;       // MCAP: header.frame_id
  };
  using FrameKey = std::pair<std::uint32_t, std::uint64_t>;  // sensor, frame id

  bool write_cloud(const std::string& path, const std::vector<Point>& points, const BirdseyeView& png,
                   std::string& error);
  std::string frame_path(FrameKey key) const;
  Status open_mcap();
  void write_mcap_frame(FrameKey key, PointCloud2Data& cloud);
  Frame& open_frame(FrameKey key);
  const SensorOut& sensor(std::uint32_t s) const;

  // options_.format, read once (not compared as text at every point).
  enum class Format : std::uint8_t { csv, pcd, ply, png, mcap };

  OutputOptions options_;
  Format format_ = Format::csv;
  CsvWriter csv_;
  bool csv_open_ = false;
  CloudWriter stream_;    // the single PCD or PLY file
  McapWriter mcap_;      // --format mcap
  std::uint16_t mcap_schema_ = 0;
  std::map<std::string, std::uint16_t> mcap_topics_;  // topic -> channel
  std::uint64_t receive_ns_ = 0;   // receive_time()
  std::uint64_t last_log_ns_ = 0;  // the last message's log_time (they never go back)
  std::vector<SensorOut> sensors_;  // by sensor
  std::size_t mcap_frame_points_ = 0;  // the largest frame written to the MCAP file so far
  PointCloud2Data spare_cloud_;        // a written MCAP frame's storage, for the next frame
  BirdseyeView png_;      // the PNG of every point; with --per-frame, the empty view each frame starts from
  std::map<FrameKey, Frame> open_;  // --per-frame and MCAP: the frames not yet closed
  std::vector<std::string> files_;
  std::uint64_t points_written_ = 0;
  std::string deferred_error_;
};

}  // namespace hesai::port
