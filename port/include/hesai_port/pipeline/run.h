// A capture file fed to the engine: one datagram at a time (the C library reads rows between them)
// or the whole file (the program's decode and stats).
#pragma once

#include <cstdint>
#include <functional>

#include "hesai_port/base/status.h"
#include "hesai_port/capture/capture.h"
#include "hesai_port/pipeline/pipeline.h"

namespace hesai::port {

/// Feeds an open capture's datagrams to a Pipeline, each labelled with its sender (source_text)
/// and stamped with its record time.
class CaptureFeed {
 public:
  CaptureFeed(CaptureFile& file, Pipeline& pipeline) : file_(file), pipeline_(pipeline) {}

  /// Feeds the next datagram. False once the feed has ended: at the end of the capture, or at
  /// damage (status() Status::input), after Pipeline::finish(); or when the pipeline stopped at a
  /// configuration error (status() Status::usage, the pipeline left unfinished).
  bool next();
  bool ended() const { return ended_; }
  /// Why the feed ended, once it has: success at the end of a whole capture.
  const Status& status() const { return status_; }
  /// Datagrams fed so far.
  std::uint64_t datagrams() const { return datagrams_; }
  /// How far into the file the last datagram lies, 0..1.
  double fraction() const;

 private:
  CaptureFile& file_;
  Pipeline& pipeline_;
  bool ended_ = false;
  Status status_;
  std::uint64_t datagrams_ = 0;
  std::uint64_t offset_ = 0;
};

/// Feeds the whole capture (CaptureFeed::next until it ends) and returns why it ended.
/// `progress`, when given, is called every 16 384 datagrams.
Status run_capture(CaptureFile& file, Pipeline& pipeline, const std::function<void(const CaptureFeed&)>& progress = {});

}  // namespace hesai::port
