// Calendar date-time to Unix time (UTC) and back, without the C library.
#pragma once

#include <cstdint>

namespace hesai {

/// A broken-down UTC date-time as the sensors send it.
struct DateTime {
  std::int32_t year = 1970;  ///< full year, e.g. 2024
  std::uint8_t month = 1;    ///< 1..12
  std::uint8_t day = 1;      ///< 1..days in month
  std::uint8_t hour = 0;     ///< 0..23
  std::uint8_t minute = 0;   ///< 0..59
  std::uint8_t second = 0;   ///< 0..59 (a leap second 60 is rejected: the sensors do not send it)
};

constexpr bool is_leap_year(std::int32_t y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

constexpr std::uint8_t days_in_month(std::int32_t y, std::uint8_t m) {
  constexpr std::uint8_t days[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return (m == 2 && is_leap_year(y)) ? 29 : days[m - 1];
}

/// True when every field is inside the calendar and the year is 1970..2500.
constexpr bool is_valid(const DateTime& t) {
  return t.year >= 1970 && t.year <= 2500 && t.month >= 1 && t.month <= 12 && t.day >= 1 &&
         t.day <= days_in_month(t.year, t.month) && t.hour <= 23 && t.minute <= 59 && t.second <= 59;
}

/// Days from 1970-01-01 to the given civil date (proleptic Gregorian; H. Hinnant's algorithm).
constexpr std::int64_t days_from_civil(std::int32_t y, std::uint32_t m, std::uint32_t d) {
  y -= m <= 2 ? 1 : 0;
  const std::int32_t era = (y >= 0 ? y : y - 399) / 400;
  const std::uint32_t yoe = static_cast<std::uint32_t>(y - era * 400);
  const std::uint32_t doy = (153 * (m > 2 ? m - 3 : m + 9) + 2) / 5 + d - 1;
  const std::uint32_t doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return static_cast<std::int64_t>(era) * 146097 + static_cast<std::int64_t>(doe) - 719468;
}

/// Seconds since the Unix epoch of a valid DateTime.
constexpr std::int64_t unix_seconds(const DateTime& t) {
  return days_from_civil(t.year, t.month, t.day) * 86400 + t.hour * 3600 + t.minute * 60 + t.second;
}

/// The UTC date-time of `seconds` since the Unix epoch, 0 <= seconds < 2^32 (the inverse of
/// unix_seconds() there; H. Hinnant's civil_from_days). Used where a sensor sends Unix seconds.
constexpr DateTime date_time_from_unix(std::uint32_t seconds) {
  const std::uint32_t days = seconds / 86400;
  const std::uint32_t rest = seconds % 86400;
  const std::uint32_t z = days + 719468;  // days since 0000-03-01
  const std::uint32_t era = z / 146097;
  const std::uint32_t doe = z - era * 146097;                                      // [0, 146096]
  const std::uint32_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;  // [0, 399]
  const std::uint32_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);                // [0, 365], from March 1
  const std::uint32_t mp = (5 * doy + 2) / 153;                                     // [0, 11], March = 0
  DateTime t;
  t.month = static_cast<std::uint8_t>(mp < 10 ? mp + 3 : mp - 9);
  t.year = static_cast<std::int32_t>(yoe + era * 400 + (t.month <= 2 ? 1 : 0));
  t.day = static_cast<std::uint8_t>(doy - (153 * mp + 2) / 5 + 1);
  t.hour = static_cast<std::uint8_t>(rest / 3600);
  t.minute = static_cast<std::uint8_t>(rest / 60 % 60);
  t.second = static_cast<std::uint8_t>(rest % 60);
  return t;
}

// Hand-checked anchors: 2000-01-01 is day 10957; 2024-02-29 12:00:00 is 1709208000.
static_assert(days_from_civil(1970, 1, 1) == 0);
static_assert(days_from_civil(2000, 1, 1) == 10957);
static_assert(unix_seconds(DateTime{2024, 2, 29, 12, 0, 0}) == 1709208000);
// And back: 1709208000 is 2024-02-29 12:00:00; 2^32 - 1 is 2106-02-07 06:28:15.
static_assert(date_time_from_unix(1709208000).year == 2024 && date_time_from_unix(1709208000).month == 2 &&
              date_time_from_unix(1709208000).day == 29 && date_time_from_unix(1709208000).hour == 12);
static_assert(unix_seconds(date_time_from_unix(0xFFFFFFFFu)) == 0xFFFFFFFFLL);
static_assert(date_time_from_unix(0xFFFFFFFFu).year == 2106 && date_time_from_unix(0xFFFFFFFFu).day == 7);

}  // namespace hesai
