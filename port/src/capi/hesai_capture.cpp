// hesai_capture.h: the hesai program's capture reader and Pipeline behind a C interface, for
// libhesai_c (and through it the Python package). The loop is run_capture's (port/src/cli/main.cpp)
// turned inside out: datagrams are fed only while the caller wants more rows.
#include "hesai_port/hesai_capture.h"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <deque>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "../cli/options.h"
#include "../cli/pipeline.h"
#include "hesai/ct.h"
#include "hesai_port/capture/capture.h"

// The layout python/hesai/_lib.py (ROW_DTYPE) reads.
static_assert(sizeof(hesai_capture_row) == 56 && offsetof(hesai_capture_row, frame) == 0 &&
              offsetof(hesai_capture_row, packet) == 8 && offsetof(hesai_capture_row, time_ns) == 16 &&
              offsetof(hesai_capture_row, azimuth_deg) == 24 && offsetof(hesai_capture_row, elevation_deg) == 28 &&
              offsetof(hesai_capture_row, distance_m) == 32 && offsetof(hesai_capture_row, x) == 36 &&
              offsetof(hesai_capture_row, y) == 40 && offsetof(hesai_capture_row, z) == 44 &&
              offsetof(hesai_capture_row, block) == 48 && offsetof(hesai_capture_row, channel) == 49 &&
              offsetof(hesai_capture_row, return_index) == 50 && offsetof(hesai_capture_row, intensity) == 51);

namespace {

using hesai::cli::OutPoint;

void put_message(char* message, std::size_t size, const std::string& text) {
  if (message == nullptr || size == 0) return;
  const std::size_t n = std::min(size - 1, text.size());
  std::memcpy(message, text.data(), n);
  message[n] = '\0';
}

// Rows as the CSV sink would write them, and where each frame closed among them.
class RowSink : public hesai::cli::Sink {
 public:
  void points(const OutPoint* p, std::size_t count) override {
    for (std::size_t i = 0; i < count; ++i) add(p[i]);
  }
  // The rows do not name their sensor yet (hesai_capture_row has no such field): frames of several
  // sensors are told apart only by their ids.
  void sensor_added(std::uint32_t, const std::string&) override {}
  void receive_time(std::uint64_t) override {}
  void frame_closed(const hesai::FrameInfo& frame, std::uint32_t) override { closures.emplace_back(rows.size(), frame.id); }

  std::vector<hesai_capture_row> rows;                         // from `taken` on: not yet given
  std::size_t taken = 0;
  std::deque<std::pair<std::size_t, std::uint64_t>> closures;  // (rows before the close, frame id)

 private:
  void add(const OutPoint& p) {
    hesai_capture_row r;
    r.frame = p.frame;
    r.packet = p.packet;
    r.time_ns = p.point.time_ns;
    r.azimuth_deg = p.point.azimuth_deg;
    r.elevation_deg = p.point.elevation_deg;
    r.distance_m = p.point.distance_m;
    r.x = p.point.x;
    r.y = p.point.y;
    r.z = p.point.z;
    r.block = p.point.block;
    r.channel = p.point.channel;
    r.return_index = p.point.return_index;
    r.intensity = p.point.intensity;
    rows.push_back(r);
  }
};

}  // namespace

struct hesai_capture {
  hesai::port::CaptureFile file;
  RowSink sink;
  std::unique_ptr<hesai::cli::Pipeline> pipeline;
  bool ended = false;  // the pipeline is finished: no more datagrams
  int status = 0;      // the failure that ended it
  std::string error;
};

extern "C" {

void hesai_capture_default_options(hesai_capture_options* o) noexcept {
  if (o == nullptr) return;
  *o = hesai_capture_options{};
  o->reflectivity = 0;
  o->firetime_azimuth = 1;
  o->rotation = -1;
  o->first_packet = 0;
  o->end_packet = UINT64_MAX;
  o->min_range_m = 0;
  o->max_range_m = 1e9f;
}

int hesai_capture_open(const char* path, const hesai_capture_options* options, hesai_capture** out, char* message,
                       std::size_t message_size) noexcept {
  using namespace hesai::cli;
  if (out == nullptr) return kExitUsage;
  *out = nullptr;
  if (path == nullptr) {
    put_message(message, message_size, "no capture path");
    return kExitUsage;
  }
  hesai_capture_options defaults;
  hesai_capture_default_options(&defaults);
  const hesai_capture_options& o = options != nullptr ? *options : defaults;
  try {
    // The option rules of options.cpp (parse_decode_option).
    DecodeOptions d;
    if (o.calibration != nullptr) d.calibration_path = o.calibration;
    if (o.firetimes != nullptr) d.firetimes_path = o.firetimes;
    if (o.channel_config != nullptr) d.channel_config_path = o.channel_config;
    if (o.reflectivity != 0 && o.reflectivity != 1) {
      put_message(message, message_size, "reflectivity takes raw or nonlinear");
      return kExitUsage;
    }
    d.reflectivity = o.reflectivity == 1 ? hesai::Reflectivity::nonlinear : hesai::Reflectivity::raw;
    d.firetime_azimuth = o.firetime_azimuth != 0;
    if (o.rotation < -1 || o.rotation > 1) {
      put_message(message, message_size, "rotation takes auto, cw or ccw");
      return kExitUsage;
    }
    d.detect_rotation = o.rotation == -1;
    d.rotation = o.rotation == 1 ? hesai::Rotation::counterclockwise : hesai::Rotation::clockwise;
    if (o.end_packet < o.first_packet) {
      put_message(message, message_size, "packets takes FIRST:END with FIRST <= END");
      return kExitUsage;
    }
    d.first_packet = o.first_packet;
    d.end_packet = o.end_packet;
    if (d.frames.set_cut_deg(o.cut_angle_deg) != hesai::Error::ok) {
      put_message(message, message_size, "cut angle takes degrees in [0, 360)");
      return kExitUsage;
    }
    if (o.has_fov != 0 && d.frames.set_fov_deg(o.fov_start_deg, o.fov_end_deg) != hesai::Error::ok) {
      put_message(message, message_size, "fov takes START:END in degrees (0..360, START != END)");
      return kExitUsage;
    }
    if (!(o.min_range_m >= 0) || !(o.max_range_m >= 0)) {
      put_message(message, message_size, "ranges take metres >= 0");
      return kExitUsage;
    }
    d.min_range = o.min_range_m;
    d.max_range = o.max_range_m;
    if (o.session_key != nullptr) {
      d.has_key = true;
      std::memcpy(d.session_key.data(), o.session_key, d.session_key.size());
    }
    d.allow_unsigned = o.allow_unsigned != 0;
    if (o.returns != 0 && o.returns != 1) {
      put_message(message, message_size, "returns takes all or distinct");
      return kExitUsage;
    }
    d.returns = o.returns == 1 ? hesai::Returns::distinct : hesai::Returns::all;

    auto c = std::make_unique<hesai_capture>();
    if (c->file.open(path) != hesai::port::CaptureError::ok) {
      put_message(message, message_size, c->file.message());
      hesai::secure_wipe(d.session_key.data(), d.session_key.size());
      return kExitInput;
    }
    c->pipeline = std::make_unique<Pipeline>(d, &c->sink);
    hesai::secure_wipe(d.session_key.data(), d.session_key.size());
    std::string error;
    if (const int rc = c->pipeline->load_files(error); rc != kExitOk) {
      put_message(message, message_size, error);
      return rc;
    }
    *out = c.release();
    return kExitOk;
  } catch (const std::bad_alloc&) {
    put_message(message, message_size, "out of memory");
    return kExitInput;
  }
}

int hesai_capture_read(hesai_capture* c, hesai_capture_row* rows, std::size_t capacity, std::size_t* count,
                       std::uint64_t* closed_frame, char* message, std::size_t message_size) noexcept {
  using namespace hesai::cli;
  if (count != nullptr) *count = 0;
  if (closed_frame != nullptr) *closed_frame = 0;
  if (c == nullptr || count == nullptr || rows == nullptr || capacity == 0) return kExitUsage;
  RowSink& s = c->sink;
  try {
    for (;;) {
      const std::size_t available = s.rows.size() - s.taken;
      const bool closes = !s.closures.empty() && s.closures.front().first - s.taken <= capacity;
      if (closes || available >= capacity || c->ended) {
        const std::size_t n = closes ? s.closures.front().first - s.taken : std::min(available, capacity);
        if (n != 0) std::memcpy(rows, s.rows.data() + s.taken, n * sizeof(hesai_capture_row));
        s.taken += n;
        *count = n;
        if (closes) {
          if (closed_frame != nullptr) *closed_frame = s.closures.front().second;
          s.closures.pop_front();
        }
        if (s.taken >= 65536 || s.taken == s.rows.size()) {  // drop what was given
          s.rows.erase(s.rows.begin(), s.rows.begin() + static_cast<std::ptrdiff_t>(s.taken));
          for (auto& closure : s.closures) closure.first -= s.taken;
          s.taken = 0;
        }
        if (n == 0 && !closes && c->status != kExitOk) {
          put_message(message, message_size, c->error);
          return c->status;
        }
        return kExitOk;
      }
      // More rows are wanted: the next datagram, as run_capture feeds it.
      hesai::port::UdpDatagram d;
      const hesai::port::CaptureStatus st = c->file.next(d);
      if (st == hesai::port::CaptureStatus::datagram) {
        if (!c->pipeline->feed(d.payload, source_key(d))) {  // the program stops here, unfinished
          c->status = kExitUsage;
          c->error = c->pipeline->error();
          c->ended = true;
        }
        continue;
      }
      if (st == hesai::port::CaptureStatus::error) {
        c->status = kExitInput;
        c->error = c->file.message();
      }
      c->pipeline->finish();
      c->ended = true;
    }
  } catch (const std::bad_alloc&) {
    put_message(message, message_size, "out of memory");
    return kExitInput;
  }
}

std::uint64_t hesai_capture_packets(const hesai_capture* c) noexcept {
  return c == nullptr ? 0 : c->pipeline->stats().packets;
}

void hesai_capture_close(hesai_capture* c) noexcept { delete c; }

}  // extern "C"
