// Which way a sensor spins, told from the block azimuths of its packets.
#pragma once

#include <cstdint>

#include "hesai/decoder.h"

namespace hesai {

/// Watches one sensor's stream and tells whether it spins clockwise or counter-clockwise (the
/// manuals give no packet field for it: QT128C2X manual Section 1.2 and Pandar40 manual Section
/// 4.2 make it a Web Control setting). The vendor's SDK reads it from consecutive block
/// azimuths; so does this detector: within a packet, from one firing to the next, and from the
/// first block azimuth of one packet to the next one's.
///
/// Within a packet (observe(const PacketInfo&), while the direction is not known): the blocks of
/// one firing are consecutive, `returns` of them with one azimuth, so the firings' azimuths are
/// those of blocks 0, returns, 2 x returns... (single return: every block; dual return: blocks 0,
/// 2, 4...). They are fired in that order, so no late packet can reorder them: when there are two
/// firings or more and every move between consecutive firings is evidence (below) the same way,
/// the packet decides the direction by itself. Every bundled capture's packets do so except the
/// dual-return QT128C2X's, whose two blocks are one firing; those decide by the rules below.
///
/// Between packets, with m the shortest signed move from one packet's first block azimuth to the
/// next one's (clockwise positive, -180 < m <= 180 degrees, so a wrap through 0 is a short move):
/// - A move is evidence when kMinMoveCdeg <= |m| <= kMaxMoveCdeg: clockwise when m > 0. Smaller
///   moves (a stationary motor, encoder noise) and larger ones (a gap of many lost packets, whose
///   direction is ambiguous past half a turn) are not evidence and change nothing.
/// - kDecideMoves moves of evidence in a row the same way (three packets) decide the direction. A
///   lost packet only makes a move longer; a late packet gives one move the other way, which
///   interrupts a run but decides nothing.
/// - Once decided, the direction changes only after kChangeMoves moves of evidence in a row the
///   other way (a unit reconfigured while streaming).
/// - Until decided, rotation() is clockwise, the manuals' default.
///
/// State: a few bytes; no heap.
class RotationDetector {
 public:
  static constexpr std::uint16_t kMinMoveCdeg = 5;     ///< 0.05 degree
  static constexpr std::uint16_t kMaxMoveCdeg = 9000;  ///< a quarter turn
  static constexpr std::uint8_t kDecideMoves = 2;
  static constexpr std::uint8_t kChangeMoves = 8;

  /// One decoded packet: its block azimuths (info.blocks of them, info.returns per firing),
  /// by both rules. Returns true when this packet decided the direction or changed it.
  bool observe(const PacketInfo& info) noexcept;
  /// One packet's first block azimuth, 0.01 degree, by the rule between packets only. An azimuth
  /// >= 36000 is not an azimuth (validation rejects it) and is ignored. Returns true when this
  /// packet decided the direction or changed it.
  bool observe(std::uint16_t azimuth_cdeg) noexcept;
  /// True once the direction is decided.
  bool known() const noexcept { return known_; }
  /// The decided direction; clockwise until then.
  Rotation rotation() const noexcept { return rotation_; }
  /// Forgets everything, as at the start of a stream.
  void reset() noexcept { *this = RotationDetector{}; }

 private:
  std::uint16_t last_cdeg_ = 0;
  bool has_last_ = false;
  bool known_ = false;
  bool run_clockwise_ = true;  // direction of the current run of evidence
  std::uint8_t run_ = 0;       // moves of evidence in a row that way (saturates at kChangeMoves)
  Rotation rotation_ = Rotation::clockwise;
};

}  // namespace hesai
