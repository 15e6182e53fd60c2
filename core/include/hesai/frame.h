// Frame assembly: which rotation each point belongs to, from its own azimuth, and when a
// rotation is complete.
//
// Contract: a FrameAssembler (400 bytes) follows one packet stream, in one thread; constant work
// per block and per point, no heap.
#pragma once

#include <cstddef>
#include <cstdint>

#include "hesai/decoder.h"
#include "hesai/error.h"

namespace hesai {

/// One frame (one rotation of the sensor), as the assembler saw it. The assembler does not
/// hold points: the caller stores them under the frame id point() gives and uses these fields
/// to know what a frame holds once it is closed.
struct FrameInfo {
  std::uint64_t id = 0;             ///< 1-based, in rotation order (0: no frame)
  std::uint64_t first_packet = 0;   ///< caller's index of the first packet that gave the frame a block or a point
  std::uint64_t last_packet = 0;    ///< caller's index of the last one
  std::uint64_t packets = 0;        ///< packets that gave the frame a block or a point (0: an empty frame)
  std::uint64_t blocks = 0;         ///< blocks whose azimuth lies in the frame
  std::uint64_t points = 0;         ///< points given to the frame by point()
  std::uint64_t late_points = 0;    ///< of `points`: points whose own rotation had already closed (see point())
  std::uint64_t lost_packets = 0;   ///< lost_before of the packets whose first block is in the frame
  bool loss = false;                ///< lost_packets > 0, or the frame ended at a gap in the packets
  bool starts_at_cut = false;       ///< false when the stream began after the frame's cut (a partial turn)
  bool ends_at_cut = false;         ///< false for the frames closed by finish() (a partial turn)
  std::uint16_t first_azimuth_cdeg = 0;  ///< azimuth of the frame's first block, 0.01 degree (0 without blocks)
  std::uint16_t last_azimuth_cdeg = 0;   ///< azimuth of its last block, 0.01 degree
};

/// Cuts a stream of packets into frames (rotations) at a configurable azimuth, by the azimuth of
/// each point, in either direction of rotation.
///
/// Use, per packet: begin_packet(); then for each block in order: block(azimuth) (true: frames
/// closed, take them with pop_closed() before the next block), then point(azimuth) for each of
/// that block's points, which names the frame the point belongs to, or points() for all of them
/// at once (the same result, usually one frame id for the whole block). At the end of the stream,
/// finish() closes the open frames (take them with pop_closed()).
///
/// Rules (block azimuths in 0.01 degree, 0..35999, as in the packets; "forward" is the direction
/// of rotation, clockwise unless set_rotation() says otherwise):
/// - A rotation runs from the cut angle forward to the cut again. A point belongs to the frame
///   of the rotation that holds its own azimuth (block + channel offset + firing-time correction),
///   not its block's: a packet, or a block, that straddles the cut gives points to both frames.
///   A point lying exactly on the cut belongs to the rotation that starts there.
/// - The block azimuths say where the stream is. The reference azimuth is the furthest block
///   azimuth reached so far. A move is forward when it is less than half a turn forward
///   (35990 -> 10 is a forward move of 20 across 0 clockwise). A move of half a turn or more
///   forward is a step back (100 after 105 clockwise): azimuth jitter or a late packet. It never
///   passes the cut and leaves the reference where it was; its points still go by their azimuth.
///   Equal azimuths (the two blocks of a dual return) do not move.
/// - After lost packets (lost_before > 0), the move to the packet's first block is forward
///   whatever its size, so the stream passes a cut across a gap of more than half a turn. A gap of
///   a whole turn or more still passes only one cut: the turns that were not seen are not counted.
/// - A point lies at most the beam spread (set_beam_spread(): the decoder's beam_spread()) behind
///   or ahead of its block. A frame is closed once the reference azimuth is past its end by the
///   spread behind: then no later block that moves forward can give it a point. With no spread it
///   closes at the block that passes the cut. Frames close in id order, with ends_at_cut true.
/// - A point whose rotation has already closed (a step back past the spread, or a calibration
///   wider than the spread given) goes to the oldest open frame and counts in its late_points:
///   no point is dropped and none is counted twice.
/// - The first block of a stream opens the frame of its rotation, usually a partial turn
///   (starts_at_cut false). When it lies less than the spread behind past the cut, the rotation
///   before it opens first (id one less), for the points of the first blocks that lie behind the
///   cut; it may stay empty. A frame opens early when a point ahead of its block lies past the cut.
/// - Lost packets are reported in the frame that receives that packet's first block. When that
///   block also passes the cut (the gap straddles the cut), the frame it leaves gets loss = true as
///   well: some of the lost packets may have been its own.
/// - A block azimuth >= 36000 is not an azimuth (validation rejects it): the block is ignored.
///
/// State: four frames and a few counters (about 400 bytes); no heap.
class FrameAssembler {
 public:
  FrameAssembler() = default;

  /// Cut angle in degrees, [0, 360), rounded to 0.01 degree; default 0. Applies from the next block.
  /// Error::invalid_argument (and no change) outside the range or NaN.
  [[nodiscard]] Error set_cut_deg(float degrees) noexcept;
  /// The cut angle in 0.01 degree (0..35999).
  std::uint16_t cut_cdeg() const noexcept { return cut_cdeg_; }

  /// Direction of rotation (default clockwise); applies from the next block. A change while a
  /// stream is under way keeps the open frames and goes on from the reference azimuth in the new
  /// direction (a RotationDetector deciding after the first packets).
  void set_rotation(Rotation rotation) noexcept;
  Rotation rotation() const noexcept { return rotation_; }

  /// How far points lie from their block azimuth (Decoder::beam_spread()); default none.
  /// Error::invalid_argument (and no change) unless -180 <= min <= max <= 180 (NaN fails).
  [[nodiscard]] Error set_beam_spread(AzimuthSpread spread) noexcept;

  /// Field of view [start, end) in degrees for in_fov(); start in [0, 360), end in [0, 360],
  /// start != end. start > end wraps through 0 (300, 60: from 300 to 360 and 0 to 60).
  /// Error::invalid_argument (and no change) otherwise.
  [[nodiscard]] Error set_fov_deg(float start_degrees, float end_degrees) noexcept;
  /// No field of view: in_fov() is true for every azimuth.
  void clear_fov() noexcept { has_fov_ = false; }
  /// Whether a field of view is set (in_fov() can be false).
  bool has_fov() const noexcept { return has_fov_; }
  /// True when a point azimuth (degrees) lies in the field of view. An azimuth within one turn
  /// outside [0, 360) is folded in first (-10 is 350); NaN and other values are outside.
  bool in_fov(float azimuth_deg) const noexcept;

  /// Starts a packet: its index (any increasing counter of the caller) and the number of packets
  /// lost just before it (SequenceTracker::observe(), 0 without sequence numbers).
  void begin_packet(std::uint64_t packet_index, std::uint32_t lost_before) noexcept;
  /// One block azimuth, 0.01 degree. True when frames closed (the stream moved far enough past
  /// their end): take them with pop_closed() before the next block. The first block of a stream
  /// opens its frame and closes nothing.
  bool block(std::uint16_t azimuth_cdeg) noexcept;
  /// One point of the last block, by its azimuth in degrees (Point::azimuth_deg): counts it in its
  /// frame and returns that frame's id. An azimuth that is not one (NaN, beyond two turns) counts as
  /// its block's. Before the first block of a stream it counts in the first frame to open.
  std::uint64_t point(float azimuth_deg) noexcept;
  /// The points of the last block at once: the same as point() for each, in order (the same ids,
  /// frames, late_points and early openings), in one step when they all land in one open frame.
  /// Point i's azimuth (degrees) is the float at `azimuth_deg` plus i x `stride_bytes` bytes:
  /// `&pts[0].azimuth_deg, n, sizeof(Point)` for Points, `column, n, sizeof(float)` for a column
  /// (stride_bytes: a multiple of sizeof(float), as both are). Returns the id of the frame that
  /// got every point; 0 when count is 0 or the points went to more than one frame, and then
  /// ids_out[i] holds point i's id. ids_out: room for count ids, or null when the caller needs no
  /// ids; after a non-zero return its contents are unspecified.
  /// Cost: one pass over the azimuths (their smallest and largest), then constant work. The
  /// point-by-point rule (count x point()) serves a block that is not the common case: any
  /// azimuth negative (-0 too), NaN or 720 and more, an offset from the block that point() folds
  /// (not within half a turn: above -180 and up to +180 degrees), points on both sides of a cut,
  /// a late frame, a frame still to open, or no block yet in the stream.
  std::uint64_t points(const float* azimuth_deg, std::size_t count, std::size_t stride_bytes,
                       std::uint64_t* ids_out) noexcept;
  /// The oldest closed frame not yet taken, in id order; false when there is none.
  bool pop_closed(FrameInfo& out) noexcept;
  /// End of stream: closes every open frame (ends_at_cut false) and returns true if there was
  /// one. A later block starts again as at the start of a stream, with the ids going on.
  bool finish() noexcept;
  /// Forgets the stream and the closed frames not taken; keeps the cut, the field of view, the
  /// rotation and the spread. Ids start again at 1.
  void reset() noexcept;

  /// True while a frame is open.
  bool is_open() const noexcept { return first_open_ < next_id_; }
  /// The frame holding the reference azimuth (the last block that moved forward), so far; id 0
  /// when no stream is under way.
  const FrameInfo& current() const noexcept;
  /// Closed frames overwritten because pop_closed() was not called before the next block (0 when
  /// used as documented).
  std::uint64_t frames_dropped() const noexcept { return dropped_; }

 private:
  // Frames by id modulo kSlots: ids [oldest_, first_open_) are closed and not yet taken,
  // [first_open_, next_id_) open. Open frames lie within one of the reference's (k-1 .. k+1), so
  // with pop_closed() called after each block, four slots are always enough.
  static constexpr std::uint64_t kSlots = 4;

  FrameInfo& slot(std::uint64_t id) noexcept { return slots_[id % kSlots]; }
  std::int32_t forward(std::uint16_t from, std::uint16_t to) const noexcept;
  // Forward distance from block_id_'s cut to the reference azimuth, 0..35999.
  std::int32_t ref_pos() const noexcept { return forward(cut_cdeg_, ref_cdeg_); }
  void start_stream(std::uint16_t azimuth_cdeg) noexcept;
  void open_next(bool at_cut) noexcept;
  bool close_through(std::uint64_t id, bool at_cut) noexcept;
  void count_packet(std::uint64_t id) noexcept;
  void update_reach() noexcept;
  std::uint64_t frame_at(float offset) const noexcept;

  FrameInfo slots_[kSlots];
  std::uint64_t next_id_ = 1;          // id of the next frame to open
  std::uint64_t first_open_ = 1;       // oldest open frame (== next_id_: none)
  std::uint64_t oldest_ = 1;           // oldest frame not yet taken by pop_closed()
  std::uint64_t block_id_ = 0;         // frame holding the reference azimuth (0: no stream under way)
  std::uint64_t complete_from_ = 0;    // first frame of the stream whose start was seen whole
  std::uint64_t packet_index_ = 0;
  std::uint64_t pending_lost_ = 0;     // lost before the packet whose first block is to come
  std::uint64_t pending_points_ = 0;   // points given before the first block of a stream
  std::uint64_t dropped_ = 0;
  AzimuthSpread spread_;
  float behind_cdeg_ = 0;              // spread behind a block in the direction of rotation, 0.01 degree
  float ahead_cdeg_ = 0;               // and ahead of it
  float fov_start_ = 0;
  float fov_end_ = 360;
  std::int32_t block_pos_ = 0;         // forward distance from block_id_'s cut to the last block (below ref_pos() after a step back)
  std::uint16_t cut_cdeg_ = 0;
  std::uint16_t ref_cdeg_ = 0;         // furthest block azimuth reached
  std::uint16_t block_cdeg_ = 0;       // last block azimuth
  Rotation rotation_ = Rotation::clockwise;
  std::uint8_t has_packet_ = 0;        // bit id % kSlots: the current packet counts in that frame
  bool in_packet_ = false;             // begin_packet() called
  bool packet_started_ = false;        // the current packet has had a block
  bool has_fov_ = false;
};

}  // namespace hesai
