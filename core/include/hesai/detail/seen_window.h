// Which of the last N numbers arrived, a bit each: the window SequenceTracker (UDP sequence),
// HealthMonitor (packet slots) and ReplayGuard (RFC 4303's anti-replay window) each keep. Numbers
// run modulo 2^32; bit n mod N stands for number n. N is a power of two and a multiple of 32.
#pragma once

#include <array>
#include <cstdint>

namespace hesai::detail {

template <std::uint32_t N>
class SeenWindow {
  static_assert(N % 32 == 0 && (N & (N - 1)) == 0, "a power of two, whole 32-bit words");

 public:
  bool test(std::uint32_t n) const noexcept { return (bits_[(n & (N - 1)) / 32] >> (n % 32) & 1u) != 0; }
  void set(std::uint32_t n) noexcept { bits_[(n & (N - 1)) / 32] |= 1u << (n % 32); }
  void clear() noexcept { bits_.fill(0); }
  /// The window moves k numbers on from `newest`: newest + 1 .. newest + k are marked as not
  /// arrived (all of it when k >= N).
  void clear_after(std::uint32_t newest, std::uint32_t k) noexcept {
    if (k >= N) {
      clear();
      return;
    }
    for (std::uint32_t i = 1; i <= k; ++i) bits_[((newest + i) & (N - 1)) / 32] &= ~(1u << ((newest + i) % 32));
  }

 private:
  std::array<std::uint32_t, N / 32> bits_{};
};

}  // namespace hesai::detail
