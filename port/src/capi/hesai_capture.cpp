// hesai_capture.h: the engine's capture feed and Pipeline (hesai_port/pipeline/) behind a C
// interface, for libhesai_c (and through it the Python package): datagrams are fed (CaptureFeed)
// only while the caller wants more rows.
#include "hesai_port/hesai_capture.h"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <deque>
#include <map>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "hesai/ct.h"
#include "hesai/gps.h"
#include "hesai/hesai.h"
#include "hesai_port/capture/capture.h"
#include "hesai_port/pipeline/pipeline.h"
#include "hesai_port/pipeline/report.h"
#include "hesai_port/pipeline/run.h"

// The layout python/hesai/_lib.py (ROW_DTYPE) reads.
static_assert(sizeof(hesai_capture_row) == 56 && offsetof(hesai_capture_row, frame) == 0 &&
              offsetof(hesai_capture_row, packet) == 8 && offsetof(hesai_capture_row, time_ns) == 16 &&
              offsetof(hesai_capture_row, azimuth_deg) == 24 && offsetof(hesai_capture_row, elevation_deg) == 28 &&
              offsetof(hesai_capture_row, distance_m) == 32 && offsetof(hesai_capture_row, x) == 36 &&
              offsetof(hesai_capture_row, y) == 40 && offsetof(hesai_capture_row, z) == 44 &&
              offsetof(hesai_capture_row, block) == 48 && offsetof(hesai_capture_row, channel) == 49 &&
              offsetof(hesai_capture_row, return_index) == 50 && offsetof(hesai_capture_row, intensity) == 51 &&
              offsetof(hesai_capture_row, sensor) == 52);

namespace {

using hesai::port::PointRun;

// hesai_capture.h's return values: the hesai program's exit statuses for the same failures
// (0 success, 1 a bad request, 2 an input that cannot be read).
constexpr int kExitOk = 0;
constexpr int kExitUsage = 1;
constexpr int kExitInput = 2;
int status_code(const hesai::port::Status& s) {
  switch (s.fault()) {
    case hesai::port::Fault::none: return kExitOk;
    case hesai::port::Fault::usage: return kExitUsage;
    case hesai::port::Fault::input: return kExitInput;
  }
  return kExitInput;
}

void put_message(char* message, std::size_t size, const std::string& text) {
  if (message == nullptr || size == 0) return;
  const std::size_t n = std::min(size - 1, text.size());
  std::memcpy(message, text.data(), n);
  message[n] = '\0';
}

// The most sensors a row can name (hesai_capture_row.sensor is 16 bits).
constexpr std::uint32_t kMaxSensors = 65536;

// A frame that closed: the rows given before it, its id and its sensor.
struct Closure {
  std::size_t rows;
  std::uint64_t frame;
  std::uint16_t sensor;
};

// Rows as the CSV sink would write them, and where each frame closed among them.
class RowSink : public hesai::port::Sink {
 public:
  // A run of one packet's points of one frame: those that fit go straight into the caller's
  // rows, the rest to the staging rows.
  void points(const PointRun& run) override {
    if (discard || run.count == 0 || run.sensor >= kMaxSensors) return;
    const std::size_t direct_count = std::min(run.count, direct_capacity - direct_n);
    hesai_capture_row* out = direct + direct_n;
    for (std::size_t i = 0; i < direct_count; ++i) out[i] = row(run, run.points[i]);
    direct_n += direct_count;
    for (std::size_t i = direct_count; i < run.count; ++i) rows.push_back(row(run, run.points[i]));
  }
  void sensor_added(std::uint32_t sensor, const std::string& label) override {
    if (sensor >= kMaxSensors) {
      too_many = true;
      return;
    }
    if (names.size() <= sensor) names.resize(sensor + 1);  // a deque: the names given stay put
    names[sensor] = label;
  }
  void receive_time(std::uint64_t) override {}
  void frame_closed(const hesai::FrameInfo& frame, std::uint32_t sensor) override {
    if (!discard && track_closures && sensor < kMaxSensors)
      closures.push_back(Closure{direct_n + rows.size(), frame.id, static_cast<std::uint16_t>(sensor)});
  }

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

 private:
  static hesai_capture_row row(const PointRun& run, const hesai::Point& p) {
    hesai_capture_row r;
    r.frame = run.frame;
    r.packet = run.packet;
    r.time_ns = p.time_ns;
    r.azimuth_deg = p.azimuth_deg;
    r.elevation_deg = p.elevation_deg;
    r.distance_m = p.distance_m;
    r.x = p.x;
    r.y = p.y;
    r.z = p.z;
    r.block = p.block;
    r.channel = p.channel;
    r.return_index = p.return_index;
    r.intensity = p.intensity;
    r.sensor = static_cast<std::uint16_t>(run.sensor);
    return r;
  }
};

// One sensor of hesai_capture_read_columns: the Pipeline's Source without its accounting.
struct ColumnSource {
  std::unique_ptr<hesai::Decoder> decoder;
  hesai::RotationDetector rotation;
  hesai::HeldPackets<hesai::port::Pipeline::kHeldPackets> held;  // tagged with the packet's index
  std::uint16_t sensor = 0;  // its index, as the Pipeline numbers them
};

}  // namespace

struct hesai_capture {
  hesai::port::CaptureFile file;
  std::string path;
  RowSink sink;
  std::unique_ptr<hesai::port::Pipeline> pipeline;
  std::unique_ptr<hesai::port::CaptureFeed> feed;  // the capture to the pipeline
  bool ended = false;  // the pipeline is finished: no more datagrams
  int status = 0;      // the failure that ended it
  std::string error;
  enum class Mode { unread, rows, columns, stats } mode = Mode::unread;
  std::string stats;   // hesai_capture_stats_json's text, once made

  // hesai_capture_read_columns: the options it takes, and its state.
  bool columns_refused = false;  // an option it does not take is set
  bool detect_rotation = true;
  std::uint64_t first_packet = 0, end_packet = UINT64_MAX;
  std::map<std::uint64_t, ColumnSource> sources;  // by source_key, as the Pipeline's
  hesai::GpsPacket gps{};
  bool have_gps = false;
  std::uint64_t index = 0;  // point-cloud packets decoded
  std::uint64_t sources_made = 0;  // sensors numbered so far (the Pipeline's sources_made_)
  hesai::port::UdpDatagram pending;  // read, not yet decoded (no room left)
  bool has_pending = false;
  bool finishing = false;   // the input ended: the held packets are being released
  std::int32_t times[HESAI_MAX_POINTS_PER_PACKET];
};

namespace {

// The next datagram to the pipeline; at the end (or the damage) the pipeline is finished.
void feed_next(hesai_capture* c) {
  if (c->feed->next()) {
    if (c->sink.too_many && !c->sink.discard) {  // rows cannot name the sensor: stop
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

// Feeds the pipeline the rest of the capture, as run_capture does. Returns false when the
// pipeline stops (a configuration error: c->status kExitUsage).
bool feed_all(hesai_capture* c) {
  while (!c->ended) feed_next(c);
  return c->status != kExitUsage;
}

// Decodes `payload` of `src` into the columns at `at` (room for a packet checked by the caller);
// the points count only when the caller advances past them. Error as the decoder's.
hesai::Error decode_columns_at(hesai_capture* c, ColumnSource& src, hesai::ByteView payload, const hesai_capture_columns& out,
                               std::size_t at, hesai::PacketInfo& info, std::size_t& count) {
  const hesai::PointColumns cols{out.x + at, out.y + at, out.z + at, c->times, out.intensity + at, out.channel + at,
                                 out.return_index + at, HESAI_MAX_POINTS_PER_PACKET};
  return src.decoder->decode(payload, info, cols, count);
}

// A decoded packet's points kept (Pipeline::process without its accounting): the absolute times
// and the packet index written; the number of points to advance by (0 outside --packets).
std::size_t keep_columns(hesai_capture* c, const hesai_capture_columns& out, std::size_t at, std::uint64_t index,
                         std::uint16_t src_sensor, const hesai::PacketInfo& info, std::size_t count) {
  if (index < c->first_packet || index >= c->end_packet) return 0;
  for (std::size_t i = 0; i < count; ++i) out.time_ns[at + i] = info.time_ns + c->times[i];
  if (out.packet != nullptr)
    for (std::size_t i = 0; i < count; ++i) out.packet[at + i] = index;
  if (out.sensor != nullptr)
    for (std::size_t i = 0; i < count; ++i) out.sensor[at + i] = src_sensor;
  return count;
}

// Pipeline::release_held: the oldest held packet decoded in the decoder's direction, at `at`.
std::size_t release_held_columns(hesai_capture* c, ColumnSource& src, const hesai_capture_columns& out, std::size_t at) {
  const hesai::ByteView payload = src.held.front();
  const std::uint64_t index = src.held.front_tag();
  hesai::PacketInfo info;
  std::size_t count = 0;
  const hesai::Error e = decode_columns_at(c, src, payload, out, at, info, count);
  src.held.pop_front();
  if (e != hesai::Error::ok) return 0;  // it decoded when it came; as the Pipeline, skipped
  return keep_columns(c, out, at, index, src.sensor, info, count);
}

}  // namespace

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
    c->detect_rotation = d.detect_rotation;
    c->first_packet = d.first_packet;
    c->end_packet = d.end_packet;
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

int hesai_capture_read(hesai_capture* c, hesai_capture_row* rows, std::size_t capacity, std::size_t* count,
                       std::uint64_t* closed_frame, std::uint16_t* closed_sensor, char* message,
                       std::size_t message_size) noexcept {
  using namespace hesai::port;
  if (count != nullptr) *count = 0;
  if (closed_frame != nullptr) *closed_frame = 0;
  if (closed_sensor != nullptr) *closed_sensor = 0;
  if (c == nullptr || count == nullptr || rows == nullptr || capacity == 0) return kExitUsage;
  if (c->mode != hesai_capture::Mode::unread && c->mode != hesai_capture::Mode::rows) {
    put_message(message, message_size, "this capture is read another way (columns or stats)");
    return kExitUsage;
  }
  c->mode = hesai_capture::Mode::rows;
  RowSink& s = c->sink;
  s.track_closures = closed_frame != nullptr;
  if (!s.track_closures) s.closures.clear();  // the rows only
  try {
    if (s.taken == s.rows.size() && s.closures.empty() && !c->ended) {
      // Nothing staged: the pipeline writes into the caller's rows until they are full or a
      // frame closes.
      s.rows.clear();
      s.taken = 0;
      s.direct = rows;
      s.direct_capacity = capacity;
      s.direct_n = 0;
      while (!c->ended && s.direct_n < capacity && s.closures.empty()) feed_next(c);
      const std::size_t made = s.direct_n;
      s.direct = nullptr;
      s.direct_capacity = s.direct_n = 0;
      std::size_t n = made;
      bool closes = false;
      if (!s.closures.empty() && s.closures.front().rows <= made) {
        n = s.closures.front().rows;
        closes = true;
        if (closed_frame != nullptr) *closed_frame = s.closures.front().frame;
        if (closed_sensor != nullptr) *closed_sensor = s.closures.front().sensor;
        s.closures.pop_front();
      }
      // What came after the rows given (the next frame's first rows, those beyond the capacity)
      // is staged for the next call, in order.
      s.rows.insert(s.rows.begin(), rows + n, rows + made);
      for (auto& closure : s.closures) closure.rows -= n;
      *count = n;
      if (n != 0 || closes || made != 0) return kExitOk;
      // Nothing made: the end or a failure, said below.
    }
    for (;;) {
      const std::size_t available = s.rows.size() - s.taken;
      const bool closes = !s.closures.empty() && s.closures.front().rows - s.taken <= capacity;
      if (closes || available >= capacity || c->ended) {
        const std::size_t n = closes ? s.closures.front().rows - s.taken : std::min(available, capacity);
        if (n != 0) std::memcpy(rows, s.rows.data() + s.taken, n * sizeof(hesai_capture_row));
        s.taken += n;
        *count = n;
        if (closes) {
          if (closed_frame != nullptr) *closed_frame = s.closures.front().frame;
          if (closed_sensor != nullptr) *closed_sensor = s.closures.front().sensor;
          s.closures.pop_front();
        }
        if (s.taken >= 65536 || s.taken == s.rows.size()) {  // drop what was given
          s.rows.erase(s.rows.begin(), s.rows.begin() + static_cast<std::ptrdiff_t>(s.taken));
          for (auto& closure : s.closures) closure.rows -= s.taken;
          s.taken = 0;
        }
        if (n == 0 && !closes && c->status != kExitOk) {
          put_message(message, message_size, c->error);
          return c->status;
        }
        return kExitOk;
      }
      feed_next(c);  // more rows are wanted
    }
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

int hesai_capture_read_columns(hesai_capture* c, const hesai_capture_columns* columns, std::size_t* count,
                               char* message, std::size_t message_size) noexcept {
  using namespace hesai::port;
  if (count != nullptr) *count = 0;
  if (c == nullptr || columns == nullptr || count == nullptr) return kExitUsage;
  const hesai_capture_columns& out = *columns;
  if (out.x == nullptr || out.y == nullptr || out.z == nullptr || out.time_ns == nullptr || out.intensity == nullptr ||
      out.channel == nullptr || out.return_index == nullptr) {
    put_message(message, message_size, "a column is NULL");
    return kExitUsage;
  }
  if (out.capacity < HESAI_CAPTURE_COLUMNS_MIN) {
    put_message(message, message_size, "columns hold fewer than HESAI_CAPTURE_COLUMNS_MIN points");
    return kExitUsage;
  }
  if (c->columns_refused) {
    put_message(message, message_size,
                "the columns take no cut angle, field of view, range limits or --returns distinct (decode_file does)");
    return kExitUsage;
  }
  if (c->mode != hesai_capture::Mode::unread && c->mode != hesai_capture::Mode::columns) {
    put_message(message, message_size, "this capture is read another way (rows or stats)");
    return kExitUsage;
  }
  c->mode = hesai_capture::Mode::columns;
  constexpr std::size_t kPacket = HESAI_MAX_POINTS_PER_PACKET;
  constexpr std::size_t kWorst = (Pipeline::kHeldPackets + 1) * kPacket;  // a decision releases the held
  std::size_t n = 0;
  try {
    while (!c->ended) {
      if (c->finishing) {  // Pipeline::finish: each source's held packets, in the assumed direction
        bool more = false;
        for (auto& [key, src] : c->sources) {
          while (!src.held.empty() && out.capacity - n >= kPacket) n += release_held_columns(c, src, out, n);
          more = more || !src.held.empty();
        }
        if (more) break;  // no room: the rest in the next call
        c->ended = true;
        break;
      }
      if (out.capacity - n < kWorst) break;
      hesai::port::UdpDatagram d;
      if (c->has_pending) {
        d = c->pending;
        c->has_pending = false;
      } else {
        const hesai::port::CaptureStatus st = c->file.next(d);
        if (st != hesai::port::CaptureStatus::datagram) {
          if (st == hesai::port::CaptureStatus::error) {
            c->status = kExitInput;
            c->error = c->file.message();
          }
          c->finishing = true;
          continue;
        }
      }
      // Pipeline::feed, without its accounting.
      hesai::Model model = hesai::Model::unknown;
      hesai::PacketKind kind = hesai::PacketKind::point_cloud;
      if (hesai::identify(d.payload, model, kind) != hesai::Error::ok) continue;
      if (kind == hesai::PacketKind::gps) {
        hesai::GpsPacket gps;
        if (hesai::parse_gps_packet(d.payload, gps) != hesai::Error::ok) continue;
        c->gps = gps;
        c->have_gps = true;
        for (auto& [key, src] : c->sources) src.decoder->update_gps(gps);
        continue;
      }
      const std::uint64_t key = source_key(d);
      auto it = c->sources.find(key);
      if (it != c->sources.end() && it->second.decoder->model() != model) {
        while (!it->second.held.empty()) n += release_held_columns(c, it->second, out, n);
        it->second.decoder->clear_session_key();
        c->sources.erase(it);
        it = c->sources.end();
      }
      if (it == c->sources.end()) {
        if (c->sources_made >= kMaxSensors) {  // the column cannot name it
          c->status = kExitInput;
          c->error = "more than 65536 sensors in the capture";
          c->ended = true;
          break;
        }
        ColumnSource s;
        s.sensor = static_cast<std::uint16_t>(c->sources_made++);
        c->sink.names.push_back(source_text(d, c->file));
        s.decoder = std::make_unique<hesai::Decoder>(model);
        if (!c->pipeline->configure_decoder(*s.decoder)) {
          c->status = kExitUsage;
          c->error = c->pipeline->error();
          c->ended = true;
          break;
        }
        if (c->have_gps) s.decoder->update_gps(c->gps);
        it = c->sources.emplace(key, std::move(s)).first;
      }
      ColumnSource& src = it->second;
      hesai::PacketInfo info;
      std::size_t got = 0;
      if (decode_columns_at(c, src, d.payload, out, n, info, got) != hesai::Error::ok) continue;
      const std::uint64_t index = c->index++;
      if (c->detect_rotation) {
        const bool decided = src.rotation.observe(info);
        if (!src.rotation.known()) {
          if (src.held.full()) n += release_held_columns(c, src, out, n);
          if (src.held.push(d.payload, index)) continue;
          // decode() accepted it, so it fits (as in the Pipeline): decoded below.
          if (decode_columns_at(c, src, d.payload, out, n, info, got) != hesai::Error::ok) continue;
        } else if (decided) {
          const hesai::Rotation r = src.rotation.rotation();
          if (r != src.decoder->rotation() || !src.held.empty()) {
            src.decoder->set_rotation(r);
            while (!src.held.empty()) n += release_held_columns(c, src, out, n);
            if (decode_columns_at(c, src, d.payload, out, n, info, got) != hesai::Error::ok) continue;
          }
        }
      }
      n += keep_columns(c, out, n, index, src.sensor, info, got);
    }
  } catch (const std::bad_alloc&) {
    put_message(message, message_size, "out of memory");
    *count = n;
    return kExitInput;
  }
  *count = n;
  if (n == 0 && c->ended && c->status != kExitOk) {
    put_message(message, message_size, c->error);
    return c->status;
  }
  return kExitOk;
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
