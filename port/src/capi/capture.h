// What the files of libhesai_c's capture interface (hesai_capture.h) share: the handle, the sinks
// the engine's Pipeline writes into (rows for hesai_capture_read, columns for
// hesai_capture_read_columns), and the statuses. hesai_capture.cpp opens, counts and describes a
// capture; capture_rows.cpp reads it as rows; capture_columns.cpp as columns.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "hesai_port/capture/capture.h"
#include "hesai_port/hesai_capture.h"
#include "hesai_port/pipeline/pipeline.h"
#include "hesai_port/pipeline/run.h"

namespace hesai::capi {

// hesai_capture.h's return values: the hesai program's exit statuses for the same failures
// (0 success, 1 a bad request, 2 an input that cannot be read).
constexpr int kExitOk = 0;
constexpr int kExitUsage = 1;
constexpr int kExitInput = 2;
int status_code(const port::Status& s);

// `text` into message[0 .. size), cut and NUL-terminated (nothing for a NULL or empty buffer).
void put_message(char* message, std::size_t size, const std::string& text);

// The most sensors a row or a column can name (hesai_capture_row.sensor is 16 bits).
constexpr std::uint32_t kMaxSensors = 65536;

// A frame that closed: the rows given before it, its id and its sensor.
struct Closure {
  std::size_t rows;
  std::uint64_t frame;
  std::uint16_t sensor;
};

// Rows as the CSV sink would write them, where each frame closed among them, and the sensors'
// names (in every mode: the Pipeline names its sensors to its Sink).
class RowSink : public port::Sink {
 public:
  void points(const port::PointRun& run) override;
  void sensor_added(std::uint32_t sensor, const std::string& label) override;
  void receive_time(std::uint64_t) override {}
  void frame_closed(const FrameInfo& frame, std::uint32_t sensor) override;

  // While hesai_capture_read has nothing staged, rows go straight into the caller's array (one
  // copy less); those beyond its capacity are staged in `rows`.
  hesai_capture_row* direct = nullptr;
  std::size_t direct_capacity = 0, direct_n = 0;
  std::vector<hesai_capture_row> rows;                         // from `taken` on: not yet given
  std::size_t taken = 0;
  std::deque<Closure> closures;
  bool discard = false;                                        // stats: counts only
  bool track_closures = true;  // hesai_capture_read was given closed_frame: it stops where frames close
  std::deque<std::string> names;                               // the sensors', by index
  bool too_many = false;                                       // a sensor beyond kMaxSensors came
};

// The columns mode's sink (port::ColumnSink): a packet's points are decoded straight into the
// caller's columns while a whole packet fits there; the absolute time, packet index and sensor
// are written beside them when the Pipeline keeps the packet. What does not fit (the packets
// released at the end of the capture, several sensors' held ones at once) is staged here, in
// order, and given by the next calls.
class ColumnWriter : public port::ColumnSink {
 public:
  PointColumns room() override;
  void kept(std::size_t count, std::uint64_t index, std::uint32_t sensor, const PacketInfo& info) override;

  // A call's columns: the points staged before come first (as many as fit).
  void begin(const hesai_capture_columns& out);
  // The points written into the call's columns; they are the caller's from now on.
  std::size_t end();
  std::size_t written() const { return n_; }
  bool staging() const { return taken_ != staged_; }

 private:
  struct Staged {  // the caller's columns, for points that did not fit in them
    std::vector<float> x, y, z;
    std::vector<std::int64_t> time_ns;
    std::vector<std::uint8_t> intensity, channel, return_index;
    std::vector<std::uint64_t> packet;
    std::vector<std::uint16_t> sensor;
  };
  const hesai_capture_columns* out_ = nullptr;
  std::size_t n_ = 0;       // points written into *out_
  bool direct_ = false;     // the last room() was in *out_
  Staged stage_;
  std::size_t staged_ = 0, taken_ = 0;  // stage_ holds points [taken_, staged_)
  std::int32_t times_[kMaxPointsPerPacket];  // the decoder's times, relative to the packet's
};

}  // namespace hesai::capi

struct hesai_capture {
  hesai::port::CaptureFile file;
  std::string path;
  hesai::capi::RowSink sink;
  hesai::capi::ColumnWriter columns;
  std::unique_ptr<hesai::port::Pipeline> pipeline;
  std::unique_ptr<hesai::port::CaptureFeed> feed;  // the capture to the pipeline
  bool ended = false;  // the pipeline is finished: no more datagrams
  int status = 0;      // the failure that ended it
  std::string error;
  enum class Mode { unread, rows, columns, stats } mode = Mode::unread;
  std::string stats;   // hesai_capture_stats_json's text, once made
  bool columns_refused = false;  // an option hesai_capture_read_columns does not take is set
};

namespace hesai::capi {

// The next datagram to the pipeline; at the end (or the damage) the pipeline is finished.
void feed_next(hesai_capture* c);

}  // namespace hesai::capi
