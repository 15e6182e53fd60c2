// Frame assembly: where one rotation ends and the next begins, from the block azimuths.
//
// Contract: a FrameAssembler (184 bytes) follows one packet stream, in one thread; constant work
// per block, no heap.
#pragma once

#include <cstdint>

#include "hesai/error.h"

namespace hesai {

/// One frame (one rotation of the sensor), as the assembler saw it. The assembler does not
/// hold points: the caller stores them and uses these fields to know where a frame ends.
struct FrameInfo {
  std::uint64_t id = 0;             ///< 1-based, in the order frames open (0: no frame)
  std::uint64_t first_packet = 0;   ///< caller's index of the packet holding the frame's first block
  std::uint64_t last_packet = 0;    ///< caller's index of the packet holding its last block
  std::uint64_t packets = 0;        ///< packets with at least one block in the frame
  std::uint64_t blocks = 0;         ///< blocks given to block() while the frame was open
  std::uint64_t points = 0;         ///< sum of add_points() while the frame was open
  std::uint64_t lost_packets = 0;   ///< lost_before of the packets whose first block is in the frame
  bool loss = false;                ///< lost_packets > 0, or the frame ended at a gap in the packets
  bool starts_at_cut = false;       ///< false for the first frame of a stream (a partial turn)
  bool ends_at_cut = false;         ///< false for the frame closed by finish() (a partial turn)
  std::uint16_t first_azimuth_cdeg = 0;  ///< azimuth of the first block, 0.01 degree
  std::uint16_t last_azimuth_cdeg = 0;   ///< azimuth of the last block, 0.01 degree
};

/// Cuts a stream of packets into frames (rotations) at a configurable azimuth.
///
/// Use, per packet: begin_packet(); then for each block in order: block(azimuth) (true: the
/// previous frame closed just before this block, see last_closed()), then add_points(points of
/// that block). At the end of the stream, finish() closes the open frame.
///
/// Rules (azimuths are block azimuths in 0.01 degree, 0..35999, as in the packets):
/// - A frame closes when the azimuth crosses the cut: the clockwise move from the reference
///   azimuth to the current one passes over or lands on the cut. The block that crosses is the
///   first block of the new frame. A block lying exactly on the cut crosses when reached, not
///   when left.
/// - The reference azimuth is the furthest azimuth reached so far. A move is forward when it is
///   less than half a turn clockwise (35990 -> 10 is a forward move of 20 across 0). A move of
///   half a turn or more clockwise is a step backwards (100 after 105, 35995 after 5): azimuth
///   jitter or a late packet. It never closes a frame and leaves the reference where it was, so
///   the cut is not crossed twice. Equal azimuths (the two blocks of a dual return) never cross.
/// - After lost packets (lost_before > 0), the move to the packet's first block is forward
///   whatever its size, so a frame closes across a gap of more than half a turn. A gap of a
///   whole turn or more still closes only one frame: the turns that were not seen are not counted.
/// - The first frame starts at the first block of the stream: it is usually a partial turn but
///   it is a frame (id 1), with starts_at_cut false (true only if its first block lies on the cut).
///   The frame closed by finish() has ends_at_cut false.
/// - A packet whose blocks straddle the cut belongs to both frames: it is the last packet of
///   one and the first of the next, and counts in both `packets`.
/// - Lost packets reported with a packet count in the frame that receives that packet's first
///   block. When that block is also the crossing (the gap straddles the cut), the frame that
///   closes gets loss = true as well: some of the lost packets may have been its own.
/// - A block azimuth >= 36000 is not an azimuth (validation rejects it): the block is ignored.
///
/// State: a few dozen bytes; no heap.
class FrameAssembler {
 public:
  FrameAssembler() = default;

  /// Cut angle in degrees, [0, 360), rounded to 0.01 degree; default 0. Applies from the next block.
  /// Error::invalid_argument (and no change) outside the range or NaN.
  [[nodiscard]] Error set_cut_deg(float degrees) noexcept;
  /// The cut angle in 0.01 degree (0..35999).
  std::uint16_t cut_cdeg() const noexcept { return cut_cdeg_; }

  /// Field of view [start, end) in degrees for in_fov(); start in [0, 360), end in [0, 360],
  /// start != end. start > end wraps through 0 (300, 60: from 300 to 360 and 0 to 60).
  /// Error::invalid_argument (and no change) otherwise.
  [[nodiscard]] Error set_fov_deg(float start_degrees, float end_degrees) noexcept;
  /// No field of view: in_fov() is true for every azimuth.
  void clear_fov() noexcept { has_fov_ = false; }
  /// True when a point azimuth (degrees) lies in the field of view. An azimuth within one turn
  /// outside [0, 360) is folded in first (-10 is 350); NaN and other values are outside.
  bool in_fov(float azimuth_deg) const noexcept;

  /// Starts a packet: its index (any increasing counter of the caller) and the number of packets
  /// lost just before it (SequenceTracker::observe(), 0 without sequence numbers).
  void begin_packet(std::uint64_t packet_index, std::uint32_t lost_before) noexcept;
  /// One block azimuth, 0.01 degree. True when this block starts a new frame because the
  /// previous one closed just before it (then last_closed() is that frame). The first block of a
  /// stream opens frame 1 and returns false.
  bool block(std::uint16_t azimuth_cdeg) noexcept;
  /// Adds points to the open frame (to the next frame to open if none is open).
  void add_points(std::uint32_t n) noexcept;
  /// End of stream: closes the open frame into `out` (ends_at_cut false) and returns true;
  /// false when no frame is open. A later block starts again as at the start of a stream,
  /// with the ids going on.
  bool finish(FrameInfo& out) noexcept;
  /// Forgets everything except the cut and the field of view; ids start again at 1.
  void reset() noexcept;

  /// The frame closed last (id 0 before any).
  const FrameInfo& last_closed() const noexcept { return closed_; }
  /// True while a frame is open, and the frame so far.
  bool is_open() const noexcept { return open_; }
  const FrameInfo& current() const noexcept { return cur_; }

 private:
  void open_frame(std::uint16_t azimuth_cdeg, bool at_cut) noexcept;
  bool crosses(std::uint16_t azimuth_cdeg, bool any_forward) noexcept;

  FrameInfo cur_;
  FrameInfo closed_;
  std::uint64_t next_id_ = 1;
  std::uint64_t packet_index_ = 0;
  std::uint64_t pending_lost_ = 0;     // lost before the packet whose first block is to come
  std::uint64_t pending_points_ = 0;   // points given while no frame was open
  float fov_start_ = 0;
  float fov_end_ = 360;
  std::uint16_t cut_cdeg_ = 0;
  std::uint16_t ref_cdeg_ = 0;         // furthest azimuth reached
  bool open_ = false;
  bool in_packet_ = false;             // begin_packet() called
  bool packet_started_ = false;        // the current packet has had a block
  bool packet_in_frame_ = false;       // the current packet counts in the open frame
  bool has_fov_ = false;
};

}  // namespace hesai
