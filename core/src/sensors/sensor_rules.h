// Shared by decoder.cpp and the sensors' files (internal to the core): rounding to integer
// nanoseconds, and the conversion of the manuals' block-time tables by it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/bytes.h"
#include "hesai/error.h"
#include "hesai/model.h"

namespace hesai::detail {

constexpr std::int32_t round_to_int(double v) {
  return static_cast<std::int32_t>(v < 0 ? v - 0.5 : v + 0.5);
}

/// Block time offsets from t0 in ns (tables/block_times.h: end times for Pandar40/40P/64, start
/// times for QT128), indexed [dual][block].
template <std::size_t N>
constexpr std::array<std::array<std::int32_t, N>, 2> block_ns(const std::array<double, N>& single,
                                                              const std::array<double, N>& dual) {
  std::array<std::array<std::int32_t, N>, 2> ns{};
  for (std::size_t b = 0; b < N; ++b) {
    ns[0][b] = round_to_int(single[b] * 1000);
    ns[1][b] = round_to_int(dual[b] * 1000);
  }
  return ns;
}

}  // namespace hesai::detail
