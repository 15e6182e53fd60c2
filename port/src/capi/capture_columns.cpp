// hesai_capture_read_columns: the engine's Pipeline in its columns mode (Pipeline::set_columns),
// each packet decoded by the core's columnar decode straight into the caller's columns.
#include <algorithm>
#include <cstring>
#include <new>

#include "capture.h"

namespace hesai::capi {

namespace {

constexpr std::size_t kPacket = kMaxPointsPerPacket;

// The columns a packet's points go to: room for a packet at `at` of each.
template <typename Columns>
PointColumns packet_room(const Columns& c, std::size_t at, std::int32_t* times) {
  return {c.x + at, c.y + at, c.z + at, times, c.intensity + at, c.channel + at, c.return_index + at, kPacket};
}

// What the Pipeline knows of a kept packet's points, beside what the decoder wrote: the absolute
// time (the packet's plus each point's offset), the packet index and the sensor.
void put_context(std::int64_t* time_ns, std::uint64_t* packet, std::uint16_t* sensor, const std::int32_t* times,
                 std::size_t count, std::uint64_t index, std::uint16_t src, std::int64_t packet_time) {
  for (std::size_t i = 0; i < count; ++i) time_ns[i] = packet_time + times[i];
  if (packet != nullptr) std::fill(packet, packet + count, index);
  if (sensor != nullptr) std::fill(sensor, sensor + count, src);
}

template <typename T>
void move_part(const std::vector<T>& from, std::size_t first, std::size_t count, T* to) {
  // count 0 from a vector never filled: its data() may be null, which memcpy may not be given.
  if (to != nullptr && count != 0) std::memcpy(to, from.data() + first, count * sizeof(T));
}

template <typename Staged, typename F>
void for_each_column(Staged& g, F f) {
  f(g.x);
  f(g.y);
  f(g.z);
  f(g.time_ns);
  f(g.intensity);
  f(g.channel);
  f(g.return_index);
  f(g.packet);
  f(g.sensor);
}

}  // namespace

PointColumns ColumnWriter::room() {
  // Straight into the caller's columns while nothing waits in the stage before (the order) and a
  // whole packet fits.
  direct_ = out_ != nullptr && !staging() && out_->capacity - n_ >= kPacket;
  if (direct_) return packet_room(*out_, n_, times_);
  const std::size_t size = staged_ + kPacket;
  Staged& g = stage_;
  for_each_column(g, [size](auto& v) {
    if (v.size() < size) v.resize(size);
  });
  struct {
    float *x, *y, *z;
    std::uint8_t *intensity, *channel, *return_index;
  } at{g.x.data(), g.y.data(), g.z.data(), g.intensity.data(), g.channel.data(), g.return_index.data()};
  return packet_room(at, staged_, times_);
}

void ColumnWriter::kept(std::size_t count, std::uint64_t index, std::uint32_t sensor, const PacketInfo& info) {
  if (sensor >= kMaxSensors) return;  // a column cannot name it: the read ends there (feed_next)
  const auto src = static_cast<std::uint16_t>(sensor);
  if (direct_) {
    put_context(out_->time_ns + n_, out_->packet == nullptr ? nullptr : out_->packet + n_,
                out_->sensor == nullptr ? nullptr : out_->sensor + n_, times_, count, index, src, info.time_ns);
    n_ += count;
  } else {
    put_context(stage_.time_ns.data() + staged_, stage_.packet.data() + staged_, stage_.sensor.data() + staged_, times_,
                count, index, src, info.time_ns);
    staged_ += count;
  }
}

void ColumnWriter::begin(const hesai_capture_columns& out) {
  out_ = &out;
  n_ = std::min(staged_ - taken_, out.capacity);
  const Staged& g = stage_;
  move_part(g.x, taken_, n_, out.x);
  move_part(g.y, taken_, n_, out.y);
  move_part(g.z, taken_, n_, out.z);
  move_part(g.time_ns, taken_, n_, out.time_ns);
  move_part(g.intensity, taken_, n_, out.intensity);
  move_part(g.channel, taken_, n_, out.channel);
  move_part(g.return_index, taken_, n_, out.return_index);
  move_part(g.packet, taken_, n_, out.packet);
  move_part(g.sensor, taken_, n_, out.sensor);
  taken_ += n_;
  if (taken_ == staged_) taken_ = staged_ = 0;  // all given: the stage is empty (its memory kept)
}

std::size_t ColumnWriter::end() {
  out_ = nullptr;
  return n_;
}

}  // namespace hesai::capi

using namespace hesai::capi;  // capture.h: the handle, the sinks, the statuses

extern "C" {

int hesai_capture_read_columns(hesai_capture* c, const hesai_capture_columns* columns, std::size_t* count,
                               char* message, std::size_t message_size) noexcept {
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
  if (c->mode == hesai_capture::Mode::unread) c->pipeline->set_columns(&c->columns);
  c->mode = hesai_capture::Mode::columns;
  // One datagram makes at most the packets a source holds and itself (the one that decides the
  // direction releases the held): fed only while they fit. The end of the capture releases every
  // source's held packets at once: the stage takes what does not fit.
  constexpr std::size_t kWorst = (hesai::port::Pipeline::kHeldPackets + 1) * kPacket;
  static_assert(kWorst <= HESAI_CAPTURE_COLUMNS_MIN, "a call's columns take a datagram's packets");
  ColumnWriter& w = c->columns;
  try {
    w.begin(out);
    while (!c->ended && !w.staging() && out.capacity - w.written() >= kWorst) feed_next(c);
  } catch (const std::bad_alloc&) {
    put_message(message, message_size, "out of memory");
    *count = w.end();
    return kExitInput;
  }
  const std::size_t n = w.end();
  *count = n;
  if (n == 0 && c->ended && c->status != kExitOk) {
    put_message(message, message_size, c->error);
    return c->status;
  }
  return kExitOk;
}

}  // extern "C"
