#include "hesai/sequence.h"

#include "hesai/saturating.h"

namespace hesai {

namespace {
constexpr std::uint32_t kSerialHalf = 0x80000000u;  // 2^31: RFC 1982's undefined distance

// (b - a) mod 2^32 is "ahead" when in 1 .. 2^31 - 1.
constexpr bool is_ahead(std::uint32_t distance) { return distance != 0 && distance < kSerialHalf; }
static_assert(is_ahead(1u - 0xFFFFFFFEu), "1 is three ahead of 0xFFFFFFFE");
static_assert(!is_ahead(0xFFFFFFFEu - 1u), "0xFFFFFFFE is behind 1");
static_assert(!is_ahead(kSerialHalf), "half the space counts as behind");
}  // namespace

void SequenceTracker::start_series(std::uint32_t seq) noexcept {
  seen_.clear();
  newest_ = seq;
  span_ = 1;
  seen_.set(seq);
}

// Moves the newest number k ahead (1 <= k <= window); the k - 1 numbers between are lost.
std::uint32_t SequenceTracker::advance(std::uint32_t k) noexcept {
  seen_.clear_after(newest_, k);
  newest_ += k;
  seen_.set(newest_);
  span_ = span_ + k < kSequenceWindow ? span_ + k : kSequenceWindow;
  const std::uint32_t lost = k - 1;
  saturating_add(counts_.lost, lost);
  return lost;
}

std::uint32_t SequenceTracker::observe(std::uint32_t seq) noexcept {
  saturating_increment(counts_.packets);
  if (!started_) {
    started_ = true;
    start_series(seq);
    last_ = SequenceEvent::first;
    return 0;
  }

  const std::uint32_t d = seq - newest_;
  const bool ahead = is_ahead(d);
  const std::uint32_t behind = 0u - d;  // meaningful when !ahead
  const bool in_window = ahead ? d <= kSequenceWindow : behind < kSequenceWindow;

  if (has_candidate_) {
    has_candidate_ = false;
    const std::uint32_t from_candidate = seq - candidate_;
    if (!in_window && from_candidate >= 1 && from_candidate <= kSequenceWindow) {
      // The far-behind number was the first of a restarted series: undo its count as stale.
      saturating_subtract(counts_.reordered, 1);
      saturating_subtract(counts_.stale, 1);
      saturating_increment(counts_.resyncs);
      start_series(candidate_);
      last_ = SequenceEvent::resync;
      return advance(from_candidate);
    }
  }

  if (ahead) {
    if (d <= kSequenceWindow) {
      last_ = d == 1 ? SequenceEvent::in_order : SequenceEvent::gap;
      return advance(d);
    }
    saturating_increment(counts_.resyncs);  // too far ahead to count as loss
    start_series(seq);
    last_ = SequenceEvent::resync;
    return 0;
  }

  if (behind < kSequenceWindow) {
    if (seen_.test(seq)) {
      saturating_increment(counts_.duplicates);
      last_ = SequenceEvent::duplicate;
      return 0;
    }
    seen_.set(seq);
    saturating_increment(counts_.reordered);
    if (behind < span_ && counts_.lost > 0) saturating_subtract(counts_.lost, 1);  // it was counted lost when skipped
    last_ = SequenceEvent::late;
    return 0;
  }

  // More than the window behind: late, unless the next number shows a restart here.
  candidate_ = seq;
  has_candidate_ = true;
  saturating_increment(counts_.reordered);
  saturating_increment(counts_.stale);
  last_ = SequenceEvent::stale;
  return 0;
}

}  // namespace hesai
