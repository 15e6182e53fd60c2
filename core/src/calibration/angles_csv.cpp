// Angle correction CSVs (hesai/calibration.h: parse_angle_csv).
#include "hesai/calibration.h"

#include <array>
#include <cstddef>
#include <cstdint>

#include "csv_rows.h"

namespace hesai {

using namespace csv;

ParseResult parse_angle_csv(ByteView text, std::size_t expected_channels, AngleCorrection& out) noexcept {
  out.channels = 0;
  out.elevation_deg.fill(0.0);
  out.azimuth_deg.fill(0.0);
  if (!expected_ok(expected_channels)) return fail(Error::invalid_argument, 0);

  RowReader rows(text);
  Row row;
  if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  if (word_is(row.field[0], "eeff")) {  // QT128, manual Figure 1.7
    const ParseResult r = check_version_row(row);
    if (r.error != Error::ok) return r;
    if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  }
  if (row.count != 3 || !is_channel_word(row.field[0]) || !word_is(row.field[1], "elevation") ||
      !word_is(row.field[2], "azimuth")) {
    return fail(Error::calib_bad_header, row.line);
  }

  std::array<bool, kMaxChannels> seen{};
  std::size_t n = 0;
  std::uint32_t last = row.line;
  while (rows.next(row)) {
    last = row.line;
    if (n == expected_channels) return fail(Error::calib_channel_count, row.line);
    if (row.count != 3) return fail(Error::calib_bad_row, row.line);
    std::int32_t ch = 0;
    double elevation = 0.0;
    double azimuth = 0.0;
    if (!parse_int(row.field[0], ch) || !parse_number(row.field[1], elevation) ||
        !parse_number(row.field[2], azimuth)) {
      return fail(Error::calib_bad_number, row.line);
    }
    if (!channel_in_range(ch, expected_channels)) return fail(Error::calib_bad_channel, row.line);
    const std::size_t i = static_cast<std::size_t>(ch - 1);
    if (seen[i]) return fail(Error::calib_bad_channel, row.line);
    seen[i] = true;
    out.elevation_deg[i] = elevation;
    out.azimuth_deg[i] = azimuth;
    ++n;
  }
  if (n != expected_channels) return fail(Error::calib_channel_count, last + 1);
  out.channels = static_cast<std::uint16_t>(expected_channels);
  return {};
}

}  // namespace hesai
