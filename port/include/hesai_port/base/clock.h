// The host's clocks, for pacing, timeouts and receive times (POSIX clock_gettime).
#pragma once

#include <cstdint>

namespace hesai::port {

/// Wall-clock time, ns since the Unix epoch (CLOCK_REALTIME).
std::int64_t realtime_ns();
/// Monotonic time, ns (CLOCK_MONOTONIC), for pacing and timeouts.
std::int64_t monotonic_ns();
/// Sleeps until the monotonic clock reaches `deadline_ns`.
void sleep_until_ns(std::int64_t deadline_ns);

}  // namespace hesai::port
