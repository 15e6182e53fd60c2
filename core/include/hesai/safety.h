// QT128 functional-safety monitoring across packets: lidar states, faults, and a stuck
// fault-reporting system.
//
// Source: QT128C2X manual, Section 3.1.2 "UDP Data", table "Functional Safety: 17 bytes": the
// Lidar State byte holds the lidar's state in [7:5] (d-0 Init .. d-7 Standby), the fault code type
// in [4:3] (b-01 current fault, b-10 past fault) and a 3-bit rolling counter in [2:0] that
// "increments by 1 every time the fault message is updated"; "normally, the fault message is
// updated every 5 ms". The next byte holds the total fault code number [7:4] and the fault code
// ID [3:0] (the fault's position in the queue, from 1); then the outgoing fault code (u16).
//
// Cost: SafetyMonitor is 136 bytes of fixed state (its counters and five fields), no heap;
// observe() is O(1) and never fails. Not thread-safe: one monitor per sensor, fed from one thread.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/decoder.h"

namespace hesai {

/// The lidar states of the Lidar State field, bits [7:5].
enum class LidarState : std::uint8_t {
  init = 0,
  normal = 1,
  report_fault = 2,
  pre_performance_degradation = 3,
  performance_degradation = 4,
  pre_shutdown = 5,
  shutdown = 6,
  standby = 7,
};
inline constexpr std::size_t kLidarStateCount = 8;

/// "init", "normal", "report_fault", "pre_performance_degradation", "performance_degradation",
/// "pre_shutdown", "shutdown", "standby" for 0..7; "unknown" otherwise.
const char* lidar_state_name(std::uint8_t state) noexcept;

/// Fault code type values (bits [4:3]); 0 and 3 are not defined by the manual.
inline constexpr std::uint8_t kFaultCurrent = 1;
inline constexpr std::uint8_t kFaultPast = 2;

/// The rolling counter must change within this much packet time, ns: four times the manual's
/// 5 ms update period, and less than the 8 x 5 ms = 40 ms the counter needs to come back to a value.
inline constexpr std::int64_t kSafetyStallNs = 20000000;

/// Counters of functional-safety sections (packets without one count nowhere here); each
/// saturates at its largest value (hesai/saturating.h).
struct SafetyCounts {
  std::uint64_t packets = 0;                          ///< packets with a functional-safety section
  std::array<std::uint64_t, kLidarStateCount> states{};  ///< packets per lidar state (index: LidarState)
  std::uint64_t current_fault = 0;                    ///< fault code type b-01
  std::uint64_t past_fault = 0;                       ///< fault code type b-10
  std::uint64_t reserved_fault_type = 0;              ///< fault code type b-11, which the manual does not define
  std::uint64_t counter_stalls = 0;                   ///< rolling counter unchanged for more than kSafetyStallNs
  std::uint16_t last_fault_code = 0;    ///< outgoing fault code of the last packet with a current or past fault
  std::uint8_t last_fault_id = 0;       ///< its Fault Code ID (queue position, from 1); 0: no fault seen
  std::uint8_t last_fault_total = 0;    ///< its Total Fault Code Num (queue length)
};

/// Adds one packet's section to `counts`: packets, its state, its fault type and, when it
/// carries a current or past fault, the last fault code and its queue position; `stall_began`
/// (SafetyMonitor::observe()'s result) adds a stall. A section with present == false counts nothing.
void count_safety(SafetyCounts& counts, const FunctionalSafety& fs, bool stall_began) noexcept;

/// Watches one sensor's functional-safety sections, in arrival order.
///
/// Stall rule: the rolling counter is expected to change (by any amount: captures show steps of
/// 1 and of 3 mod 8) within kSafetyStallNs of packet time (PacketInfo::time_ns). When the packet
/// time since the first packet that showed the current value exceeds kSafetyStallNs, one stall
/// is counted; it is not counted again until the value changes. So each stall counts once,
/// however many packets it lasts.
///
/// Discontinuities: when the packet time goes backwards (a late packet, a clock step, a
/// restarted stream) or moves forward by more than kSafetyStallNs from the previous packet (lost
/// packets, a pause, a clock step), the monitor cannot tell whether the counter moved in the
/// interval: it restarts the stall clock at this packet and counts no stall across it. A stall
/// already counted stays the same stall while its value is unchanged, so a loss in the middle of
/// a stall does not count it twice. Lost packets within kSafetyStallNs change nothing: in that
/// time a counter updated every 5 ms cannot wrap round to the value it had.
class SafetyMonitor {
 public:
  /// One packet's section and packet time. Returns true when a stall began at this packet.
  /// Sections with present == false are ignored (false).
  bool observe(const FunctionalSafety& fs, std::int64_t time_ns) noexcept;
  const SafetyCounts& counts() const noexcept { return counts_; }
  /// True while the current stall lasts (counted, value not yet changed).
  bool stalled() const noexcept { return stalled_; }
  /// Forgets everything, counters included.
  void reset() noexcept { *this = SafetyMonitor{}; }

 private:
  SafetyCounts counts_;
  std::int64_t value_since_ns_ = 0;  // packet time of the first packet with the current value (since the last restart)
  std::int64_t last_ns_ = 0;         // packet time of the previous packet
  std::uint8_t counter_ = 0;         // current rolling counter value
  bool started_ = false;
  bool stalled_ = false;
};

static_assert(sizeof(SafetyMonitor) <= 160, "the monitor's fixed state: counters and five fields");

}  // namespace hesai
