// Block time references of the Pandar40/40P, Pandar64 and QT128C2X, relative to the packet's
// absolute time t0 (date-time + timestamp), in microseconds, as the manuals give them.
// The firing time of a channel is this block time plus the channel's offset from the model's
// firing-time table (hesai/detail/tables/<model>_tables.h).
//
// Pandar40/40P and Pandar64 give block END times (the last firing of the block ends); QT128C2X
// gives block START times (the first firing starts). In dual return the two blocks holding the
// two returns of one firing share one time.
#pragma once

#include <array>
#include <cstddef>

namespace hesai::tables {

// ---- Pandar40 / Pandar40P: 10 blocks ---------------------------------------------------------
// Source: Pandar40 manual, Appendix II, 2 "Laser Firing Time Calculation".
// Single return: end of block N = t0 - 28.58 - 55.56 * (10 - N).
// Dual return: blocks (1, 2), (3, 4), ... (9, 10) hold one firing each and share
// its end time: blocks 10 & 9 = t0 - 28.58, 8 & 7 = t0 - 28.58 - 55.56 * 1, 6 & 5 = ... * 2,
// 4 & 3 = ... * 3, 2 & 1 = ... * 4. (The OCR splits this list around the firing-time list.)
// The Pandar40P document gives no block times; the Pandar40 ones serve it.

/// End of the last block before t0, in us (Pandar40/40P).
inline constexpr double pandar40_last_block_end_us = -28.58;
/// Time between two firings (blocks in single return, block pairs in dual), in us.
inline constexpr double pandar40_firing_period_us = 55.56;
inline constexpr std::size_t pandar40_block_count = 10;

/// End time of block `block` (1..10) relative to t0, in us (Pandar40/40P). `dual` selects the
/// dual-return table. The caller keeps `block` in 1..10.
constexpr double pandar40_block_end_us(std::size_t block, bool dual) {
  // Single: firings counted back from block 10. Dual: block pair k = (block + 1) / 2 of 5.
  const std::size_t firings_before_last = dual ? (5 - (block + 1) / 2) : (10 - block);
  return pandar40_last_block_end_us - pandar40_firing_period_us * static_cast<double>(firings_before_last);
}

// ---- Pandar64: 6 blocks ------------------------------------------------------------------------
// Source: Pandar64 manual, Appendix B.3 "End time of each block".
// Single return: end of block N = t0 - 42.58 - 55.56 * (6 - N).
// Dual return: blocks 6 & 5 = t0 - 42.58, 4 & 3 = t0 - 42.58 - 55.56 * 1,
// 2 & 1 = t0 - 42.58 - 55.56 * 2.

/// End of the last block before t0, in us (Pandar64).
inline constexpr double pandar64_last_block_end_us = -42.58;
/// Time between two firings (blocks in single return, block pairs in dual), in us.
inline constexpr double pandar64_firing_period_us = 55.56;
inline constexpr std::size_t pandar64_block_count = 6;

/// End time of block `block` (1..6) relative to t0, in us (Pandar64). `dual` selects the
/// dual-return table. The caller keeps `block` in 1..6.
constexpr double pandar64_block_end_us(std::size_t block, bool dual) {
  const std::size_t firings_before_last = dual ? (3 - (block + 1) / 2) : (6 - block);
  return pandar64_last_block_end_us - pandar64_firing_period_us * static_cast<double>(firings_before_last);
}

// ---- QT128C2X: 2 blocks ------------------------------------------------------------------------
// Source: QT128C2X manual, Appendix II "Start Time of Each Block" (the same in the Chinese
// edition). Single return: block 1 starts at t0 + 9, block 2 at t0 + 9 + 111.11. Dual return:
// blocks 1 and 2 both start at t0 + 9. t0 is the time the lidar commands the firing stored in
// the first block (Appendix II, "Absolute Time of Point Cloud Data Packets", Definition).

/// Start of block 1 after t0, in us (QT128C2X).
inline constexpr double qt128_first_block_start_us = 9.0;
/// Time between two firings (Section 4.2.2, Trigger Method, time-based: "lasers fire every
/// 111.11 us"), in us.
inline constexpr double qt128_firing_period_us = 111.11;
inline constexpr std::size_t qt128_block_count = 2;

/// Start time of block `block` (1..2) relative to t0, in us (QT128C2X). The caller keeps `block`
/// in 1..2.
constexpr double qt128_block_start_us(std::size_t block, bool dual) {
  return (dual || block == 1) ? qt128_first_block_start_us : qt128_first_block_start_us + qt128_firing_period_us;
}

namespace detail {
template <std::size_t N>
constexpr std::array<double, N> block_times(double (*f)(std::size_t, bool), bool dual) {
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = f(i + 1, dual);
  return out;
}
}  // namespace detail

/// The same block times as arrays, index = block - 1, per return mode, in us relative to t0.
inline constexpr std::array<double, 10> pandar40_block_end_us_single =
    detail::block_times<10>(pandar40_block_end_us, false);
inline constexpr std::array<double, 10> pandar40_block_end_us_dual =
    detail::block_times<10>(pandar40_block_end_us, true);
inline constexpr std::array<double, 6> pandar64_block_end_us_single =
    detail::block_times<6>(pandar64_block_end_us, false);
inline constexpr std::array<double, 6> pandar64_block_end_us_dual =
    detail::block_times<6>(pandar64_block_end_us, true);
inline constexpr std::array<double, 2> qt128_block_start_us_single =
    detail::block_times<2>(qt128_block_start_us, false);
inline constexpr std::array<double, 2> qt128_block_start_us_dual =
    detail::block_times<2>(qt128_block_start_us, true);

}  // namespace hesai::tables
