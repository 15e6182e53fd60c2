// QT128 channel-configuration CSVs (hesai/calibration.h: parse_channel_config_csv).
#include "hesai/calibration.h"

#include <array>
#include <cstddef>
#include <cstdint>

#include "csv_rows.h"

namespace hesai {

using namespace csv;

ParseResult parse_channel_config_csv(ByteView text, ChannelConfig& out) noexcept {
  out.laser_num = 0;
  out.block_num = 0;
  out.loops = 0;
  for (auto& loop : out.channel) loop.fill(0);
  out.hash.fill('\0');
  out.hash_length = 0;

  RowReader rows(text);
  Row row;
  if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  if (!word_is(row.field[0], "eeff")) return fail(Error::calib_bad_header, row.line);
  ParseResult r = check_version_row(row);
  if (r.error != Error::ok) return r;

  if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  if (row.count != 4 || !word_is(row.field[0], "lasernum") || !word_is(row.field[2], "blocknum")) {
    return fail(Error::calib_bad_header, row.line);
  }
  std::int32_t laser_num = 0;
  std::int32_t block_num = 0;
  if (!parse_int(row.field[1], laser_num) || !parse_int(row.field[3], block_num)) {
    return fail(Error::calib_bad_number, row.line);
  }
  if (!channel_in_range(laser_num, kMaxChannels) || block_num < 1 || block_num > 255) {
    return fail(Error::calib_bad_header, row.line);
  }
  const std::size_t nlaser = static_cast<std::size_t>(laser_num);

  if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  if (row.count < 1 || row.count > 2) return fail(Error::calib_bad_header, row.line);
  const std::size_t nloops = row.count;
  for (std::size_t k = 0; k < nloops; ++k) {
    if (!word_is(row.field[k], kLoopWord[k])) return fail(Error::calib_bad_header, row.line);
  }

  std::array<std::array<bool, kMaxChannels>, 2> seen{};
  std::size_t n = 0;
  bool have_hash = false;
  std::uint32_t last = row.line;
  while (rows.next(row)) {
    last = row.line;
    if (n == nlaser) {  // past the channel rows: one hash line may follow
      if (have_hash || row.count != 1) return fail(Error::calib_channel_count, row.line);
      const Field& h = row.field[0];
      if (h.size() > out.hash.size()) return fail(Error::calib_bad_row, row.line);
      for (std::size_t i = 0; i < h.size(); ++i) out.hash[i] = h.begin[i];
      out.hash_length = static_cast<std::uint8_t>(h.size());
      have_hash = true;
      continue;
    }
    if (row.count != nloops) return fail(Error::calib_bad_row, row.line);
    std::array<std::int32_t, 2> ch{};
    for (std::size_t k = 0; k < nloops; ++k) {
      if (!parse_int(row.field[k], ch[k])) return fail(Error::calib_bad_number, row.line);
    }
    for (std::size_t k = 0; k < nloops; ++k) {
      if (!channel_in_range(ch[k], kMaxChannels)) return fail(Error::calib_bad_channel, row.line);
      const std::size_t c = static_cast<std::size_t>(ch[k] - 1);
      if (seen[k][c]) return fail(Error::calib_bad_channel, row.line);
      seen[k][c] = true;
      out.channel[k][n] = static_cast<std::uint8_t>(ch[k]);
    }
    ++n;
  }
  if (n != nlaser) return fail(Error::calib_channel_count, last + 1);
  out.laser_num = static_cast<std::uint16_t>(nlaser);
  out.block_num = static_cast<std::uint8_t>(block_num);
  out.loops = static_cast<std::uint8_t>(nloops);
  return {};
}

}  // namespace hesai
