// Where decoded points go: CSV rows and PCD/PLY records written as they come, or bird's-eye PNG
// views; one file for the whole input, or one per frame; or an MCAP file of one ROS 2
// PointCloud2 message per frame.
#pragma once

#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "hesai_port/formats/mcap.h"
#include "hesai_port/formats/writers.h"
#include "options.h"
#include "pipeline.h"

namespace hesai::cli {

/// Writes the points in the chosen format. open() checks the destination before any decoding.
class OutputSink : public Sink {
 public:
  explicit OutputSink(const OutputOptions& o);
  /// Prepares the destination: creates the --per-frame directory, opens the CSV file or the PCD/PLY
  /// file (written as a stream, its header's count rewritten by close()). Returns kExitOk,
  /// kExitUsage (no --out where one is needed; a pipe for PCD/PLY) or kExitInput (the output
  /// cannot be created), with a message.
  int open(std::string& error);
  void points(const OutPoint* p, std::size_t count) override;
  void frame_closed(const FrameInfo& frame) override;
  /// Writes what is still held (the single PNG), closes the file. Returns false with a message.
  /// Memory: the open frames' points or PNG views with --per-frame, and the open frames' points
  /// for MCAP (two frames near a cut, where a packet gives points to both); otherwise a block of
  /// output or the PNG's pixels, whatever the number of points.
  bool close(std::string& error);
  /// Files written so far.
  const std::vector<std::string>& files() const { return files_; }
  std::uint64_t points_written() const { return points_written_; }

 private:
  // What --per-frame holds of a frame until it closes.
  struct Frame {
    std::vector<Point> points;           // CSV, PCD, PLY
    std::vector<std::uint64_t> packets;  // packet index of each point (CSV)
    port::BirdseyeView png;              // PNG
  };
  bool write_cloud(const std::string& path, const std::vector<Point>& points, const port::BirdseyeView& png,
                   std::string& error);
  std::string frame_path(std::uint64_t id) const;
  int open_mcap(std::string& error);
  void write_mcap_frame(std::uint64_t id, const std::vector<Point>& points);
  Frame& open_frame(std::uint64_t id);

  // options_.format, read once (not compared as text at every point).
  enum class Format : std::uint8_t { csv, pcd, ply, png, mcap };

  OutputOptions options_;
  Format format_ = Format::csv;
  port::CsvWriter csv_;
  bool csv_open_ = false;
  port::CloudWriter stream_;    // the single PCD or PLY file
  port::McapWriter mcap_;      // --format mcap
  std::uint16_t mcap_channel_ = 0;
  std::size_t mcap_frame_points_ = 0;  // the largest frame written to the MCAP file so far
  std::vector<Point> spare_points_;     // a written MCAP frame's storage, for the next frame
  port::BirdseyeView png_;      // the PNG of every point; with --per-frame, the empty view each frame starts from
  std::map<std::uint64_t, Frame> open_;  // --per-frame and MCAP: the frames not yet closed, by id
  std::vector<Point> run_;  // the points of one frame of a packet, for the one file's writer (reused)
  std::vector<std::string> files_;
  std::uint64_t points_written_ = 0;
  std::string deferred_error_;
};

}  // namespace hesai::cli
