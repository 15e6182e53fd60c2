// Packet loss, duplicate and reorder accounting from the 32-bit UDP sequence number.
//
// Contract: a SequenceTracker (576 bytes: a 4096-bit window) follows one sender, in one thread;
// no heap. observe() is constant work for the next number; a jump of k numbers ahead clears k
// bits (k < 4096; a longer jump clears the 128 words at once).
#pragma once

#include <array>
#include <cstdint>
#include "hesai/detail/seen_window.h"

namespace hesai {

/// Numbers the tracker remembers behind the newest one (a power of two).
inline constexpr std::uint32_t kSequenceWindow = 4096;
static_assert((kSequenceWindow & (kSequenceWindow - 1)) == 0, "window must be a power of two");

/// What observe() made of a number.
enum class SequenceEvent : std::uint8_t {
  none,       ///< nothing observed yet
  first,      ///< the first number of the stream (nothing before it counts as lost)
  in_order,   ///< newest + 1
  gap,        ///< newest + k, 2 <= k <= window: k - 1 numbers lost
  duplicate,  ///< a number in the window seen before
  late,       ///< a number in the window not seen before: reordered (and no longer lost)
  stale,      ///< a number more than the window behind (see SequenceTracker)
  resync,     ///< the series restarted elsewhere (see SequenceTracker)
};

/// Counters of one source; each saturates at its largest value (hesai/saturating.h).
struct SequenceCounts {
  std::uint64_t packets = 0;     ///< numbers observed
  std::uint64_t lost = 0;        ///< numbers skipped and not (yet) seen
  std::uint64_t duplicates = 0;  ///< numbers seen again
  std::uint64_t reordered = 0;   ///< numbers that arrived after a later one (stale ones included)
  std::uint64_t stale = 0;       ///< of `reordered`: arrived more than the window late, `lost` not reduced
  std::uint64_t resyncs = 0;     ///< restarts of the series (sensor restart, jump of more than the window)
};

/// Tracks one source's UDP sequence numbers (a 32-bit counter that wraps at 2^32).
///
/// Numbers are compared with serial-number arithmetic (RFC 1982): n is ahead of the newest
/// number h when (n - h) mod 2^32 is in 1 .. 2^31 - 1, behind otherwise (exactly 2^31 counts as
/// behind). A bitmap remembers which of the last kSequenceWindow numbers (h - 4095 .. h) arrived.
///
/// Rules, with W = kSequenceWindow and h the newest number:
/// - n = h + k, 1 <= k <= W: the k - 1 numbers between are lost; observe() returns k - 1.
/// - n within the window behind h, already seen: duplicate.
/// - n within the window behind h, not seen: reordered. If it was counted lost, lost drops by one;
///   a number from before the first observed number (never counted lost) only counts as reordered.
/// - n = h + k with k > W: a restart of the series (a sensor restart, or a loss longer than the
///   window, which cannot be told apart): resyncs + 1, nothing added to lost, h = n.
/// - n more than the window behind (h - n >= W): either a packet held up for more than the
///   window, or the first number of a restarted series. The tracker waits for the next number:
///   * if the next number follows n (is 1 .. W ahead of it), the series restarted at n:
///     resyncs + 1, nothing added to lost across the jump, and counting goes on from n;
///   * otherwise n was a late packet: it stays counted as reordered and stale (counted so at once),
///     and lost is NOT reduced, because whether n had been counted lost (or was a copy) is no
///     longer known. Its number is not remembered.
///   Two consecutive packets held up for more than the window therefore read as a restart there
///   and a restart back (two resyncs). A restart to a number less than W behind h reads as
///   duplicates and late packets until the new series passes h.
///
/// State: 512 bytes of bitmap and a few counters; no heap.
class SequenceTracker {
 public:
  /// Observes one number; returns how many numbers were newly found missing just before it
  /// (the FrameAssembler's lost_before): k - 1 for a gap of k, 0 otherwise.
  std::uint32_t observe(std::uint32_t seq) noexcept;
  /// How the last observe() classified its number.
  SequenceEvent last_event() const noexcept { return last_; }
  const SequenceCounts& counts() const noexcept { return counts_; }
  /// The newest number of the series (meaningful after the first observe()).
  std::uint32_t newest() const noexcept { return newest_; }
  /// Forgets everything, counters included.
  void reset() noexcept { *this = SequenceTracker{}; }

 private:
  void start_series(std::uint32_t seq) noexcept;
  std::uint32_t advance(std::uint32_t k) noexcept;

  detail::SeenWindow<kSequenceWindow> seen_;  // which numbers of the window arrived
  SequenceCounts counts_;
  std::uint32_t newest_ = 0;
  std::uint32_t span_ = 0;        // numbers h - span + 1 .. h belong to the current series
  std::uint32_t candidate_ = 0;   // a number far behind, waiting for the next to tell late from restart
  bool started_ = false;
  bool has_candidate_ = false;
  SequenceEvent last_ = SequenceEvent::none;
};

}  // namespace hesai
