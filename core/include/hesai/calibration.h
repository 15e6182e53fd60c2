// Calibration files: angle correction, firetime correction and QT128 channel configuration CSVs.
//
// Contract: the parsers are reentrant and thread-safe; each writes only its output struct
// (AngleCorrection 2 056 bytes, FiretimeCorrection 2 312, ChannelConfig 326: caller-owned, may be
// temporaries). Cost: linear in the text, one pass; under 1 KiB of stack on Cortex-M.
//
// The core reads no files: the caller loads a file's bytes and passes them as a ByteView; the
// parsers fill caller-owned fixed-size structs. No heap, no C library (numbers are parsed here).
//
// Accepted text, for every format: UTF-8 with or without a byte-order mark, LF or CRLF line ends,
// spaces or tabs around fields, empty fields at the end of a row ("EEFF,1,1," is three fields),
// blank lines anywhere (the shipped files end with one or none). Header words match whatever
// their case, spaces and underscores ("Laser id", "LaserID", "laser_id").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/bytes.h"
#include "hesai/detail/decimal.h"  // parse_decimal(), which the parsers use for every number
#include "hesai/error.h"
#include "hesai/model.h"

namespace hesai {

/// A unit's angle correction file. Index = channel - 1.
struct AngleCorrection {
  std::uint16_t channels = 0;                       ///< channels in the file; 0 until a parse succeeds
  std::array<double, kMaxChannels> elevation_deg{};  ///< vertical angle of each channel, degrees
  std::array<double, kMaxChannels> azimuth_deg{};    ///< horizontal offset of each channel, degrees
};

/// A firetime correction file. Index = channel - 1; [loop] is the firing sequence - 1.
struct FiretimeCorrection {
  std::uint16_t channels = 0;  ///< channels of the model; 0 until a parse succeeds
  std::uint8_t loops = 1;      ///< 1 for Pandar40P/64 files, LoopNum (2) for QT128 files
  /// Firing time offset of each channel in each loop, microseconds, as the file gives it (0 where
  /// it does not fire). Pandar40P/64 files give negative offsets (before the block's end time),
  /// QT128 files positive ones (after the block's start time).
  std::array<std::array<double, kMaxChannels>, 2> firetime_us{};
  /// Whether the channel fires in the loop (QT128 sequence 1 rests channels 1..32, sequence 2 33..64).
  std::array<std::array<bool, kMaxChannels>, 2> fires{};
};

/// QT128 channel customisation file (packets with header flags bit 6): which channels a block sends.
struct ChannelConfig {
  std::uint16_t laser_num = 0;  ///< channels sent in each block (decimal in the file); 0 until a parse succeeds
  std::uint8_t block_num = 0;   ///< blocks per packet
  std::uint8_t loops = 0;       ///< firing sequences listed (columns Loop1, Loop2): 1 or 2
  /// Per loop: channel[loop][i] is the 1-based channel of the i-th unit sent in a block, i < laser_num.
  std::array<std::array<std::uint8_t, kMaxChannels>, 2> channel{};
  /// The text of the optional line after the channel rows (a hash, "3142432" in the shipped file),
  /// without trailing empty fields; not NUL-terminated.
  std::array<char, 64> hash{};
  std::uint8_t hash_length = 0;
};

/// Outcome of a calibration parse. [[nodiscard]]: a dropped parse result is a compile error.
struct [[nodiscard]] ParseResult {
  Error error = Error::ok;
  /// 1-based line of the first bad row, 0 when ok. For a missing row (calib_channel_count with
  /// too few rows) the line after the last row; for a missing header, the line after the file.
  std::uint32_t line = 0;
};

/// Parses an angle correction CSV: an optional `EEFF,major,minor` row (QT128, manual Figure 1.7),
/// a `Laser id,Elevation,Azimuth` or `Channel,Elevation,Azimuth` header, then one row
/// `channel,elevation_deg,azimuth_deg` for each channel 1..expected_channels, each exactly once,
/// in any order.
/// Errors: invalid_argument (expected_channels not 1..kMaxChannels, line 0), calib_bad_header,
/// calib_bad_row (not 3 fields), calib_bad_number, calib_bad_channel (outside 1..expected or
/// repeated), calib_channel_count (more or fewer rows than expected_channels).
/// On error `out.channels` is 0 and the rest of `out` is unspecified.
[[nodiscard]] ParseResult parse_angle_csv(ByteView text, std::size_t expected_channels, AngleCorrection& out) noexcept;

/// Parses a firetime correction CSV, either form:
/// - Pandar40P/64: `Channel,fire time(us)` (or `(μs)`), then `channel,time_us` rows, one per
///   channel, any order. loops = 1 and every channel fires.
/// - QT128 (manual App. II): `EEFF,major,minor`, `Horizontal Resolution Mode,m,LoopNum,L`
///   (L = 1 or 2), `Loop1,Firetime1[,Loop2,Firetime2]`, then rows `ch1,t1[,ch2,t2]`: in loop k
///   channel chk fires at tk us. Channel 0 means no entry (all-zero rows pad the file). A channel
///   listed in no row of a loop does not fire in it; every channel must fire in some loop; at most
///   expected_channels rows.
/// Errors as for parse_angle_csv. On error `out.channels` is 0.
[[nodiscard]] ParseResult parse_firetime_csv(ByteView text, std::size_t expected_channels, FiretimeCorrection& out) noexcept;

/// Parses a QT128 channel configuration CSV: `EEFF,major,minor`, `LaserNum,N,BlockNum,B`
/// (N = 1..kMaxChannels, B = 1..255, both decimal), `Loop1[,Loop2]`, then N rows of one channel
/// (1..kMaxChannels) per loop, no channel twice in a loop, then an optional hash line of one field
/// (up to 64 characters).
/// Errors: calib_bad_header, calib_bad_row, calib_bad_number, calib_bad_channel, calib_channel_count
/// (fewer than N channel rows, or any row after them but a single hash line). A hash line of more
/// than 64 characters is calib_bad_row. On error `out.laser_num` is 0.
[[nodiscard]] ParseResult parse_channel_config_csv(ByteView text, ChannelConfig& out) noexcept;

}  // namespace hesai
