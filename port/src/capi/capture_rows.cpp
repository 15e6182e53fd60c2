// hesai_capture_read: the engine's Pipeline into the caller's rows, as the CSV sink would write
// them, stopping where frames close when asked to.
#include <algorithm>
#include <cstring>
#include <new>

#include "capture.h"

namespace hesai::capi {

namespace {

hesai_capture_row row(const port::PointRun& run, const Point& p) {
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

}  // namespace

// A run of one packet's points of one frame: those that fit go straight into the caller's rows,
// the rest to the staging rows.
void RowSink::points(const port::PointRun& run) {
  if (discard || run.count == 0 || run.sensor >= kMaxSensors) return;
  const std::size_t direct_count = std::min(run.count, direct_capacity - direct_n);
  hesai_capture_row* out = direct + direct_n;
  for (std::size_t i = 0; i < direct_count; ++i) out[i] = row(run, run.points[i]);
  direct_n += direct_count;
  for (std::size_t i = direct_count; i < run.count; ++i) rows.push_back(row(run, run.points[i]));
}

void RowSink::sensor_added(std::uint32_t sensor, const std::string& label) {
  if (sensor >= kMaxSensors) {
    too_many = true;
    return;
  }
  if (names.size() <= sensor) names.resize(sensor + 1);  // a deque: the names given stay put
  names[sensor] = label;
}

void RowSink::frame_closed(const FrameInfo& frame, std::uint32_t sensor) {
  if (!discard && track_closures && sensor < kMaxSensors)
    closures.push_back(Closure{direct_n + rows.size(), frame.id, static_cast<std::uint16_t>(sensor)});
}

}  // namespace hesai::capi

using namespace hesai::capi;  // capture.h: the handle, the sinks, the statuses

extern "C" {

int hesai_capture_read(hesai_capture* c, hesai_capture_row* rows, std::size_t capacity, std::size_t* count,
                       std::uint64_t* closed_frame, std::uint16_t* closed_sensor, char* message,
                       std::size_t message_size) noexcept {
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

}  // extern "C"
