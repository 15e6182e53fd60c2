#include "hesai/rotation.h"

namespace hesai {

namespace {
constexpr std::int32_t kTurn = 36000;  // 360 degrees in 0.01 degree

// Shortest signed move from `from` to `to`, clockwise positive: -17999 .. 18000.
constexpr std::int32_t shortest_move(std::int32_t from, std::int32_t to) {
  const std::int32_t m = ((to - from) % kTurn + kTurn) % kTurn;  // 0 .. 35999 clockwise
  return m > kTurn / 2 ? m - kTurn : m;
}

static_assert(shortest_move(35950, 50) == 100, "clockwise through 0");
static_assert(shortest_move(50, 35950) == -100, "counter-clockwise through 0");
}  // namespace

bool RotationDetector::observe(std::uint16_t azimuth_cdeg) noexcept {
  if (azimuth_cdeg >= kTurn) return false;
  const bool first = !has_last_;
  const std::int32_t move = shortest_move(last_cdeg_, azimuth_cdeg);
  last_cdeg_ = azimuth_cdeg;
  has_last_ = true;
  const std::int32_t size = move < 0 ? -move : move;
  if (first || size < kMinMoveCdeg || size > kMaxMoveCdeg) return false;

  const bool clockwise = move > 0;
  if (run_ == 0 || clockwise != run_clockwise_) {
    run_clockwise_ = clockwise;
    run_ = 0;
  }
  if (run_ < kChangeMoves) ++run_;
  const Rotation seen = clockwise ? Rotation::clockwise : Rotation::counterclockwise;
  if (known_ && seen == rotation_) return false;
  if (run_ < (known_ ? kChangeMoves : kDecideMoves)) return false;
  known_ = true;
  rotation_ = seen;
  return true;
}

bool RotationDetector::observe(const PacketInfo& info) noexcept {
  const std::size_t blocks = info.blocks <= info.block_azimuth.size() ? info.blocks : info.block_azimuth.size();
  if (blocks == 0) return false;
  const bool changed = observe(info.block_azimuth[0]);
  if (known_) return changed;

  // Within the packet: the firings' azimuths, blocks 0, r, 2r... with r blocks per firing.
  const std::size_t step = info.returns != 0 ? info.returns : 1;
  int clockwise_moves = 0;
  int counterclockwise_moves = 0;
  for (std::size_t b = step; b < blocks; b += step) {
    const std::uint16_t from = info.block_azimuth[b - step];
    const std::uint16_t to = info.block_azimuth[b];
    if (from >= kTurn || to >= kTurn) return false;
    const std::int32_t move = shortest_move(from, to);
    const std::int32_t size = move < 0 ? -move : move;
    if (size < kMinMoveCdeg || size > kMaxMoveCdeg) return false;
    if (move > 0) {
      ++clockwise_moves;
    } else {
      ++counterclockwise_moves;
    }
  }
  if (clockwise_moves + counterclockwise_moves == 0) return false;  // one firing: no evidence
  if (clockwise_moves != 0 && counterclockwise_moves != 0) return false;
  const bool clockwise = clockwise_moves != 0;
  known_ = true;
  rotation_ = clockwise ? Rotation::clockwise : Rotation::counterclockwise;
  if (run_clockwise_ != clockwise) run_ = 0;  // moves the other way so far count for no change
  run_clockwise_ = clockwise;
  return true;
}

}  // namespace hesai
