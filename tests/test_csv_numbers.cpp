// Every number of a CSV row against the C library's printf, the reference the column contract
// (hesai_port/formats/writers.h) is written in: "%.3f" / "%.4f" of the float's exact value (as a
// double), a minus sign dropped when no digit other than 0 shows, and "%u" / "%" PRIu64 / "%"
// PRId64 for the integers. Whole rows are compared, from format_csv_row and from CsvWriter's
// files, so a field that runs into its neighbour fails too.
//
// About 1.3 million floats, each at 3 and 4 decimals:
//   - strides through every float of the ranges a sensor produces (distance 0..300 m, x/y/z
//     +-300 m, angles -360..720 deg), steps odd so the low significand bits vary;
//   - every float in windows where the digits change length or the formatter changes path:
//     around 0 and the sign boundaries -0.0005 / -0.00005, the powers of ten, 300, 360, 720, the
//     fast path's end (|v| * 10^d = 2^51) and the llrint/to_chars switch (|v| * 10^d = 4e18);
//   - the exact ties, the only floats whose rounding direction is decided by ties-to-even: odd
//     n/16 (halfway at 3 decimals) and odd n/32 (at 4) up to +-1024, with their neighbours;
//   - the floats nearest the decimal boundaries (k + 0.5) / 10^d, and one float on each side,
//     for k through and beyond the sensor ranges;
//   - random bit patterns (NaN payloads, infinities, denormals, huge values among them) and the
//     special values by name.
#include <gtest/gtest.h>

#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "hesai_port/formats/writers.h"

namespace {

using hesai::Point;
namespace port = hesai::port;

// printf's fixed-point digits of the float's value, with the column contract's sign rule.
const char* reference_fixed(char (&s)[64], float v, int decimals) {
  std::snprintf(s, sizeof s, "%.*f", decimals, static_cast<double>(v));
  const char* t = s;
  if (t[0] == '-' && std::strspn(t + 1, "0.") == std::strlen(t + 1)) ++t;  // "-0.000": "0.000"
  return t;
}
std::string reference_fixed(float v, int decimals) {
  char s[64];
  return reference_fixed(s, v, decimals);
}

std::string reference_row(const Point& p, std::uint32_t frame, std::uint64_t packet) {
  char head[96];
  std::snprintf(head, sizeof head, "%" PRIu32 ",%" PRIu64 ",%u,%u,%u,", frame, packet, unsigned{p.block},
                unsigned{p.channel}, unsigned{p.return_index});
  char tail[48];
  std::snprintf(tail, sizeof tail, ",%u,%" PRId64, unsigned{p.intensity}, p.time_ns);
  return head + reference_fixed(p.azimuth_deg, 3) + "," + reference_fixed(p.elevation_deg, 3) + "," +
         reference_fixed(p.distance_m, 4) + "," + reference_fixed(p.x, 4) + "," + reference_fixed(p.y, 4) + "," +
         reference_fixed(p.z, 4) + tail;
}

std::string row_of(const Point& p, std::uint32_t frame, std::uint64_t packet) {
  char row[port::kCsvMaxRow];
  return std::string(row, port::format_csv_row(row, p, frame, packet));
}

float from_bits(std::uint32_t b) {
  float v;
  std::memcpy(&v, &b, sizeof v);
  return v;
}
std::uint32_t bits_of(float v) {
  std::uint32_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}
// Floats in value order as integers: -0 and +0 are -0 and 0, neighbours differ by 1.
std::int64_t ordered(float v) {
  const std::uint32_t b = bits_of(v);
  return (b & 0x80000000u) != 0 ? -static_cast<std::int64_t>(b & 0x7FFFFFFFu) : static_cast<std::int64_t>(b);
}
float from_ordered(std::int64_t o) {
  return o < 0 ? from_bits(0x80000000u | static_cast<std::uint32_t>(-o)) : from_bits(static_cast<std::uint32_t>(o));
}

// Every float of [lo, hi] with a step of about (count of floats) / n, odd.
void stride(std::vector<float>& out, float lo, float hi, std::int64_t n) {
  const std::int64_t a = ordered(lo), b = ordered(hi);
  const std::int64_t step = ((b - a) / n) | 1;
  for (std::int64_t o = a; o <= b; o += step) out.push_back(from_ordered(o));
  out.push_back(hi);
}
// Every float within `ulps` of v.
void around(std::vector<float>& out, float v, std::int64_t ulps) {
  const std::int64_t c = ordered(v);
  for (std::int64_t o = c - ulps; o <= c + ulps; ++o) out.push_back(from_ordered(o));
}

std::vector<float> test_values() {
  std::vector<float> v;
  v.reserve(1400000);
  // The sensor's ranges.
  stride(v, 0.0f, 300.0f, 200000);
  stride(v, -300.0f, 300.0f, 200000);
  stride(v, -360.0f, 720.0f, 200000);
  // Where the digits change length, the sign rule, the paths of the formatter.
  for (const float c : {0.0f, -0.0005f, -0.00005f, 0.0005f, 0.00005f, 300.0f, -300.0f, 360.0f, 720.0f, -360.0f})
    around(v, c, 4096);
  for (float ten = 1e-6f; ten < 1e38f; ten *= 10.0f) {
    around(v, ten, 256);
    around(v, -ten, 256);
  }
  for (const double d : {1e3, 1e4}) {
    for (const double edge : {0x1p51, 4.0e18, 0x1p32 * d, 1e4 * d, 1e8 * d}) {
      around(v, static_cast<float>(edge / d), 1024);
      around(v, static_cast<float>(-edge / d), 1024);
    }
  }
  // The exact ties and their neighbours.
  for (int n = -32767; n <= 32767; n += 2) {
    for (const float t : {static_cast<float>(n) / 16.0f, static_cast<float>(n) / 32.0f}) {
      v.push_back(t);
      v.push_back(std::nextafter(t, 2000.0f));
      v.push_back(std::nextafter(t, -2000.0f));
    }
  }
  // The floats nearest the boundaries (k + 0.5) / 10^d and their neighbours: every 29th k from
  // -10^5 to 10^6 (-10..100 m at 4 decimals, -100..1000 deg at 3), every 1013th on to 10^7.
  for (const double d : {1e3, 1e4}) {
    for (std::int64_t k = -100000; k < 10000000; k += k < 1000000 ? 29 : 1013) {
      const float f = static_cast<float>((static_cast<double>(k) + 0.5) / d);
      v.push_back(f);
      v.push_back(std::nextafter(f, 1e30f));
      v.push_back(std::nextafter(f, -1e30f));
    }
  }
  // Random bit patterns, and the special values by name.
  std::uint32_t x = 2463534242u;  // xorshift32
  for (int i = 0; i < 120000; ++i) {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    v.push_back(from_bits(x));
  }
  using L = std::numeric_limits<float>;
  for (const float s : {L::infinity(), L::quiet_NaN(), L::signaling_NaN(), L::denorm_min(), L::min(), L::max(),
                        from_bits(0x007FFFFFu), from_bits(0x7FC12345u), from_bits(0x7F800001u), 0x1p24f, 0x1p31f,
                        0x1p32f, 0x1p63f, 0x1p64f}) {
    v.push_back(s);
    v.push_back(-s);
  }
  return v;
}

TEST(CsvNumbers, FixedPointFieldsEqualPrintf) {
  const std::vector<float> values = test_values();
  ASSERT_GT(values.size(), 1200000u);
  // Each value at 3 decimals (azimuth, elevation) and 4 (distance, x, y, z), beside another value;
  // the row against one assembled from printf's fields (no strings, one compare: this runs
  // 650 000 times, under ASan too).
  std::size_t checked = 0;
  char row[port::kCsvMaxRow];
  char ref[4][64];
  char expected[port::kCsvMaxRow];
  for (std::size_t i = 0; i + 1 < values.size(); i += 2) {
    const float a = values[i], b = values[i + 1];
    Point p;
    p.azimuth_deg = a;
    p.elevation_deg = b;
    p.distance_m = a;
    p.x = b;
    p.y = b;
    p.z = a;
    const std::size_t n = port::format_csv_row(row, p, 0, 0);
    const char* a3 = reference_fixed(ref[0], a, 3);
    const char* b3 = reference_fixed(ref[1], b, 3);
    const char* a4 = reference_fixed(ref[2], a, 4);
    const char* b4 = reference_fixed(ref[3], b, 4);
    char* e = expected;
    for (const char* field : {"0,0,0,0,0", a3, b3, a4, b4, b4, a4, "0,0"}) {
      const std::size_t k = std::strlen(field);
      std::memcpy(e, field, k);
      e += k;
      *e++ = ',';
    }
    const auto expected_bytes = static_cast<std::size_t>(e - 1 - expected);
    if (n != expected_bytes || std::memcmp(row, expected, n) != 0) {
      FAIL() << "float bits " << std::hex << bits_of(a) << " " << bits_of(b) << ":\n  " << std::string(row, n)
             << "\nexpected\n  " << std::string(expected, expected_bytes);
    }
    ++checked;
  }
  EXPECT_GT(checked, 600000u);
}

TEST(CsvNumbers, IntegerFieldsEqualPrintf) {
  std::vector<std::uint64_t> wide = {0, 1, 9, 10, 99, 100, 0xFFFFFFFFu, 0x100000000u, std::numeric_limits<std::uint64_t>::max()};
  for (std::uint64_t ten = 1; ten <= std::numeric_limits<std::uint64_t>::max() / 10; ten *= 10) {
    for (const std::uint64_t v : {ten - 1, ten, ten + 1, 10 * ten - 1}) wide.push_back(v);
  }
  std::uint64_t x = 88172645463325252u;  // xorshift64: every length
  for (int i = 0; i < 20000; ++i) {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    wide.push_back(x >> (i % 64));
  }
  for (std::size_t i = 0; i < wide.size(); ++i) {
    Point p;
    p.block = static_cast<std::uint8_t>(i);  // every byte value in every uint8 column
    p.channel = static_cast<std::uint8_t>(i * 7 + 3);
    p.return_index = static_cast<std::uint8_t>(i * 13 + 5);
    p.intensity = static_cast<std::uint8_t>(i * 31 + 11);
    p.time_ns = static_cast<std::int64_t>(wide[wide.size() - 1 - i]);  // negative ones too
    const auto frame = static_cast<std::uint32_t>(wide[i] >> (i % 33));
    ASSERT_EQ(row_of(p, frame, wide[i]), reference_row(p, frame, wide[i])) << i;
  }
}

// CsvWriter builds its rows in its block buffer (frame and packet formatted once a call, the
// sensor appended): the file against reference rows, over several blocks, with sensor fields
// of 0, 18 and kMaxSensorBytes bytes and runs of 1 to 400 rows.
TEST(CsvNumbers, WriterRowsEqualPrintf) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  port::CsvWriter w;
  ASSERT_TRUE(w.open(f, "tmpfile").ok());
  std::string expected = std::string(port::CsvWriter::kHeader) + "\n";
  const std::string sensors[] = {"", "192.168.1.201:2368", std::string(port::CsvWriter::kMaxSensorBytes, 's')};
  std::uint32_t x = 12345u;
  auto next = [&x] {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    return x;
  };
  std::vector<Point> run;
  std::uint64_t rows = 0;
  for (std::uint32_t call = 0; expected.size() < 3 * (1u << 20); ++call) {
    run.resize(1 + next() % 400);
    for (Point& p : run) {
      p.block = static_cast<std::uint8_t>(next());
      p.channel = static_cast<std::uint8_t>(next());
      p.return_index = static_cast<std::uint8_t>(next() % 3);
      p.intensity = static_cast<std::uint8_t>(next());
      p.azimuth_deg = static_cast<float>(next() % 3600000) / 10000.0f;
      p.elevation_deg = static_cast<float>(next() % 400000) / 10000.0f - 25.0f;
      p.distance_m = static_cast<float>(next() % 3000000) / 10000.0f;
      p.x = from_bits(next() % 64 == 0 ? next() : bits_of(static_cast<float>(next() % 6000000) / 10000.0f - 300.0f));
      p.y = static_cast<float>(next() % 6000000) / 10000.0f - 300.0f;
      p.z = static_cast<float>(next() % 600000) / 10000.0f - 30.0f;
      p.time_ns = 1700000000000000000 + static_cast<std::int64_t>(next()) * 1000;
    }
    const std::uint64_t packet = call % 5 == 0 ? std::numeric_limits<std::uint64_t>::max() - call : call;
    const std::string& sensor = sensors[call % 3];
    ASSERT_TRUE(w.write(run.data(), run.size(), call / 7, packet, sensor).ok());
    for (const Point& p : run) expected += reference_row(p, call / 7, packet) + "," + sensor + "\n";
    rows += run.size();
  }
  EXPECT_EQ(w.rows(), rows);
  ASSERT_TRUE(w.close().ok());
  std::rewind(f);
  std::string text(expected.size() + 1, '\0');
  text.resize(std::fread(&text[0], 1, text.size(), f));
  std::fclose(f);
  ASSERT_EQ(text.size(), expected.size());
  for (std::size_t at = 0; at < text.size(); at += 4096) {  // a diff of one page, not of 3 MB
    ASSERT_EQ(text.substr(at, 4096), expected.substr(at, 4096)) << "at byte " << at;
  }
}

}  // namespace
