#include "hesai/replay.h"

namespace hesai {

bool ReplayGuard::accept(const PacketInfo& info) noexcept {
  return info.has_sequence ? accept_sequence(info.sequence) : accept_time(info.time_ns);
}

bool ReplayGuard::accept_sequence(std::uint32_t seq) noexcept {
  if (!has_sequence_) {
    has_sequence_ = true;
    newest_ = seq;
    seen_.set(seq);
    return true;
  }
  const std::uint32_t ahead = seq - newest_;
  if (ahead != 0 && ahead < 0x80000000u) {  // RFC 1982: 1 .. 2^31 - 1 ahead
    seen_.clear_after(newest_, ahead);  // the numbers skipped: not seen
    newest_ = seq;
    seen_.set(seq);
    return true;
  }
  const std::uint32_t behind = newest_ - seq;  // 0 for the newest itself
  if (behind >= kReplayWindow || seen_.test(seq)) return false;
  seen_.set(seq);
  return true;
}

bool ReplayGuard::accept_time(std::int64_t time_ns) noexcept {
  std::int64_t oldest = time_ns;
  for (std::size_t i = 0; i < time_count_; ++i) {
    if (times_[i] == time_ns) return false;
    if (times_[i] < oldest) oldest = times_[i];
  }
  if (time_count_ == kReplayTimes && time_ns <= oldest) return false;  // older than every time remembered
  times_[time_next_] = time_ns;
  time_next_ = (time_next_ + 1) % kReplayTimes;
  if (time_count_ < kReplayTimes) ++time_count_;
  return true;
}

}  // namespace hesai
