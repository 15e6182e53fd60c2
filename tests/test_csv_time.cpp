// The CSV's time_ns column (format_csv_row writes numbers of 10 digits and more as a leading part
// and the last 9 digits): every value against printf's %lld, around each power of ten, the 9-digit
// boundary, leading zeros in the last 9 digits, negative values and the int64 extremes.
#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "hesai_port/formats/writers.h"

namespace {

std::string last_field(const hesai::Point& p) {
  char row[hesai::port::kCsvMaxRow];
  const std::string s(row, hesai::port::format_csv_row(row, p, 0, 0));
  return s.substr(s.rfind(',') + 1);
}

TEST(CsvTime, EqualsPrintfAtEveryBoundary) {
  std::vector<std::int64_t> values = {0, 1, -1, 999999999, 1000000000, 1000000001, 1999999999,
                                      1700000000000000000, 1700000000000000001, 1700000000100000000,
                                      1700000000999999999, 1700000001000000000, -1700000000123456789,
                                      std::numeric_limits<std::int64_t>::max(),
                                      std::numeric_limits<std::int64_t>::min()};
  for (std::int64_t ten = 1; ten <= std::numeric_limits<std::int64_t>::max() / 10; ten *= 10) {
    for (const std::int64_t v : {ten - 1, ten, ten + 1, 3 * ten + 7}) {
      values.push_back(v);
      values.push_back(-v);
    }
  }
  std::uint64_t x = 88172645463325252u;  // xorshift64: values of every length
  for (int i = 0; i < 20000; ++i) {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    values.push_back(static_cast<std::int64_t>(x >> (i % 64)));
  }
  for (const std::int64_t v : values) {
    hesai::Point p{};
    p.time_ns = v;
    char expected[32];
    std::snprintf(expected, sizeof expected, "%" PRId64, v);
    ASSERT_EQ(last_field(p), expected) << v;
  }
}

}  // namespace
