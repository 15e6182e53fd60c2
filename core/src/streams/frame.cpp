#include "hesai/frame.h"

#include <cstring>

#include "../base/compiler.h"

namespace hesai {

namespace {
constexpr std::int32_t kTurn = 36000;  // 360 degrees in 0.01 degree
constexpr std::int32_t kHalfTurn = 18000;
constexpr FrameInfo kNoFrame{};

// Clockwise distance from `from` to `to`, both in [0, kTurn): 0..kTurn-1.
constexpr std::int32_t clockwise(std::int32_t from, std::int32_t to) { return (to + kTurn - from) % kTurn; }

static_assert(clockwise(35990, 10) == 20, "wrap through 0 is a short forward move");
static_assert(clockwise(105, 100) == 35995, "jitter is almost a full turn clockwise");

// A float's bits and back, without a call to memcpy where the core is built freestanding.
inline std::uint32_t float_bits(float f) noexcept {
#if HESAI_GNU
  return __builtin_bit_cast(std::uint32_t, f);
#else
  std::uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
#endif
}
inline float bits_float(std::uint32_t b) noexcept {
#if HESAI_GNU
  return __builtin_bit_cast(float, b);
#else
  float f;
  std::memcpy(&f, &b, sizeof f);
  return f;
#endif
}

struct BitsRange {
  std::uint32_t lo = ~0u;
  std::uint32_t hi = 0;
};

// The smallest and largest bits, as unsigned integers, of `count` floats `step` floats apart;
// kStep, when not 0, is the step known at compile time (a plain column: the loop vectorises).
// For floats with the sign bit clear the integers order as the floats do (+0 < ... < +infinity
// < every NaN); a float with the sign bit set (negative, -0, a negative NaN) is above them all.
template <std::size_t kStep>
BitsRange bits_range(const float* first, std::size_t count, std::size_t step) noexcept {
  if (kStep != 0) step = kStep;
  BitsRange r;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t bits = float_bits(first[i * step]);
    r.lo = bits < r.lo ? bits : r.lo;
    r.hi = bits > r.hi ? bits : r.hi;
  }
  return r;
}

}  // namespace

Error FrameAssembler::set_cut_deg(float degrees) noexcept {
  if (!(degrees >= 0.0f && degrees < 360.0f)) return Error::invalid_argument;
  std::int32_t cdeg = static_cast<std::int32_t>(degrees * 100.0f + 0.5f);
  if (cdeg >= kTurn) cdeg = 0;  // 359.996 and above round to 360.00, which is 0
  cut_cdeg_ = static_cast<std::uint16_t>(cdeg);
  block_pos_ = ref_pos();  // the stream goes on from the new cut
  return Error::ok;
}

void FrameAssembler::set_rotation(Rotation rotation) noexcept {
  if (rotation == rotation_) return;
  rotation_ = rotation;
  update_reach();
  block_pos_ = ref_pos();  // the stream goes on in the new direction
}

Error FrameAssembler::set_beam_spread(AzimuthSpread spread) noexcept {
  if (!(spread.min_deg >= -180.0f && spread.min_deg <= spread.max_deg && spread.max_deg <= 180.0f))
    return Error::invalid_argument;
  spread_ = spread;
  update_reach();
  return Error::ok;
}

void FrameAssembler::update_reach() noexcept {
  const float behind_cw = spread_.min_deg < 0 ? -spread_.min_deg * 100.0f : 0.0f;
  const float ahead_cw = spread_.max_deg > 0 ? spread_.max_deg * 100.0f : 0.0f;
  const bool cw = rotation_ == Rotation::clockwise;
  behind_cdeg_ = cw ? behind_cw : ahead_cw;
  ahead_cdeg_ = cw ? ahead_cw : behind_cw;
}

std::int32_t FrameAssembler::forward(std::uint16_t from, std::uint16_t to) const noexcept {
  return rotation_ == Rotation::clockwise ? clockwise(from, to) : clockwise(to, from);
}

Error FrameAssembler::set_fov_deg(float start_degrees, float end_degrees) noexcept {
  if (!(start_degrees >= 0.0f && start_degrees < 360.0f)) return Error::invalid_argument;
  if (!(end_degrees >= 0.0f && end_degrees <= 360.0f)) return Error::invalid_argument;
  if (start_degrees == end_degrees) return Error::invalid_argument;
  fov_start_ = start_degrees;
  fov_end_ = end_degrees;
  has_fov_ = true;
  return Error::ok;
}

bool FrameAssembler::in_fov(float azimuth_deg) const noexcept {
  if (!has_fov_) return true;
  float a = azimuth_deg;
  if (!(a >= -360.0f && a < 720.0f)) return false;  // NaN too
  if (a < 0.0f) a += 360.0f;
  if (a >= 360.0f) a -= 360.0f;
  if (fov_start_ < fov_end_) return a >= fov_start_ && a < fov_end_;
  return a >= fov_start_ || a < fov_end_;  // wraps through 0
}

void FrameAssembler::begin_packet(std::uint64_t packet_index, std::uint32_t lost_before) noexcept {
  packet_index_ = packet_index;
  pending_lost_ += lost_before;  // a packet that brings no block hands its loss to the next one
  in_packet_ = true;
  packet_started_ = false;
  has_packet_ = 0;
}

void FrameAssembler::open_next(bool at_cut) noexcept {
  const std::uint64_t id = next_id_++;
  // Only closed frames can be this far behind (open ones lie within one of the reference).
  for (; id - oldest_ >= kSlots; ++oldest_) ++dropped_;
  FrameInfo& f = slot(id);
  f = FrameInfo{};
  f.id = id;
  f.starts_at_cut = at_cut;
  f.points = pending_points_;
  pending_points_ = 0;
  has_packet_ = static_cast<std::uint8_t>(has_packet_ & ~(1u << (id % kSlots)));
}

bool FrameAssembler::close_through(std::uint64_t id, bool at_cut) noexcept {
  bool any = false;
  for (; first_open_ <= id && first_open_ < next_id_; ++first_open_) {
    slot(first_open_).ends_at_cut = at_cut;
    any = true;
  }
  return any;
}

void FrameAssembler::count_packet(std::uint64_t id) noexcept {
  const unsigned bit = 1u << (id % kSlots);
  if (!in_packet_ || (has_packet_ & bit) != 0) return;
  FrameInfo& f = slot(id);
  if (f.packets == 0) f.first_packet = packet_index_;
  f.last_packet = packet_index_;
  ++f.packets;
  has_packet_ = static_cast<std::uint8_t>(has_packet_ | bit);
}

void FrameAssembler::start_stream(std::uint16_t azimuth_cdeg) noexcept {
  ref_cdeg_ = azimuth_cdeg;
  block_pos_ = ref_pos();
  // Points of the first blocks can lie behind the cut: the rotation before opens first.
  if (static_cast<float>(block_pos_) < behind_cdeg_) open_next(false);
  // A frame's start is whole when the stream began at least the spread ahead before its cut:
  // the block's own frame only when it lies on the cut and no point lies ahead of its block.
  const std::uint64_t own = next_id_;
  if (block_pos_ == 0 && ahead_cdeg_ <= 0.0f) {
    complete_from_ = own;
  } else {
    complete_from_ = static_cast<float>(kTurn - block_pos_) >= ahead_cdeg_ ? own + 1 : own + 2;
  }
  open_next(own >= complete_from_);
  block_id_ = own;
}

bool FrameAssembler::block(std::uint16_t azimuth_cdeg) noexcept {
  if (azimuth_cdeg >= kTurn) return false;
  const bool first_of_packet = in_packet_ && !packet_started_;
  const bool after_gap = first_of_packet && pending_lost_ > 0;

  bool closed = false;
  if (block_id_ == 0) {
    start_stream(azimuth_cdeg);
  } else {
    const std::int32_t move = forward(ref_cdeg_, azimuth_cdeg);
    if (move != 0 && (after_gap || move < kHalfTurn)) {
      const bool past_cut = ref_pos() + move >= kTurn;
      ref_cdeg_ = azimuth_cdeg;
      if (past_cut) {  // the reference enters the next rotation
        if (after_gap) slot(block_id_).loss = true;  // the gap straddles the cut
        closed = close_through(block_id_ - 1, true);
        ++block_id_;
        if (block_id_ == next_id_) open_next(block_id_ >= complete_from_);
      }
      block_pos_ = ref_pos();
      // Past the end of the frame before by the spread behind: no later point can reach it.
      if (static_cast<float>(block_pos_) >= behind_cdeg_) closed = close_through(block_id_ - 1, true) || closed;
    } else {
      block_pos_ = ref_pos() - (move == 0 ? 0 : kTurn - move);  // the same azimuth, or a step back
    }
  }
  block_cdeg_ = azimuth_cdeg;

  count_packet(block_id_);
  FrameInfo& f = slot(block_id_);
  if (first_of_packet) {
    f.lost_packets += pending_lost_;
    if (pending_lost_ > 0) f.loss = true;
    pending_lost_ = 0;
    packet_started_ = true;
  }
  if (f.blocks == 0) f.first_azimuth_cdeg = azimuth_cdeg;
  ++f.blocks;
  f.last_azimuth_cdeg = azimuth_cdeg;
  return closed;
}

std::uint64_t FrameAssembler::point(float azimuth_deg) noexcept {
  if (block_id_ == 0) {
    ++pending_points_;
    return next_id_;
  }
  // The point's offset from its block, clockwise, in (-half turn, half turn].
  float offset = 0.0f;
  if (azimuth_deg >= -360.0f && azimuth_deg < 720.0f) offset = azimuth_deg * 100.0f - static_cast<float>(block_cdeg_);
  while (offset > static_cast<float>(kHalfTurn)) offset -= static_cast<float>(kTurn);
  while (offset <= -static_cast<float>(kHalfTurn)) offset += static_cast<float>(kTurn);
  std::uint64_t id = frame_at(offset);
  if (id == next_id_) open_next(id >= complete_from_);  // a point ahead opens the next frame early
  const bool late = id < first_open_;
  if (late) id = first_open_;
  count_packet(id);
  FrameInfo& f = slot(id);
  ++f.points;
  if (late) ++f.late_points;
  return id;
}

std::uint64_t FrameAssembler::frame_at(float offset) const noexcept {
  // `offset`: a point's from the last block, clockwise, in (-half turn, half turn]; the frame of
  // its rotation by where it lies past block_id_'s cut.
  if (rotation_ == Rotation::counterclockwise) offset = -offset;
  const float at = static_cast<float>(block_pos_) + offset;
  std::uint64_t id = block_id_;
  if (at < 0.0f) --id;
  if (at >= static_cast<float>(kTurn)) ++id;
  return id;
}

std::uint64_t FrameAssembler::points(const float* azimuth_deg, std::size_t count, std::size_t stride_bytes,
                                     std::uint64_t* ids_out) noexcept {
  if (count == 0) return 0;
  const std::size_t step = stride_bytes / sizeof(float);
  if (block_id_ != 0) {
    // A point's frame is monotonic in its azimuth while no offset needs point()'s half-turn fold:
    // then the smallest and the largest azimuth decide for all, their offsets computed as point()
    // computes them. Only azimuths with the sign bit clear are taken so (the decoder's lie in
    // [0, 360)): a NaN among them is the largest, and its offset, NaN, fails the fold's bounds;
    // so does an azimuth of 720 or more (point() counts it as its block's), more than half a
    // turn from any block.
    const BitsRange bits =
        step == 1 ? bits_range<1>(azimuth_deg, count, step) : bits_range<0>(azimuth_deg, count, step);
    const float lo_offset = bits_float(bits.lo) * 100.0f - static_cast<float>(block_cdeg_);
    const float hi_offset = bits_float(bits.hi) * 100.0f - static_cast<float>(block_cdeg_);
    const bool unfolded = lo_offset > -static_cast<float>(kHalfTurn) && hi_offset <= static_cast<float>(kHalfTurn);
    if (bits.hi < 0x80000000u && unfolded) {
      const std::uint64_t id = frame_at(lo_offset);
      // One open frame for all: none late, none opening the next frame early.
      if (id == frame_at(hi_offset) && id >= first_open_ && id < next_id_) {
        count_packet(id);
        slot(id).points += count;
        return id;
      }
    }
  }
  // Point by point.
  std::uint64_t one = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint64_t id = point(azimuth_deg[i * step]);
    if (ids_out != nullptr) ids_out[i] = id;
    if (i == 0) {
      one = id;
    } else if (id != one) {
      one = 0;
    }
  }
  return one;
}

bool FrameAssembler::pop_closed(FrameInfo& out) noexcept {
  if (oldest_ >= first_open_) return false;
  out = slot(oldest_);
  ++oldest_;
  return true;
}

bool FrameAssembler::finish() noexcept {
  if (block_id_ == 0) return false;
  FrameInfo& f = slot(block_id_);
  f.lost_packets += pending_lost_;
  if (pending_lost_ > 0) f.loss = true;
  pending_lost_ = 0;
  close_through(next_id_ - 1, false);
  block_id_ = 0;
  return true;
}

void FrameAssembler::reset() noexcept {
  // Field by field: a whole fresh object would cost its 400 bytes of stack on a microcontroller.
  // The slots need no clearing: open_next() clears each before use.
  next_id_ = first_open_ = oldest_ = 1;
  block_id_ = complete_from_ = packet_index_ = pending_lost_ = pending_points_ = dropped_ = 0;
  block_pos_ = 0;
  ref_cdeg_ = block_cdeg_ = 0;
  in_packet_ = packet_started_ = false;
}

const FrameInfo& FrameAssembler::current() const noexcept {
  return block_id_ != 0 ? slots_[block_id_ % kSlots] : kNoFrame;
}

}  // namespace hesai
