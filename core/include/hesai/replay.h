// Replayed signed packets: a signature proves who made a packet, not that it is new. A ReplayGuard
// refuses a signed packet that does not move forward within one signature session.
//
// The rule is the sliding window of IPsec's anti-replay service (RFC 4303, section 3.4.3), over
// the packet's UDP sequence number, which the QT128C2X's signature covers (QT128C2X manual 4.9.3:
// it "is calculated using Point Cloud UDP Data (from Header to Tail, appended with UDP Sequence)"):
// - a number ahead of the newest accepted one (serial-number arithmetic, RFC 1982) is new;
// - a number less than kReplayWindow behind it that was not accepted yet is new (reordered);
// - a number accepted before, or kReplayWindow or more behind, is a replay.
// A packet without a sequence (QT128C2X flags bit 0 clear) is judged by its packet time the same
// way, against the last kReplayTimes accepted times: a time accepted before, or not after the
// oldest of them once there are kReplayTimes, is a replay.
//
// One guard per sensor and session key: a new key (a session started again) starts it anew
// (reset()), since a packet signed under the old key no longer verifies. A sensor that restarts
// its sequence within a session is refused until its numbers pass the old ones: a unit that
// reboots loses its session ("in case of a reboot, start a session again", QT128C2X manual 4.9.3),
// so it gets a new key first.
//
// Contract: a ReplayGuard (about 650 bytes) follows one sender, in one thread; no heap.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/decoder.h"
#include "hesai/detail/seen_window.h"

namespace hesai {

/// Sequence numbers a ReplayGuard remembers behind the newest accepted one.
inline constexpr std::uint32_t kReplayWindow = 1024;
static_assert((kReplayWindow & (kReplayWindow - 1)) == 0 && kReplayWindow % 32 == 0, "a power of two, whole words");
/// Packet times a ReplayGuard remembers, for packets without a sequence.
inline constexpr std::size_t kReplayTimes = 64;

class ReplayGuard {
 public:
  /// True when the packet is new (and from now on remembered); false when it is a replay.
  /// `info` is the decoded packet's (its sequence when has_sequence, else its time).
  bool accept(const PacketInfo& info) noexcept;
  /// Forgets every packet (a new session key).
  void reset() noexcept { *this = ReplayGuard{}; }

 private:
  bool accept_sequence(std::uint32_t seq) noexcept;
  bool accept_time(std::int64_t time_ns) noexcept;

  detail::SeenWindow<kReplayWindow> seen_;  // which numbers of the window were accepted
  std::uint32_t newest_ = 0;
  bool has_sequence_ = false;  // newest_ holds an accepted number
  std::array<std::int64_t, kReplayTimes> times_{};  // the last accepted times, a ring
  std::size_t time_count_ = 0;  // times accepted, up to kReplayTimes
  std::size_t time_next_ = 0;   // where the next goes
};

}  // namespace hesai
