#include "hesai/replay.h"

namespace hesai {

namespace {
constexpr std::uint32_t kMask = kReplayWindow - 1;
}  // namespace

bool ReplayGuard::accept(const PacketInfo& info) noexcept {
  return info.has_sequence ? accept_sequence(info.sequence) : accept_time(info.time_ns);
}

bool ReplayGuard::accept_sequence(std::uint32_t seq) noexcept {
  const auto bit = [](std::uint32_t n) { return std::uint32_t{1} << (n & kMask) % 32; };
  const auto word = [this](std::uint32_t n) -> std::uint32_t& { return seen_[(n & kMask) / 32]; };
  if (!has_sequence_) {
    has_sequence_ = true;
    newest_ = seq;
    word(seq) |= bit(seq);
    return true;
  }
  const std::uint32_t ahead = seq - newest_;
  if (ahead != 0 && ahead < 0x80000000u) {  // RFC 1982: 1 .. 2^31 - 1 ahead
    if (ahead >= kReplayWindow) {
      seen_.fill(0);
    } else {
      for (std::uint32_t n = newest_ + 1; n != seq; ++n) word(n) &= ~bit(n);  // numbers skipped: not seen
    }
    newest_ = seq;
    word(seq) |= bit(seq);
    return true;
  }
  const std::uint32_t behind = newest_ - seq;  // 0 for the newest itself
  if (behind >= kReplayWindow || (word(seq) & bit(seq)) != 0) return false;
  word(seq) |= bit(seq);
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
