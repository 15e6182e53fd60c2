#include "hesai/safety.h"

#include "hesai/saturating.h"

namespace hesai {

namespace {
// to - from for to >= from, without signed overflow (the difference fits in 64 unsigned bits).
std::uint64_t elapsed_ns(std::int64_t from, std::int64_t to) {
  return static_cast<std::uint64_t>(to) - static_cast<std::uint64_t>(from);
}
constexpr std::uint64_t kStall = static_cast<std::uint64_t>(kSafetyStallNs);
}  // namespace

const char* lidar_state_name(std::uint8_t state) noexcept {
  switch (static_cast<LidarState>(state)) {
    case LidarState::init: return "init";
    case LidarState::normal: return "normal";
    case LidarState::report_fault: return "report_fault";
    case LidarState::pre_performance_degradation: return "pre_performance_degradation";
    case LidarState::performance_degradation: return "performance_degradation";
    case LidarState::pre_shutdown: return "pre_shutdown";
    case LidarState::shutdown: return "shutdown";
    case LidarState::standby: return "standby";
  }
  return "unknown";
}

void count_safety(SafetyCounts& counts, const FunctionalSafety& fs, bool stall_began) noexcept {
  if (!fs.present) return;
  saturating_increment(counts.packets);
  // The decoder gives 3 bits; the mask keeps a hand-filled struct in range too.
  saturating_increment(counts.states[fs.lidar_state & (kLidarStateCount - 1)]);
  if (stall_began) saturating_increment(counts.counter_stalls);
  switch (fs.fault_code_type) {
    case kFaultCurrent: saturating_increment(counts.current_fault); break;
    case kFaultPast: saturating_increment(counts.past_fault); break;
    case 0: return;  // no fault in this packet
    default: saturating_increment(counts.reserved_fault_type); return;
  }
  counts.last_fault_code = fs.fault_code;
  counts.last_fault_id = fs.fault_code_id;
  counts.last_fault_total = fs.total_fault_codes;
}

bool SafetyMonitor::observe(const FunctionalSafety& fs, std::int64_t time_ns) noexcept {
  if (!fs.present) return false;
  bool stall_began = false;
  const bool continuous = started_ && time_ns >= last_ns_ && elapsed_ns(last_ns_, time_ns) <= kStall;
  if (!started_ || fs.rolling_counter != counter_) {
    counter_ = fs.rolling_counter;
    value_since_ns_ = time_ns;
    stalled_ = false;
  } else if (!continuous) {
    value_since_ns_ = time_ns;  // restart the stall clock; a stall already counted stays counted
  } else if (!stalled_ && elapsed_ns(value_since_ns_, time_ns) > kStall) {  // value_since_ns_ <= last_ns_ <= time_ns
    stalled_ = true;
    stall_began = true;
  }
  started_ = true;
  last_ns_ = time_ns;
  count_safety(counts_, fs, stall_began);
  return stall_began;
}

}  // namespace hesai
