#include "hesai/frame.h"

namespace hesai {

namespace {
constexpr std::uint32_t kTurn = 36000;      // 360 degrees in 0.01 degree
constexpr std::uint32_t kHalfTurn = 18000;

// Clockwise distance from `from` to `to`, both in [0, kTurn): 0..kTurn-1.
constexpr std::uint32_t clockwise(std::uint32_t from, std::uint32_t to) { return (to + kTurn - from) % kTurn; }

static_assert(clockwise(35990, 10) == 20, "wrap through 0 is a short forward move");
static_assert(clockwise(105, 100) == 35995, "jitter is almost a full turn clockwise");
}  // namespace

Error FrameAssembler::set_cut_deg(float degrees) noexcept {
  if (!(degrees >= 0.0f && degrees < 360.0f)) return Error::invalid_argument;
  std::uint32_t cdeg = static_cast<std::uint32_t>(degrees * 100.0f + 0.5f);
  if (cdeg >= kTurn) cdeg = 0;  // 359.996 and above round to 360.00, which is 0
  cut_cdeg_ = static_cast<std::uint16_t>(cdeg);
  return Error::ok;
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
  packet_in_frame_ = false;
}

void FrameAssembler::open_frame(std::uint16_t azimuth_cdeg, bool at_cut) noexcept {
  cur_ = FrameInfo{};
  cur_.id = next_id_++;
  cur_.starts_at_cut = at_cut;
  cur_.first_azimuth_cdeg = azimuth_cdeg;
  cur_.points = pending_points_;
  pending_points_ = 0;
  ref_cdeg_ = azimuth_cdeg;
  open_ = true;
  packet_in_frame_ = false;
}

bool FrameAssembler::crosses(std::uint16_t azimuth_cdeg, bool any_forward) noexcept {
  const std::uint32_t move = clockwise(ref_cdeg_, azimuth_cdeg);
  if (move == 0) return false;                           // same azimuth: dual return
  if (!any_forward && move >= kHalfTurn) return false;   // a step back: jitter or a late packet
  const std::uint32_t to_cut = clockwise(ref_cdeg_, cut_cdeg_);
  ref_cdeg_ = azimuth_cdeg;
  return to_cut != 0 && to_cut <= move;
}

bool FrameAssembler::block(std::uint16_t azimuth_cdeg) noexcept {
  if (azimuth_cdeg >= kTurn) return false;
  const bool first_of_packet = in_packet_ && !packet_started_;
  const bool after_gap = first_of_packet && pending_lost_ > 0;

  bool closed = false;
  if (!open_) {
    open_frame(azimuth_cdeg, azimuth_cdeg == cut_cdeg_);
  } else if (crosses(azimuth_cdeg, after_gap)) {
    cur_.ends_at_cut = true;
    if (after_gap) cur_.loss = true;  // the gap straddles the cut
    closed_ = cur_;
    closed = true;
    open_frame(azimuth_cdeg, true);
  }

  if (in_packet_ && !packet_in_frame_) {
    if (cur_.packets == 0) cur_.first_packet = packet_index_;
    cur_.last_packet = packet_index_;
    ++cur_.packets;
    packet_in_frame_ = true;
  }
  if (first_of_packet) {
    cur_.lost_packets += pending_lost_;
    if (pending_lost_ > 0) cur_.loss = true;
    pending_lost_ = 0;
    packet_started_ = true;
  }
  ++cur_.blocks;
  cur_.last_azimuth_cdeg = azimuth_cdeg;
  return closed;
}

void FrameAssembler::add_points(std::uint32_t n) noexcept {
  if (open_) {
    cur_.points += n;
  } else {
    pending_points_ += n;
  }
}

bool FrameAssembler::finish(FrameInfo& out) noexcept {
  if (!open_) return false;
  cur_.lost_packets += pending_lost_;
  if (pending_lost_ > 0) cur_.loss = true;
  pending_lost_ = 0;
  cur_.ends_at_cut = false;
  closed_ = cur_;
  out = cur_;
  open_ = false;
  packet_in_frame_ = false;
  return true;
}

void FrameAssembler::reset() noexcept {
  const std::uint16_t cut = cut_cdeg_;
  const bool has_fov = has_fov_;
  const float fov_start = fov_start_;
  const float fov_end = fov_end_;
  *this = FrameAssembler{};
  cut_cdeg_ = cut;
  has_fov_ = has_fov;
  fov_start_ = fov_start;
  fov_end_ = fov_end;
}

}  // namespace hesai
