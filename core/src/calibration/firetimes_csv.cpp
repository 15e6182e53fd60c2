// Firing-time CSVs, both forms: Pandar40P/64 channel,time pairs and the QT128 two-loop file
// (hesai/calibration.h: parse_firetime_csv).
#include "hesai/calibration.h"

#include <array>
#include <cstddef>
#include <cstdint>

#include "csv_rows.h"

namespace hesai {

using namespace csv;

namespace {

ParseResult parse_qt_firetime(RowReader& rows, Row& row, std::size_t expected, FiretimeCorrection& out) {
  ParseResult r = check_version_row(row);
  if (r.error != Error::ok) return r;

  if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  if (row.count != 4 || !word_is(row.field[0], "horizontalresolutionmode") || !word_is(row.field[2], "loopnum")) {
    return fail(Error::calib_bad_header, row.line);
  }
  std::int32_t mode = 0;
  std::int32_t loops = 0;
  if (!parse_int(row.field[1], mode) || !parse_int(row.field[3], loops)) return fail(Error::calib_bad_number, row.line);
  if (loops < 1 || loops > 2) return fail(Error::calib_bad_header, row.line);
  const std::size_t nloops = static_cast<std::size_t>(loops);

  if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  if (row.count != 2 * nloops) return fail(Error::calib_bad_header, row.line);
  for (std::size_t k = 0; k < nloops; ++k) {
    if (!word_is(row.field[2 * k], kLoopWord[k]) || !word_is(row.field[2 * k + 1], kFiretimeWord[k])) {
      return fail(Error::calib_bad_header, row.line);
    }
  }

  std::size_t n = 0;
  std::uint32_t last = row.line;
  while (rows.next(row)) {
    last = row.line;
    if (n == expected) return fail(Error::calib_channel_count, row.line);
    if (row.count != 2 * nloops) return fail(Error::calib_bad_row, row.line);
    std::array<std::int32_t, 2> ch{};
    std::array<double, 2> t{};
    for (std::size_t k = 0; k < nloops; ++k) {
      if (!parse_int(row.field[2 * k], ch[k]) || !parse_number(row.field[2 * k + 1], t[k])) {
        return fail(Error::calib_bad_number, row.line);
      }
    }
    for (std::size_t k = 0; k < nloops; ++k) {
      if (ch[k] == 0) continue;  // no entry (padding)
      if (!channel_in_range(ch[k], expected)) return fail(Error::calib_bad_channel, row.line);
      const std::size_t i = static_cast<std::size_t>(ch[k] - 1);
      if (out.fires[k][i]) return fail(Error::calib_bad_channel, row.line);
      out.fires[k][i] = true;
      out.firetime_us[k][i] = t[k];
    }
    ++n;
  }
  for (std::size_t i = 0; i < expected; ++i) {
    if (!out.fires[0][i] && !out.fires[1][i]) return fail(Error::calib_channel_count, last + 1);
  }
  out.loops = static_cast<std::uint8_t>(nloops);
  return {};
}

}  // namespace

ParseResult parse_firetime_csv(ByteView text, std::size_t expected_channels, FiretimeCorrection& out) noexcept {
  out.channels = 0;
  out.loops = 1;
  for (auto& loop : out.firetime_us) loop.fill(0.0);
  for (auto& loop : out.fires) loop.fill(false);
  if (!expected_ok(expected_channels)) return fail(Error::invalid_argument, 0);

  RowReader rows(text);
  Row row;
  if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  if (word_is(row.field[0], "eeff")) {  // QT128, manual App. II
    const ParseResult r = parse_qt_firetime(rows, row, expected_channels, out);
    if (r.error != Error::ok) return r;
    out.channels = static_cast<std::uint16_t>(expected_channels);
    return r;
  }

  // Pandar40P / Pandar64: channel,time pairs.
  if (row.count != 2 || !is_channel_word(row.field[0]) || !is_firetime_word(row.field[1])) {
    return fail(Error::calib_bad_header, row.line);
  }
  std::size_t n = 0;
  std::uint32_t last = row.line;
  while (rows.next(row)) {
    last = row.line;
    if (n == expected_channels) return fail(Error::calib_channel_count, row.line);
    if (row.count != 2) return fail(Error::calib_bad_row, row.line);
    std::int32_t ch = 0;
    double t = 0.0;
    if (!parse_int(row.field[0], ch) || !parse_number(row.field[1], t)) return fail(Error::calib_bad_number, row.line);
    if (!channel_in_range(ch, expected_channels)) return fail(Error::calib_bad_channel, row.line);
    const std::size_t i = static_cast<std::size_t>(ch - 1);
    if (out.fires[0][i]) return fail(Error::calib_bad_channel, row.line);
    out.fires[0][i] = true;
    out.firetime_us[0][i] = t;
    ++n;
  }
  if (n != expected_channels) return fail(Error::calib_channel_count, last + 1);
  out.channels = static_cast<std::uint16_t>(expected_channels);
  return {};
}

}  // namespace hesai
