// hesai_capture.h: the engine's capture feed and Pipeline (hesai_port/pipeline/) behind a C
// interface, for libhesai_c (and through it the Python package): datagrams are fed (CaptureFeed)
// only while the caller wants more rows or columns. This file opens, counts and describes a
// capture; capture_rows.cpp reads it as rows, capture_columns.cpp as columns (the Pipeline's
// columns mode).
#include "hesai_port/hesai_capture.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <memory>
#include <new>
#include <string>

#include "capture.h"
#include "hesai/ct.h"
#include "hesai/hesai.h"
#include "hesai_port/pipeline/report.h"

// The layout python/hesai/_lib.py (ROW_DTYPE) reads.
static_assert(sizeof(hesai_capture_row) == 56 && offsetof(hesai_capture_row, frame) == 0 &&
              offsetof(hesai_capture_row, packet) == 8 && offsetof(hesai_capture_row, time_ns) == 16 &&
              offsetof(hesai_capture_row, azimuth_deg) == 24 && offsetof(hesai_capture_row, elevation_deg) == 28 &&
              offsetof(hesai_capture_row, distance_m) == 32 && offsetof(hesai_capture_row, x) == 36 &&
              offsetof(hesai_capture_row, y) == 40 && offsetof(hesai_capture_row, z) == 44 &&
              offsetof(hesai_capture_row, block) == 48 && offsetof(hesai_capture_row, channel) == 49 &&
              offsetof(hesai_capture_row, return_index) == 50 && offsetof(hesai_capture_row, intensity) == 51 &&
              offsetof(hesai_capture_row, sensor) == 52);

namespace hesai::capi {

int status_code(const port::Status& s) {
  switch (s.fault()) {
    case port::Fault::none: return kExitOk;
    case port::Fault::usage: return kExitUsage;
    case port::Fault::input: return kExitInput;
  }
  return kExitInput;
}

void put_message(char* message, std::size_t size, const std::string& text) {
  if (message == nullptr || size == 0) return;
  const std::size_t n = std::min(size - 1, text.size());
  std::memcpy(message, text.data(), n);
  message[n] = '\0';
}

void feed_next(hesai_capture* c) {
  if (c->feed->next()) {
    if (c->sink.too_many && !c->sink.discard) {  // rows and columns cannot name the sensor: stop
      c->status = kExitInput;
      c->error = "more than 65536 sensors in the capture";
      c->ended = true;
    }
    return;
  }
  c->status = status_code(c->feed->status());  // 0 at the end of a whole capture
  c->error = c->feed->status().message();
  c->ended = true;
}

namespace {

// Feeds the pipeline the rest of the capture, as run_capture does. Returns false when the
// pipeline stops (a configuration error: c->status kExitUsage).
bool feed_all(hesai_capture* c) {
  while (!c->ended) feed_next(c);
  return c->status != kExitUsage;
}

}  // namespace

}  // namespace hesai::capi

using namespace hesai::capi;  // capture.h: the handle, the sinks, the statuses

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
  using namespace hesai::port;
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
    c->path = path;
    // What hesai_capture_read_columns takes: no frames, no per-point selection.
    c->columns_refused = o.cut_angle_deg != 0.0f || o.has_fov != 0 || o.min_range_m != 0.0f ||
                         o.max_range_m != 1e9f || o.returns != 0;
    if (c->file.open(path) != hesai::port::CaptureError::ok) {
      put_message(message, message_size, c->file.message());
      hesai::secure_wipe(d.session_key.data(), d.session_key.size());
      return kExitInput;
    }
    c->pipeline = std::make_unique<Pipeline>(d, &c->sink);
    hesai::secure_wipe(d.session_key.data(), d.session_key.size());
    if (const Status s = c->pipeline->load_files(); !s.ok()) {
      put_message(message, message_size, s.message());
      return status_code(s);
    }
    c->feed = std::make_unique<CaptureFeed>(c->file, *c->pipeline);
    *out = c.release();
    return kExitOk;
  } catch (const std::bad_alloc&) {
    put_message(message, message_size, "out of memory");
    return kExitInput;
  }
}

std::size_t hesai_capture_sensors(const hesai_capture* c) noexcept { return c == nullptr ? 0 : c->sink.names.size(); }

const char* hesai_capture_sensor_name(const hesai_capture* c, std::size_t index) noexcept {
  if (c == nullptr || index >= c->sink.names.size()) return nullptr;
  return c->sink.names[index].c_str();
}

std::uint64_t hesai_capture_packets(const hesai_capture* c) noexcept {
  return c == nullptr ? 0 : c->pipeline->stats().packets;
}

int hesai_capture_bound(const hesai_capture* c, std::uint64_t* datagrams, std::uint64_t* points, char* message,
                        std::size_t message_size) noexcept {
  if (c == nullptr || datagrams == nullptr || points == nullptr) return kExitUsage;
  *datagrams = 0;
  *points = 0;
  try {
    hesai::port::CaptureFile file;
    if (file.open(c->path) != hesai::port::CaptureError::ok) {
      put_message(message, message_size, file.message());
      return kExitInput;
    }
    hesai::port::UdpDatagram d;
    while (file.next(d) == hesai::port::CaptureStatus::datagram) {
      ++*datagrams;
      hesai::Model model = hesai::Model::unknown;
      hesai::PacketKind kind = hesai::PacketKind::gps;
      if (hesai::identify(d.payload, model, kind) == hesai::Error::ok && kind == hesai::PacketKind::point_cloud)
        *points += hesai::max_points(model);
    }
    return kExitOk;
  } catch (const std::bad_alloc&) {
    put_message(message, message_size, "out of memory");
    return kExitInput;
  }
}

int hesai_capture_stats_json(hesai_capture* c, char* json, std::size_t size, std::size_t* length, char* message,
                             std::size_t message_size) noexcept {
  using namespace hesai::port;
  if (length != nullptr) *length = 0;
  if (c == nullptr || json == nullptr || length == nullptr || size == 0) return kExitUsage;
  json[0] = '\0';
  if (c->mode == hesai_capture::Mode::columns) {
    put_message(message, message_size, "a capture read as columns has no counts");
    return kExitUsage;
  }
  try {
    if (c->mode != hesai_capture::Mode::stats) {
      c->mode = hesai_capture::Mode::stats;
      c->sink.discard = true;
      c->sink.rows.clear();
      c->sink.taken = 0;
      c->sink.closures.clear();
      if (feed_all(c)) {
        c->pipeline->set_ip_fragments(c->file.stats().fragments);
        c->stats = stats_json(c->pipeline->stats(), c->pipeline->sensors());
      }
    }
    if (c->status == kExitUsage) {  // as the program: no counts
      put_message(message, message_size, c->error);
      return kExitUsage;
    }
    put_message(json, size, c->stats);
    *length = c->stats.size();
    if (c->status != kExitOk) put_message(message, message_size, c->error);
    return c->status;
  } catch (const std::bad_alloc&) {
    put_message(message, message_size, "out of memory");
    return kExitInput;
  }
}

std::size_t hesai_capture_layout(int which, const char* name) noexcept {
  struct Member {
    const char* name;
    std::size_t offset;
  };
  static constexpr Member kRow[] = {
      {"frame", offsetof(hesai_capture_row, frame)},         {"packet", offsetof(hesai_capture_row, packet)},
      {"block", offsetof(hesai_capture_row, block)},         {"channel", offsetof(hesai_capture_row, channel)},
      {"return", offsetof(hesai_capture_row, return_index)}, {"azimuth_deg", offsetof(hesai_capture_row, azimuth_deg)},
      {"elevation_deg", offsetof(hesai_capture_row, elevation_deg)},
      {"distance_m", offsetof(hesai_capture_row, distance_m)}, {"x", offsetof(hesai_capture_row, x)},
      {"y", offsetof(hesai_capture_row, y)},                 {"z", offsetof(hesai_capture_row, z)},
      {"intensity", offsetof(hesai_capture_row, intensity)}, {"time_ns", offsetof(hesai_capture_row, time_ns)},
      {"sensor", offsetof(hesai_capture_row, sensor)},
  };
  static constexpr Member kPoint[] = {
      {"x", offsetof(hesai_point, x)},
      {"y", offsetof(hesai_point, y)},
      {"z", offsetof(hesai_point, z)},
      {"distance_m", offsetof(hesai_point, distance_m)},
      {"azimuth_deg", offsetof(hesai_point, azimuth_deg)},
      {"elevation_deg", offsetof(hesai_point, elevation_deg)},
      {"time_ns", offsetof(hesai_point, time_ns)},
      {"intensity", offsetof(hesai_point, intensity)},
      {"channel", offsetof(hesai_point, channel)},
      {"return", offsetof(hesai_point, return_index)},
      {"confidence", offsetof(hesai_point, confidence)},
      {"block", offsetof(hesai_point, block)},
  };
  if (which != 0 && which != 1) return SIZE_MAX;
  if (name == nullptr) return which == 0 ? sizeof(hesai_capture_row) : sizeof(hesai_point);
  if (which == 0) {
    for (const Member& m : kRow)
      if (std::strcmp(m.name, name) == 0) return m.offset;
  } else {
    for (const Member& m : kPoint)
      if (std::strcmp(m.name, name) == 0) return m.offset;
  }
  return SIZE_MAX;
}

void hesai_capture_close(hesai_capture* c) noexcept { delete c; }

}  // extern "C"
