// Row types of the built-in calibration tables typed from the Hesai manuals.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace hesai::tables {

/// Design angles of one channel: elevation (vertical angle, up positive) and azimuth offset
/// (horizontal angle added to the block azimuth, clockwise seen from above positive), in degrees.
struct ChannelAngle {
  double elevation_deg;
  double azimuth_deg;
};

/// One row of a Pandar40/Pandar64 firing-time table, in the manual's order: `order` is the number
/// the manual prints in front of the row (Pandar64: "Firing sequence"; Pandar40: list item),
/// `channel` is 1-based, `time_us` is the printed value in microseconds (sign convention: see
/// the table's comment).
struct FireRow {
  std::uint8_t order;
  std::uint8_t channel;
  double time_us;
};

/// One row of the QT128C2X firetime correction table (channels 1-based, times in microseconds
/// after the block start). Row k lists the k-th firing of each firing sequence (loop).
struct QtFireRow {
  std::uint8_t loop1_channel;
  double loop1_time_us;
  std::uint8_t loop2_channel;
  double loop2_time_us;
};

namespace detail {

/// True when every channel 1..N appears exactly once in `rows`.
template <std::size_t N, std::size_t R>
constexpr bool each_channel_once(const std::array<FireRow, R>& rows) {
  std::array<int, N + 1> seen{};
  for (std::size_t i = 0; i < R; ++i) {
    const std::size_t c = rows[i].channel;
    if (c < 1 || c > N) return false;
    ++seen[c];
  }
  for (std::size_t c = 1; c <= N; ++c) {
    if (seen[c] != 1) return false;
  }
  return true;
}

/// True when the rows' times never decrease, and the printed order numbers never decrease.
template <std::size_t R>
constexpr bool rows_ascending(const std::array<FireRow, R>& rows) {
  for (std::size_t i = 1; i < R; ++i) {
    if (rows[i].time_us < rows[i - 1].time_us || rows[i].order < rows[i - 1].order) return false;
  }
  return true;
}

/// Per-channel array (index channel-1) of `sign * time_us` from rows listing each channel once.
template <std::size_t N, std::size_t R>
constexpr std::array<double, N> fire_offsets_by_channel(const std::array<FireRow, R>& rows, double sign) {
  std::array<double, N> out{};
  for (std::size_t i = 0; i < R; ++i) out[static_cast<std::size_t>(rows[i].channel - 1)] = sign * rows[i].time_us;
  return out;
}

/// True when the elevations strictly decrease from channel 1 to channel N (top to bottom).
template <std::size_t N>
constexpr bool elevations_descending(const std::array<ChannelAngle, N>& a) {
  for (std::size_t i = 1; i < N; ++i) {
    if (!(a[i].elevation_deg < a[i - 1].elevation_deg)) return false;
  }
  return true;
}

}  // namespace detail

}  // namespace hesai::tables
