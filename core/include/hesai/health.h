// Stream health of one sensor: packets lost where the packets carry no UDP sequence, and clocks
// that freeze, run backwards or count from the free-run virtual date.
//
// Sources. Pandar64 manual, Chapter 3 (note 1 under the data structure): "UDP sequence is OFF by
// default"; its settings table: "ON #1: UDP sequence only increments within the user-specified
// azimuth FOV ... ON #2: Increments at all times"; its troubleshooting table names the azimuth FOV
// first among the causes of "missing packets". Pandar40P packet document,
// "Quality Indicators": sequence gaps and repeated timestamps. Pandar64 manual, Appendix B (PTP
// table), and QT128C2X manual, the same table: a unit never locked "starts counting from a virtual
// UTC (such as 2000-01-01 00:00:00)". Model facts (firings per rotation at 600 rpm, blocks per
// packet): model_list.h.
//
// Cost: HealthMonitor is about 720 bytes of fixed state (its counters, 512 of them the blockage
// units per channel; a 256-packet window; the last 4 gaps; the previous packet's azimuth, time and
// spin rate), no heap. observe() is O(1) but for a forward gap of k packets, which clears min(k, 256)
// bits; observe_units() is O(1) but for a packet with blockage units (a pass over the 128 channels).
// Cortex-M4F: about 620 instructions a packet for both (docs/FIRMWARE.md). Not thread-safe: one
// monitor per sensor, fed from one thread, in arrival order.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/decoder.h"
#include "hesai/saturating.h"
#include "hesai/detail/seen_window.h"

namespace hesai {

/// Packets the monitor remembers behind the newest one, for late (reordered) packets.
inline constexpr std::uint32_t kHealthWindow = 256;
static_assert((kHealthWindow & (kHealthWindow - 1)) == 0 && kHealthWindow % 32 == 0, "window: a power of two, whole words");

/// A forward move of the packet time longer than this is not read as lost packets: a clock step
/// (a free-running unit locking to PTP or GPS) cannot be told from a pause of the stream. Such a
/// packet counts as a time jump; only the block azimuth (less than a rotation) counts losses across it.
inline constexpr std::int64_t kHealthMaxGapNs = 1000000000;

/// Gaps remembered for the FOV rule (HealthMonitor).
inline constexpr std::size_t kHealthGaps = 4;

/// Packets dated in [2000-01-01, 2001-01-01) UTC are on the free-run virtual clock, ns since the Unix epoch.
inline constexpr std::int64_t kVirtualClockStartNs = 946684800LL * 1000000000;
inline constexpr std::int64_t kVirtualClockEndNs = 978307200LL * 1000000000;

/// Counters of one sensor's stream. Every counter saturates at its largest value; none wraps.
struct HealthCounts {
  std::uint64_t packets = 0;       ///< packets observed
  std::uint64_t lost = 0;          ///< packets missing by the block azimuth and the packet time, not (yet) arrived
  std::uint64_t reordered = 0;     ///< packets that arrived after a later one (their slot no longer lost)
  std::uint64_t duplicates = 0;    ///< packets at the azimuth and time of one already seen
  std::uint64_t time_stalls = 0;   ///< packet time not after the previous packet's, not explained by reordering
  std::uint64_t time_virtual = 0;  ///< packets dated in the year 2000 (UTC): the unit's free-running clock
  std::uint64_t time_jumps = 0;    ///< packet time ahead by more than kHealthMaxGapNs, or by more than the
                                   ///< block azimuth allows: a clock step (not counted as loss)
  // From the units (observe_units(), UnitScan of decoder.h).
  std::uint64_t blockage_units = 0;      ///< QT128C2X units with the blockage marker (distance 1)
  std::uint64_t duplicate_returns = 0;   ///< dual-return pairs whose two returns are the same echo
  std::uint64_t beyond_rated_range = 0;  ///< points farther than rated_range_m(model)
  std::array<std::uint32_t, kMaxChannels> blockage_by_channel{};  ///< blockage units per channel - 1
  /// A gap that recurred at the same azimuths: the unit's azimuth FOV, not loss (see HealthMonitor).
  /// Its edges are the first block azimuths on either side of the missing packets at its last
  /// occurrence, 0.01 degree, from `fov_gap_from` forward (in the direction of rotation) to `fov_gap_to`.
  bool fov_gap = false;
  std::uint16_t fov_gap_from = 0;
  std::uint16_t fov_gap_to = 0;
};

/// Watches one sensor's point-cloud packets (PacketInfo from validate() or decode()) for loss,
/// reordering and clock faults, without the UDP sequence.
///
/// Each packet is placed on a count of packets from the first one (its slot). Its expected place
/// follows from the model's firings per rotation at 600 rpm (N, model_list.h) and its firings per
/// packet F = blocks / returns (a dual-return pair of blocks is one firing):
/// - by time: a packet every F x 10^8 / N ns whatever the spin rate (the firing rate is fixed; the
///   azimuth step scales with the rate): k_t = round(dt N / (F 10^8)) packets;
/// - by azimuth: a step of F x 60 x rpm / N hundredths of a degree a packet, at the mean motor speed
///   of the two packets, in the direction of rotation (set_rotation()): k_a = the first block's move
///   over the step, the move taken in (-half a turn, half a turn), so k_a cannot see a whole turn.
/// The spin rate is usable when both packets give a non-zero rpm within 1/16 of each other; it is
/// never divided by otherwise. A count k "agrees" with an azimuth move when the move k steps
/// predict lies, modulo a turn, within half a step plus 1/32 of the prediction of the move seen
/// (any move, once that tolerance reaches half a turn).
///
/// Rules, with dt the move of the packet time from the previous packet that was not late:
/// - dt = 0 and the same first block azimuth: a copy of that packet (duplicates).
/// - dt > kHealthMaxGapNs: a time jump; the packet is k_a ahead (at least 1; 1 without a usable rate).
/// - 0 < dt <= kHealthMaxGapNs: without a usable rate, k_t ahead (at least 1), counted from the
///   last packet whose time held when stalls came between (its time and slot). With one, k_t ahead
///   when k_t agrees with the azimuth; otherwise, if the clock was out of step since the last packet
///   whose time agreed (a stall between), the count from that packet's time and slot when it agrees;
///   otherwise the clock stepped: a time jump, and the packet is k_a ahead (at least 1).
/// - dt <= 0 with a usable rate and the azimuth behind by one step or more: a late packet (not a
///   stall), as far behind as the time says when that agrees with the azimuth, else as the azimuth
///   says. Any other dt <= 0: a time stall, the packet k_a ahead (at least 1; 1 without a usable rate).
/// - A packet k ahead counts k - 1 lost (observe() returns it). A late packet within kHealthWindow
///   of the newest takes one back when its slot was counted lost; one whose slot was seen is a
///   duplicate; one further back, or before the first packet, counts as reordered only.
/// - Pandar40 packets before a GPS packet carry the time within the hour: dt is taken modulo the
///   hour. Across a change of time reference, of model or of firings per packet (a return-mode
///   switch) nothing is compared: the packet is 1 ahead.
/// - A packet dated in the year 2000 counts as time_virtual, whatever else it shows.
/// - Azimuth FOV (Pandar64 manual 4.3: a unit with an FOV set sends no packet outside it): a gap
///   whose first block azimuths on either side lie within 3 azimuth steps (3 degrees without a
///   usable rate) of those of one of the last kHealthGaps gaps is the FOV, not loss: both gaps'
///   packets are taken back from `lost`, and every later gap there is not counted. A first gap
///   stays counted until it recurs, so the count is final at the end of the stream.
class HealthMonitor {
 public:
  /// The direction the unit spins (default clockwise), as Decoder::set_rotation.
  void set_rotation(Rotation rotation) noexcept { rotation_ = rotation; }
  /// One packet, in arrival order. Returns the packets newly found missing just before it (the
  /// FrameAssembler's lost_before): k - 1 for a packet k ahead, 0 otherwise.
  std::uint32_t observe(const PacketInfo& info) noexcept;
  /// The units of a decoded packet (Decoder::decode with a UnitScan): adds its blockage units (and
  /// per channel), repeated dual returns and points beyond the rated range. O(1), but a pass over
  /// the 128 channels when the packet has a blockage unit.
  void observe_units(const UnitScan& scan) noexcept;
  const HealthCounts& counts() const noexcept { return counts_; }
  /// Forgets everything, counters included (the rotation too).
  void reset() noexcept { *this = HealthMonitor{}; }

 private:
  std::uint32_t advance(std::uint32_t k) noexcept;
  void late(std::uint32_t k_back) noexcept;
  void restart(const PacketInfo& info) noexcept;
  std::uint32_t fov_rule(std::uint32_t lost, std::uint16_t from, std::uint16_t to, std::uint32_t tolerance) noexcept;
  void take_back_lost(std::uint64_t n) noexcept;

  struct Gap {
    std::uint16_t from, to;  // first block azimuths either side, 0.01 degree
    std::uint32_t lost;      // packets it counted (0: the slot is free)
  };
  std::array<Gap, kHealthGaps> gaps_{};
  std::uint8_t next_gap_ = 0;

  HealthCounts counts_;
  std::int64_t time_ns_ = 0;      // time of the newest packet that was not late
  std::int64_t trusted_ns_ = 0;   // time of the last packet whose time agreed (or set a new base)
  std::uint32_t trusted_slot_ = 0;  // its slot
  detail::SeenWindow<kHealthWindow> seen_;  // which slots of the window arrived
  std::uint32_t newest_ = 0;      // slot of the newest packet that was not late, counted from the first
  std::uint32_t span_ = 0;        // slots newest - span + 1 .. newest were counted (lost or seen)
  std::uint16_t azimuth_ = 0;     // its first block azimuth, 0.01 degree
  std::uint16_t rpm_ = 0;         // its motor speed
  Model model_ = Model::unknown;
  std::uint8_t firings_ = 0;      // its firings per packet (blocks / returns)
  TimeReference reference_ = TimeReference::utc;
  Rotation rotation_ = Rotation::clockwise;
  bool started_ = false;
};

static_assert(sizeof(HealthMonitor) <= 752, "the monitor's fixed state: counters (512 bytes per channel), a 256-packet window and a few fields");

}  // namespace hesai
