// Where decoded points go: CSV rows and PCD/PLY records written as they come, or bird's-eye PNG
// views; one file for the whole input, or one per frame.
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "hesai_port/writers.h"
#include "options.h"
#include "pipeline.h"

namespace hesai::cli {

/// Writes the points in the chosen format. open() checks the destination before any decoding.
class OutputSink : public Sink {
 public:
  explicit OutputSink(const OutputOptions& o) : options_(o) {}
  /// Prepares the destination: creates the --per-frame directory, opens the CSV file or the PCD/PLY
  /// file (written as a stream, its header's count rewritten by close()). Returns kExitOk,
  /// kExitUsage (no --out where one is needed; a pipe for PCD/PLY) or kExitInput (the output
  /// cannot be created), with a message.
  int open(std::string& error);
  void point(const OutPoint& p) override;
  void frame_closed(const FrameInfo& frame) override;
  /// Writes what is still held (the single PNG), closes the file. Returns false with a message.
  /// Memory: one frame's points with --per-frame (CSV, PCD, PLY); otherwise a block of output or
  /// the PNG's pixels, whatever the number of points.
  bool close(std::string& error);
  /// Files written so far.
  const std::vector<std::string>& files() const { return files_; }
  std::uint64_t points_written() const { return points_written_; }

 private:
  bool write_cloud(const std::string& path, std::string& error);
  std::string frame_path(std::uint64_t id) const;

  OutputOptions options_;
  port::CsvWriter csv_;
  bool csv_open_ = false;
  port::CloudWriter stream_;    // the single PCD or PLY file
  port::BirdseyeView png_;      // the PNG of the current frame (--per-frame) or of every point
  std::vector<Point> cloud_;    // the current frame (--per-frame CSV, PCD, PLY)
  std::vector<std::uint64_t> packets_;  // packet index of each point in cloud_ (per-frame CSV)
  std::vector<std::string> files_;
  std::uint64_t points_written_ = 0;
  std::string deferred_error_;
};

}  // namespace hesai::cli
