// Waiting on a socket with a deadline and a stop flag: what the PTC transports share (transport.cpp,
// tls.cpp). Private to net/.
#pragma once

#include <poll.h>

#include <atomic>
#include <cerrno>
#include <cstdint>

#include "hesai_port/base/clock.h"

namespace hesai::port {

enum class Wait { ready, timeout, stopped };

/// How often a wait looks at its stop flag: a stop is seen within this.
inline constexpr int kStopSliceMs = 100;

/// Waits until `fd` is ready for `events` (a poll error counts as ready: the next call reports
/// it), the deadline (a monotonic_ns() value) passes, or `*stop` (null: never) is true.
inline Wait wait_fd(int fd, short events, std::int64_t deadline_ns, const std::atomic<bool>* stop) {
  for (;;) {
    if (stop != nullptr && stop->load()) return Wait::stopped;
    const std::int64_t left = deadline_ns - monotonic_ns();
    const std::int64_t ms = left <= 0 ? 0 : (left + 999999) / 1000000;  // rounded up
    const std::int64_t slice = stop != nullptr ? kStopSliceMs : 60000;
    pollfd p{fd, events, 0};
    const int r = poll(&p, 1, static_cast<int>(ms < slice ? ms : slice));
    if (r > 0 || (r < 0 && errno != EINTR)) return Wait::ready;
    if (monotonic_ns() >= deadline_ns) return Wait::timeout;
  }
}

}  // namespace hesai::port
