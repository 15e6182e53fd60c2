// Shared by decoder.cpp and the sensors' files (internal to the core): each sensor's
// identification rule, defined in that sensor's file, and the conversion of the manuals'
// block-time tables to integer nanoseconds.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/bytes.h"
#include "hesai/error.h"
#include "hesai/model.h"

namespace hesai::detail {

/// Pandar40 (1256 bytes) or Pandar40P (1262/1266): a payload starting FF EE that is not GPS.
[[nodiscard]] Error identify_pandar40(ByteView p, Model& model) noexcept;
/// True when an EE FF header names 64 lasers and 6 blocks (Pandar64).
bool is_pandar64_header(ByteView p) noexcept;
/// Pandar64 by length (1194, or 1198 with UDP sequence), once is_pandar64_header() holds.
[[nodiscard]] Error identify_pandar64(ByteView p, Model& model) noexcept;
/// QT128C2X: EE FF, protocol 3.2, 2 blocks, 128 lasers (1..128 with customised channels, flags
/// bit 6), the length the laser num and flags imply.
[[nodiscard]] Error identify_qt128(ByteView p, Model& model) noexcept;
/// PandarQT64: EE FF, point cloud protocol 3.1 (sensors/qt64.cpp).
[[nodiscard]] Error identify_qt64(ByteView p, Model& model) noexcept;
/// PandarXT16, XT32, XT32M2X: EE FF, point cloud protocol 6.1 (sensors/xt.cpp).
[[nodiscard]] Error identify_xt(ByteView p, Model& model) noexcept;

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
