// Calibration CSV parsers: the shipped files with values typed from them by hand, every error
// code with its line, tolerated variants, every truncation, random damage, and the decimal parser
// against the C library's strtod.
#include "hesai/calibration.h"

#include <gtest/gtest.h>

#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <ostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using hesai::AngleCorrection;
using hesai::ChannelConfig;
using hesai::Error;
using hesai::FiretimeCorrection;
using hesai::ParseResult;

std::string read_calibration(const std::string& name) {
  const std::string path = std::string(HESAI_DATA_DIR) + "/calibration/" + name;
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.good()) << "cannot open " << path;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

hesai::ByteView view(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

ParseResult angles(const std::string& text, std::size_t channels, AngleCorrection& out) {
  return hesai::parse_angle_csv(view(text), channels, out);
}
ParseResult firetimes(const std::string& text, std::size_t channels, FiretimeCorrection& out) {
  return hesai::parse_firetime_csv(view(text), channels, out);
}
ParseResult channel_config(const std::string& text, ChannelConfig& out) {
  return hesai::parse_channel_config_csv(view(text), out);
}

bool decimal(const std::string& s, double& out) { return hesai::parse_decimal(s.data(), s.data() + s.size(), out); }

// Lines are 1-based; the text of line `line` without its line end.
std::size_t line_start(const std::string& text, int line) {
  std::size_t pos = 0;
  for (int l = 1; l < line; ++l) pos = text.find('\n', pos) + 1;
  return pos;
}

// Replaces the whole text of a line.
std::string replace_line(const std::string& text, int line, const std::string& with) {
  const std::size_t b = line_start(text, line);
  std::size_t e = text.find('\n', b);
  if (e == std::string::npos) e = text.size();
  if (e > b && text[e - 1] == '\r') --e;
  return text.substr(0, b) + with + text.substr(e);
}

std::string delete_line(const std::string& text, int line) {
  const std::size_t b = line_start(text, line);
  const std::size_t e = text.find('\n', b);
  return text.substr(0, b) + (e == std::string::npos ? std::string() : text.substr(e + 1));
}

// ---------------------------------------------------------------------------------------------
// parse_decimal

TEST(ParseDecimal, HandTypedValues) {
  struct Case {
    const char* text;
    double value;
  };
  // The expected doubles are the compiler's own reading of the same literals (round to nearest).
  const Case cases[] = {
      {"14.794", 14.794},
      {"-1.042", -1.042},
      {"+3.125", 3.125},
      {"-52.62676282", -52.62676282},
      {"9.719503673", 9.719503673},
      {"100.52", 100.52},
      {"0", 0.0},
      {"007", 7.0},
      {"5.", 5.0},
      {".5", 0.5},
      {"-.25", -0.25},
      {"1e3", 1000.0},
      {"1E-3", 0.001},
      {"2.5e+2", 250.0},
      {"0.000001", 1e-6},
      {"123456789012345678901234567890", 123456789012345678901234567890.0},
      {"0.1000000000000000055511151231257827", 0.1},
      {"9007199254740993", 9007199254740992.0},  // 2^53 + 1: a tie, rounds to even
      {"1.7976931348623157e308", DBL_MAX},
      {"2.2250738585072014e-308", DBL_MIN},
      {"4.9406564584124654e-324", std::numeric_limits<double>::denorm_min()},
      {"1e-400", 0.0},
  };
  for (const Case& c : cases) {
    double v = -99.0;
    EXPECT_TRUE(decimal(c.text, v)) << c.text;
    EXPECT_EQ(v, c.value) << c.text;
  }
  double v = 0.0;
  ASSERT_TRUE(decimal("-0", v));
  EXPECT_TRUE(std::signbit(v));
  ASSERT_TRUE(decimal("-1e-999", v));
  EXPECT_EQ(v, 0.0);
  EXPECT_TRUE(std::signbit(v));
}

TEST(ParseDecimal, RejectsWhatIsNotADecimalNumber) {
  const char* bad[] = {"",   "+",   "-",    ".",     "+.",  "e5",  ".e5",   "1e",         "1e+",
                       "1e-", "1.2.3", "1a",  "a1",   " 1",  "1 ",   "1,5",  "0x10",       "inf",
                       "nan", "--1", "+-1", "1e5.5", "1.5e", "1..", "1e1e1", "\xCE\xBC", "1\r"};
  for (const char* s : bad) {
    double v = 42.0;
    EXPECT_FALSE(decimal(s, v)) << '"' << s << '"';
    EXPECT_EQ(v, 42.0) << "a rejected number must not write the output";
  }
  double v = 0.0;
  EXPECT_FALSE(hesai::parse_decimal(nullptr, nullptr, v));
}

TEST(ParseDecimal, RejectsOverflow) {
  double v = 0.0;
  EXPECT_FALSE(decimal("1.8e308", v));
  EXPECT_FALSE(decimal("-1e309", v));
  EXPECT_FALSE(decimal("1.7976931348623159e308", v));  // above DBL_MAX + ulp/2: rounds to infinity
  EXPECT_FALSE(decimal("1e99999999999999999999", v));
  EXPECT_TRUE(decimal("1797693134862315708145274237317043567980705675258e260", v));   // DBL_MAX
  EXPECT_EQ(v, DBL_MAX);
  EXPECT_TRUE(decimal("0.00001e308", v));
  EXPECT_EQ(v, 1e303);
  EXPECT_TRUE(decimal("100000e-99999999999999", v));
  EXPECT_EQ(v, 0.0);
}

// Signed distance in units in the last place, through the ordered bit patterns.
std::int64_t ulp_distance(double a, double b) {
  auto ordered = [](double d) {
    std::int64_t i = 0;
    std::memcpy(&i, &d, sizeof i);
    return i < 0 ? std::numeric_limits<std::int64_t>::min() - i : i;
  };
  const std::int64_t d = ordered(a) - ordered(b);
  return d < 0 ? -d : d;
}

// Strings the way calibration files write them: up to 10 fraction digits, magnitudes below 1000.
TEST(ParseDecimal, NearestDoubleOnCalibrationStyleStrings) {
  std::mt19937_64 rng(20240229);
  std::uniform_real_distribution<double> value(-1000.0, 1000.0);
  std::uniform_int_distribution<int> places(0, 10);
  char buf[64];
  int mismatches = 0;
  for (int i = 0; i < 200000; ++i) {
    std::snprintf(buf, sizeof buf, "%.*f", places(rng), value(rng));
    const double want = std::strtod(buf, nullptr);
    double got = 0.0;
    ASSERT_TRUE(decimal(buf, got)) << buf;
    if (got != want && ++mismatches < 10) ADD_FAILURE() << buf << ": " << got << " != " << want;
  }
  EXPECT_EQ(mismatches, 0);
}

// Random digit strings over the whole range of double, with long mantissas and large exponents.
// Up to 19 significant digits and a normal result: the nearest double, as strtod gives. Longer
// mantissas (digits after the 19th are dropped) and subnormal results (rounded twice): within 1 ulp.
TEST(ParseDecimal, AgreesWithStrtodOverTheWholeRange) {
  std::mt19937_64 rng(1262);
  std::uniform_int_distribution<int> ndigits(1, 28);
  std::uniform_int_distribution<int> digit(0, 9);
  std::uniform_int_distribution<int> exponent(-360, 330);
  std::uniform_int_distribution<int> coin(0, 1);
  int short_normal = 0;
  int other = 0;
  int other_nearest = 0;
  int failures = 0;
  for (int i = 0; i < 300000; ++i) {
    std::string s;
    if (coin(rng)) s += '-';
    const int n = ndigits(rng);
    std::uniform_int_distribution<int> point(0, n);
    const int at = point(rng);
    int significant = 0;
    for (int k = 0; k < n; ++k) {
      if (k == at) s += '.';
      const int d = digit(rng);
      if (d != 0 || significant != 0) ++significant;
      s += static_cast<char>('0' + d);
    }
    if (at == n && coin(rng)) s += '.';
    s += 'e' + std::to_string(exponent(rng));
    const double want = std::strtod(s.c_str(), nullptr);
    double got = 0.0;
    const bool ok = decimal(s, got);
    if (std::isinf(want)) {
      EXPECT_FALSE(ok) << s << " overflows";
      continue;
    }
    ASSERT_TRUE(ok) << s;
    const std::int64_t d = ulp_distance(got, want);
    if (significant <= 19 && std::fabs(want) >= DBL_MIN) {
      ++short_normal;
      if (d != 0 && ++failures < 10) ADD_FAILURE() << s << ": " << got << " vs strtod " << want << ", " << d << " ulp";
    } else {
      ++other;
      other_nearest += d == 0 ? 1 : 0;
      if (d > 1 && ++failures < 10) ADD_FAILURE() << s << ": " << got << " vs strtod " << want << ", " << d << " ulp";
    }
  }
  EXPECT_EQ(failures, 0);
  EXPECT_GT(short_normal, 100000);
  EXPECT_GT(other, 50000);
  EXPECT_GE(other_nearest, other - other / 100) << other_nearest << " of " << other << " nearest";
}

// Every number in every shipped file reads as strtod reads it.
TEST(ParseDecimal, EveryNumberOfTheShippedFilesIsTheNearestDouble) {
  const char* files[] = {"pandar40p_unit_a_angles.csv", "pandar40p_unit_b_angles.csv", "pandar64_unit_a_angles.csv",
                         "pandar64_unit_b_angles.csv",  "qt128c2x_unit_a_angles.csv",  "pandar40p_firetimes.csv",
                         "pandar64_firetimes.csv",      "qt128c2x_firetimes.csv",      "qt128c2x_channel_config.csv"};
  int numbers = 0;
  for (const char* f : files) {
    std::string text = read_calibration(f);
    for (char& c : text) {
      if (c == '\r' || c == '\n') c = ',';
    }
    std::stringstream ss(text);
    std::string field;
    while (std::getline(ss, field, ',')) {
      if (field.empty() || !(std::isdigit(static_cast<unsigned char>(field.back())))) continue;
      char* end = nullptr;
      const double want = std::strtod(field.c_str(), &end);
      if (*end != '\0') continue;
      double got = 0.0;
      ASSERT_TRUE(decimal(field, got)) << f << ": " << field;
      EXPECT_EQ(got, want) << f << ": " << field;
      ++numbers;
    }
  }
  EXPECT_GT(numbers, 1500);
}

// ---------------------------------------------------------------------------------------------
// Angle correction files

struct AngleSpot {
  int line;  // line in the file, for the reader and for the damage test
  int channel;
  double elevation;
  double azimuth;
};

struct AngleFile {
  const char* name;
  std::size_t channels;
  int last_line;  // line of the last channel row
  std::vector<AngleSpot> spots;
};

// Typed from the files (line: row).
const AngleFile kAngleFiles[] = {
    {"pandar40p_unit_a_angles.csv", 40, 41,  // LF, header "Laser id,Elevation,Azimuth", ends with LF
     {{2, 1, 14.794, -1.042},
      {8, 7, 1.6, 3.125},
      {9, 8, 1.263, -5.208},
      {21, 20, -2.788, -5.208},
      {34, 33, -9.148, -1.042},
      {41, 40, -24.985, -1.042}}},
    {"pandar40p_unit_b_angles.csv", 40, 41,  // CRLF, header "Channel,Elevation,Azimuth", no final line end
     {{2, 1, 15.21, -1.042},
      {8, 7, 2.016, 3.125},
      {21, 20, -2.372, -5.208},
      {22, 21, -2.712, -1.042},
      {41, 40, -24.569, -1.042}}},
    {"pandar64_unit_a_angles.csv", 64, 65,
     {{2, 1, 14.9, -1.042},
      {8, 7, 1.878, 1.042},
      {22, 21, -0.49, 5.208},
      {33, 32, -2.347, 3.125},
      {65, 64, -24.879, -1.042}}},
    {"pandar64_unit_b_angles.csv", 64, 65,
     {{2, 1, 14.708, -1.042},
      {9, 8, 1.514, 3.125},
      {21, 20, -0.511, 3.125},
      {34, 33, -2.71, 5.208},
      {65, 64, -25.071, -1.042}}},
    {"qt128c2x_unit_a_angles.csv", 128, 129,  // manual Figure 1.7 without the EEFF row
     {{2, 1, -52.62676282, 10.10830596},
      {3, 2, -51.0280939, 9.719503673},
      {33, 32, -19.19081372, 6.25017485},
      {34, 33, -18.33139172, -6.21699538},
      {66, 65, 7.909760474, 5.949064148},
      {100, 99, 20.92594329, -6.32298504},
      {129, 128, 52.62676282, -10.10830596}}},
};

void PrintTo(const AngleFile& f, std::ostream* os) { *os << f.name; }

class AngleFileTest : public testing::TestWithParam<AngleFile> {};

TEST_P(AngleFileTest, ParsesWithTheValuesOfTheFile) {
  const AngleFile& f = GetParam();
  const std::string text = read_calibration(f.name);
  AngleCorrection out;
  const ParseResult r = angles(text, f.channels, out);
  ASSERT_EQ(r.error, Error::ok) << hesai::error_name(r.error) << " at line " << r.line;
  EXPECT_EQ(r.line, 0u);
  EXPECT_EQ(out.channels, f.channels);
  for (const AngleSpot& s : f.spots) {
    EXPECT_EQ(out.elevation_deg[static_cast<std::size_t>(s.channel - 1)], s.elevation) << "line " << s.line;
    EXPECT_EQ(out.azimuth_deg[static_cast<std::size_t>(s.channel - 1)], s.azimuth) << "line " << s.line;
  }
}

TEST_P(AngleFileTest, WrongChannelCountIsRefused) {
  const AngleFile& f = GetParam();
  const std::string text = read_calibration(f.name);
  AngleCorrection out;
  // One channel fewer: the last row is one too many.
  ParseResult r = angles(text, f.channels - 1, out);
  EXPECT_EQ(r.error, Error::calib_channel_count);
  EXPECT_EQ(r.line, static_cast<std::uint32_t>(f.last_line));
  EXPECT_EQ(out.channels, 0u);
  // One channel more: a row is missing after the last one.
  if (f.channels < hesai::kMaxChannels) {
    r = angles(text, f.channels + 1, out);
    EXPECT_EQ(r.error, Error::calib_channel_count);
    EXPECT_EQ(r.line, static_cast<std::uint32_t>(f.last_line + 1));
  }
}

// A damaged number is reported at its own line.
TEST_P(AngleFileTest, DamageIsReportedAtItsLine) {
  const AngleFile& f = GetParam();
  const std::string text = read_calibration(f.name);
  for (const AngleSpot& s : f.spots) {
    std::string bad = text;
    const std::size_t comma = bad.find(',', line_start(bad, s.line));
    bad[comma + 2] = 'x';
    AngleCorrection out;
    const ParseResult r = angles(bad, f.channels, out);
    EXPECT_EQ(r.error, Error::calib_bad_number) << "line " << s.line;
    EXPECT_EQ(r.line, static_cast<std::uint32_t>(s.line));
  }
}

// The rows in reverse order give the same table.
TEST_P(AngleFileTest, RowOrderDoesNotMatter) {
  const AngleFile& f = GetParam();
  const std::string text = read_calibration(f.name);
  std::vector<std::string> lines;
  std::stringstream ss(text);
  for (std::string l; std::getline(ss, l);) {
    if (!l.empty() && l.back() == '\r') l.pop_back();
    lines.push_back(l);
  }
  std::string reversed = lines[0] + "\n";
  for (std::size_t i = lines.size(); i-- > 1;) reversed += lines[i] + "\n";
  AngleCorrection a;
  AngleCorrection b;
  ASSERT_EQ(angles(text, f.channels, a).error, Error::ok);
  ASSERT_EQ(angles(reversed, f.channels, b).error, Error::ok);
  EXPECT_EQ(a.elevation_deg, b.elevation_deg);
  EXPECT_EQ(a.azimuth_deg, b.azimuth_deg);
}

INSTANTIATE_TEST_SUITE_P(ShippedFiles, AngleFileTest, testing::ValuesIn(kAngleFiles),
                         [](const testing::TestParamInfo<AngleFile>& param_info) {
                           std::string n = param_info.param.name;
                           return n.substr(0, n.find('.'));
                         });

// A 40-channel file made here: "n,<n>.5,-1.042" on line n + 1.
std::string make_angle_file(int rows) {
  std::string s = "Laser id,Elevation,Azimuth\n";
  for (int n = 1; n <= rows; ++n) s += std::to_string(n) + "," + std::to_string(n) + ".5,-1.042\n";
  return s;
}

struct ErrorCase {
  const char* what;
  std::string text;
  Error error;
  std::uint32_t line;
};

TEST(AngleCsv, EveryErrorAtItsLine) {
  const std::string good = make_angle_file(40);
  const ErrorCase cases[] = {
      {"a letter in a number", replace_line(good, 7, "6,6.5x,-1.042"), Error::calib_bad_number, 7},
      {"a letter in a channel", replace_line(good, 7, "6a,6.5,-1.042"), Error::calib_bad_number, 7},
      {"a fractional channel", replace_line(good, 7, "6.0,6.5,-1.042"), Error::calib_bad_number, 7},
      {"an empty number", replace_line(good, 9, "8,,-1.042"), Error::calib_bad_number, 9},
      {"a missing channel", delete_line(good, 10), Error::calib_channel_count, 41},
      {"a duplicate channel", replace_line(good, 12, "3,11.5,-1.042"), Error::calib_bad_channel, 12},
      {"channel 0", replace_line(good, 2, "0,1.5,-1.042"), Error::calib_bad_channel, 2},
      {"channel 41 of 40", replace_line(good, 41, "41,40.5,-1.042"), Error::calib_bad_channel, 41},
      {"a negative channel", replace_line(good, 5, "-4,4.5,-1.042"), Error::calib_bad_channel, 5},
      {"a huge channel", replace_line(good, 5, "99999999999999999999,4.5,-1.042"), Error::calib_bad_channel, 5},
      {"a row of 2 fields", replace_line(good, 5, "4,4.5"), Error::calib_bad_row, 5},
      {"a row of 4 fields", replace_line(good, 6, "5,5.5,-1.042,7"), Error::calib_bad_row, 6},
      {"an unknown header", replace_line(good, 1, "Beam,Elevation,Azimuth"), Error::calib_bad_header, 1},
      {"a header of 2 fields", replace_line(good, 1, "Laser id,Elevation"), Error::calib_bad_header, 1},
      {"no header", delete_line(good, 1), Error::calib_bad_header, 1},
      {"41 rows for 40 channels", make_angle_file(41), Error::calib_channel_count, 42},
      {"header only", make_angle_file(0), Error::calib_channel_count, 2},
      {"an empty file", "", Error::calib_bad_header, 1},
      {"blank lines only", "\r\n\n  \n", Error::calib_bad_header, 4},
      {"a short EEFF row", "EEFF,1\n" + good, Error::calib_bad_header, 1},
      {"a bad EEFF version", "EEFF,1,x\n" + good, Error::calib_bad_number, 1},
      {"EEFF and nothing else", "EEFF,1,1\n", Error::calib_bad_header, 2},
  };
  for (const ErrorCase& c : cases) {
    AngleCorrection out;
    const ParseResult r = angles(c.text, 40, out);
    EXPECT_EQ(r.error, c.error) << c.what << ": " << hesai::error_name(r.error);
    EXPECT_EQ(r.line, c.line) << c.what;
    EXPECT_EQ(out.channels, 0u) << c.what;
  }
}

TEST(AngleCsv, ExpectedChannelsOutsideTheModelRange) {
  const std::string good = make_angle_file(40);
  AngleCorrection out;
  EXPECT_EQ(angles(good, 0, out).error, Error::invalid_argument);
  EXPECT_EQ(angles(good, 129, out).error, Error::invalid_argument);
  EXPECT_EQ(angles(good, 129, out).line, 0u);
  EXPECT_EQ(angles(good, 40, out).error, Error::ok);
  EXPECT_EQ(out.elevation_deg[39], 40.5);
}

// BOM, CRLF, a header in other spelling, spaces, trailing commas and blank lines.
TEST(AngleCsv, ToleratedVariantsGiveTheSameTable) {
  const std::string text = read_calibration("pandar40p_unit_a_angles.csv");
  AngleCorrection want;
  ASSERT_EQ(angles(text, 40, want).error, Error::ok);

  std::string variant = "\xEF\xBB\xBF  LASER_ID ,\televation , AZIMUTH,,\r\n";
  std::stringstream ss(text);
  std::string l;
  std::getline(ss, l);  // the header
  int n = 0;
  while (std::getline(ss, l)) {
    const std::size_t c = l.find(',');
    ++n;
    variant += (n % 2 ? " " : "") + l.substr(0, c) + " , " + l.substr(c + 1) + (n % 3 ? ",\r\n" : "\r\n\r\n");
  }
  variant += ",,,\r\n\r\n";
  AngleCorrection got;
  const ParseResult r = angles(variant, 40, got);
  ASSERT_EQ(r.error, Error::ok) << hesai::error_name(r.error) << " at line " << r.line;
  EXPECT_EQ(got.elevation_deg, want.elevation_deg);
  EXPECT_EQ(got.azimuth_deg, want.azimuth_deg);

  // The QT128 layout of manual Figure 1.7: an EEFF row, then LaserID.
  const std::string qt = read_calibration("qt128c2x_unit_a_angles.csv");
  AngleCorrection qt_want;
  ASSERT_EQ(angles(qt, 128, qt_want).error, Error::ok);
  const std::string qt_eeff = "EEFF,1,1\nLaserID,Elevation,Azimuth\n" + qt.substr(qt.find('\n') + 1);
  AngleCorrection qt_got;
  ASSERT_EQ(angles(qt_eeff, 128, qt_got).error, Error::ok);
  EXPECT_EQ(qt_got.elevation_deg, qt_want.elevation_deg);
  EXPECT_EQ(qt_got.azimuth_deg, qt_want.azimuth_deg);
  // A number error in that file counts the EEFF line.
  const ParseResult r2 = angles(replace_line(qt_eeff, 9, "7,-44.08974439,8.3959z"), 128, qt_got);
  EXPECT_EQ(r2.error, Error::calib_bad_number);
  EXPECT_EQ(r2.line, 9u);
}

// ---------------------------------------------------------------------------------------------
// Firetime files

struct FiretimeSpot {
  int line;
  int channel;
  double time_us;
};

TEST(FiretimeCsv, Pandar40P) {
  // Header "Channel,fire time(μs)" (UTF-8 mu), CRLF, rows not in channel order.
  const std::string text = read_calibration("pandar40p_firetimes.csv");
  FiretimeCorrection out;
  const ParseResult r = firetimes(text, 40, out);
  ASSERT_EQ(r.error, Error::ok) << hesai::error_name(r.error) << " at line " << r.line;
  EXPECT_EQ(out.channels, 40u);
  EXPECT_EQ(out.loops, 1u);
  const FiretimeSpot spots[] = {{2, 4, -3.62},    {3, 40, -3.62},   {10, 29, -12.77},
                                {11, 17, -14.74}, {21, 14, -27.16}, {41, 8, -54.67}};
  for (const FiretimeSpot& s : spots) {
    EXPECT_EQ(out.firetime_us[0][static_cast<std::size_t>(s.channel - 1)], s.time_us) << "line " << s.line;
  }
  for (std::size_t i = 0; i < 40; ++i) EXPECT_TRUE(out.fires[0][i]) << i;
  for (std::size_t i = 40; i < hesai::kMaxChannels; ++i) EXPECT_FALSE(out.fires[0][i]) << i;
  for (std::size_t i = 0; i < hesai::kMaxChannels; ++i) EXPECT_FALSE(out.fires[1][i]) << i;
}

TEST(FiretimeCsv, Pandar64) {
  // Header "Channel,fire time(us)", CRLF.
  const std::string text = read_calibration("pandar64_firetimes.csv");
  FiretimeCorrection out;
  const ParseResult r = firetimes(text, 64, out);
  ASSERT_EQ(r.error, Error::ok) << hesai::error_name(r.error) << " at line " << r.line;
  EXPECT_EQ(out.channels, 64u);
  EXPECT_EQ(out.loops, 1u);
  const FiretimeSpot spots[] = {{2, 51, -3.62},     {12, 43, -10.14},  {20, 41, -15.356},
                                {41, 30, -31.052},  {64, 12, -54.668}, {65, 40, -54.668}};
  for (const FiretimeSpot& s : spots) {
    EXPECT_EQ(out.firetime_us[0][static_cast<std::size_t>(s.channel - 1)], s.time_us) << "line " << s.line;
  }
  for (std::size_t i = 0; i < 64; ++i) EXPECT_TRUE(out.fires[0][i]) << i;
}

TEST(FiretimeCsv, QT128) {
  // Manual App. II: 3 header rows, 96 channel rows, 32 all-zero rows.
  const std::string text = read_calibration("qt128c2x_firetimes.csv");
  FiretimeCorrection out;
  const ParseResult r = firetimes(text, 128, out);
  ASSERT_EQ(r.error, Error::ok) << hesai::error_name(r.error) << " at line " << r.line;
  EXPECT_EQ(out.channels, 128u);
  EXPECT_EQ(out.loops, 2u);
  struct Spot {
    int line;
    int ch1;
    double t1;
    int ch2;
    double t2;
  };
  const Spot spots[] = {{4, 99, 0.6, 65, 0.6},           {5, 65, 1.456, 99, 1.456},
                        {6, 35, 2.312, 1, 2.312},        {51, 64, 49.832, 30, 49.832},
                        {53, 68, 52.144, 98, 52.144},    {99, 61, 100.52, 31, 100.52}};
  for (const Spot& s : spots) {
    EXPECT_TRUE(out.fires[0][static_cast<std::size_t>(s.ch1 - 1)]) << "line " << s.line;
    EXPECT_EQ(out.firetime_us[0][static_cast<std::size_t>(s.ch1 - 1)], s.t1) << "line " << s.line;
    EXPECT_TRUE(out.fires[1][static_cast<std::size_t>(s.ch2 - 1)]) << "line " << s.line;
    EXPECT_EQ(out.firetime_us[1][static_cast<std::size_t>(s.ch2 - 1)], s.t2) << "line " << s.line;
  }
  // Manual App. II: firing sequence 1 = banks C, D, B (bank A, channels 1..32, rests);
  // sequence 2 = banks C, D, A (bank B, channels 33..64, rests). 96 channels fire in each.
  int fire1 = 0;
  int fire2 = 0;
  for (std::size_t i = 0; i < 128; ++i) {
    const int ch = static_cast<int>(i) + 1;
    EXPECT_EQ(out.fires[0][i], ch > 32) << ch;
    EXPECT_EQ(out.fires[1][i], ch <= 32 || ch > 64) << ch;
    if (!out.fires[0][i]) {
      EXPECT_EQ(out.firetime_us[0][i], 0.0) << ch;
    }
    fire1 += out.fires[0][i] ? 1 : 0;
    fire2 += out.fires[1][i] ? 1 : 0;
  }
  EXPECT_EQ(fire1, 96);
  EXPECT_EQ(fire2, 96);
}

TEST(FiretimeCsv, HeaderSpellings) {
  const std::string bom = "\xEF\xBB\xBF";
  const std::string headers[] = {"Channel,fire time(us)", "channel , Fire Time (\xC2\xB5s)", "Laser ID,fire time",
                                 bom + "Channel,fire time(\xCE\xBCs),"};
  for (const std::string& h : headers) {
    const std::string text = h + "\n2,-1.5\n1,-2.5\n";
    FiretimeCorrection out;
    const ParseResult r = firetimes(text, 2, out);
    EXPECT_EQ(r.error, Error::ok) << h;
    EXPECT_EQ(out.firetime_us[0][0], -2.5) << h;
    EXPECT_EQ(out.firetime_us[0][1], -1.5) << h;
  }
}

std::string make_pandar_firetime_file(int rows) {
  std::string s = "Channel,fire time(us)\r\n";
  for (int n = rows; n >= 1; --n) s += std::to_string(n) + ",-" + std::to_string(n) + ".25\r\n";
  return s;
}

// A QT128 file made here: loop 1 lists channels 33..128, loop 2 lists 1..32 and 65..128.
std::string make_qt_firetime_file() {
  std::string s = "EEFF,1,1,\r\nHorizontal Resolution Mode,1,LoopNum,2\r\nLoop1,Firetime1,Loop2,Firetime2\r\n";
  for (int i = 0; i < 96; ++i) {
    const int c1 = 33 + i;
    const int c2 = i < 32 ? 1 + i : 33 + i;
    s += std::to_string(c1) + "," + std::to_string(i) + ".5," + std::to_string(c2) + "," + std::to_string(i) + ".5\r\n";
  }
  for (int i = 0; i < 32; ++i) s += "0,0,0,0\r\n";
  return s;
}

TEST(FiretimeCsv, EveryErrorAtItsLine) {
  const std::string p = make_pandar_firetime_file(40);  // channel 40 on line 2 .. channel 1 on line 41
  const std::string q = make_qt_firetime_file();        // data on lines 4..99, padding 100..131
  struct Case {
    const char* what;
    std::string text;
    std::size_t channels;
    Error error;
    std::uint32_t line;
  };
  const Case cases[] = {
      {"a letter in a time", replace_line(p, 7, "35,-3x"), 40, Error::calib_bad_number, 7},
      {"a missing channel", delete_line(p, 10), 40, Error::calib_channel_count, 41},
      {"a duplicate channel", replace_line(p, 12, "40,-1"), 40, Error::calib_bad_channel, 12},
      {"a row of 3 fields", replace_line(p, 5, "37,-1,2"), 40, Error::calib_bad_row, 5},
      {"a row of 1 field", replace_line(p, 5, "37"), 40, Error::calib_bad_row, 5},
      {"an unknown header", replace_line(p, 1, "Channel,delay(us)"), 40, Error::calib_bad_header, 1},
      {"41 rows for 40 channels", p + "41,-1.5\r\n", 40, Error::calib_channel_count, 42},
      {"channel 41 first", make_pandar_firetime_file(41), 40, Error::calib_bad_channel, 2},
      {"channels beyond the model", make_pandar_firetime_file(41), 41, Error::ok, 0},
      {"expected 0", p, 0, Error::invalid_argument, 0},
      {"QT: made file", q, 128, Error::ok, 0},
      {"QT: LoopNum 3", replace_line(q, 2, "Horizontal Resolution Mode,1,LoopNum,3"), 128, Error::calib_bad_header, 2},
      {"QT: LoopNum x", replace_line(q, 2, "Horizontal Resolution Mode,1,LoopNum,x"), 128, Error::calib_bad_number, 2},
      {"QT: unknown mode row", replace_line(q, 2, "Mode,1,LoopNum,2"), 128, Error::calib_bad_header, 2},
      {"QT: wrong loop names", replace_line(q, 3, "Loop1,Firetime1,Loop3,Firetime2"), 128, Error::calib_bad_header, 3},
      {"QT: loop columns short", replace_line(q, 3, "Loop1,Firetime1"), 128, Error::calib_bad_header, 3},
      {"QT: a row of 3 fields", replace_line(q, 20, "49,16.5,17"), 128, Error::calib_bad_row, 20},
      {"QT: a letter in a time", replace_line(q, 20, "49,16.5,17,1o.5"), 128, Error::calib_bad_number, 20},
      {"QT: a duplicate in loop 1", replace_line(q, 21, "49,17.5,18,17.5"), 128, Error::calib_bad_channel, 21},
      {"QT: a duplicate in loop 2", replace_line(q, 21, "50,17.5,17,17.5"), 128, Error::calib_bad_channel, 21},
      {"QT: channel 129", replace_line(q, 21, "129,17.5,18,17.5"), 128, Error::calib_bad_channel, 21},
      {"QT: a channel firing in no loop", replace_line(q, 99, "0,0,0,0"), 128, Error::calib_channel_count, 132},
      {"QT: 129 rows", q + "0,0,0,0\r\n", 128, Error::calib_channel_count, 132},
      {"QT: header only", q.substr(0, line_start(q, 4)), 128, Error::calib_channel_count, 4},
      {"QT: no loop header", q.substr(0, line_start(q, 3)), 128, Error::calib_bad_header, 3},
  };
  for (const Case& c : cases) {
    FiretimeCorrection out;
    const ParseResult r = firetimes(c.text, c.channels, out);
    EXPECT_EQ(r.error, c.error) << c.what << ": " << hesai::error_name(r.error) << " at " << r.line;
    EXPECT_EQ(r.line, c.line) << c.what;
    EXPECT_EQ(out.channels, c.error == Error::ok ? c.channels : 0u) << c.what;
  }
}

// ---------------------------------------------------------------------------------------------
// Channel configuration file

TEST(ChannelConfigCsv, ShippedFile) {
  // "LaserNum,80": the file has exactly 80 channel rows (lines 4..83), so 80 is decimal.
  const std::string text = read_calibration("qt128c2x_channel_config.csv");
  ChannelConfig out;
  const ParseResult r = channel_config(text, out);
  ASSERT_EQ(r.error, Error::ok) << hesai::error_name(r.error) << " at line " << r.line;
  EXPECT_EQ(out.laser_num, 80u);
  EXPECT_EQ(out.block_num, 2u);
  EXPECT_EQ(out.loops, 2u);
  // line 4: 49,17   line 19: 64,32   line 20: 65,65   line 83: 128,128
  EXPECT_EQ(out.channel[0][0], 49u);
  EXPECT_EQ(out.channel[1][0], 17u);
  EXPECT_EQ(out.channel[0][15], 64u);
  EXPECT_EQ(out.channel[1][15], 32u);
  EXPECT_EQ(out.channel[0][16], 65u);
  EXPECT_EQ(out.channel[1][16], 65u);
  EXPECT_EQ(out.channel[0][79], 128u);
  EXPECT_EQ(out.channel[1][79], 128u);
  EXPECT_EQ(out.channel[0][80], 0u);
  // line 84: "3142432,,," (no line end)
  EXPECT_EQ(std::string(out.hash.data(), out.hash_length), "3142432");
}

TEST(ChannelConfigCsv, EveryErrorAtItsLine) {
  const std::string t = read_calibration("qt128c2x_channel_config.csv");
  const std::string rows_only = t.substr(0, line_start(t, 84));
  struct Case {
    const char* what;
    std::string text;
    Error error;
    std::uint32_t line;
  };
  const Case cases[] = {
      {"no hash line", rows_only, Error::ok, 0},
      {"no EEFF", delete_line(t, 1), Error::calib_bad_header, 1},
      {"LaserNum 0", replace_line(t, 2, "LaserNum,0,BlockNum,2"), Error::calib_bad_header, 2},
      {"LaserNum 129", replace_line(t, 2, "LaserNum,129,BlockNum,2"), Error::calib_bad_header, 2},
      {"LaserNum 0x50", replace_line(t, 2, "LaserNum,0x50,BlockNum,2"), Error::calib_bad_number, 2},
      {"BlockNum 0", replace_line(t, 2, "LaserNum,80,BlockNum,0"), Error::calib_bad_header, 2},
      {"unknown row 2", replace_line(t, 2, "Lasers,80,BlockNum,2"), Error::calib_bad_header, 2},
      {"loop 3", replace_line(t, 3, "Loop1,Loop3"), Error::calib_bad_header, 3},
      {"three loops", replace_line(t, 3, "Loop1,Loop2,Loop3"), Error::calib_bad_header, 3},
      {"LaserNum 81: the hash is a short row", replace_line(t, 2, "LaserNum,81,BlockNum,2"), Error::calib_bad_row, 84},
      {"LaserNum 81, no hash", replace_line(rows_only, 2, "LaserNum,81,BlockNum,2"), Error::calib_channel_count, 84},
      {"LaserNum 79", replace_line(t, 2, "LaserNum,79,BlockNum,2"), Error::calib_channel_count, 83},
      {"a row of 1 field", replace_line(t, 30, "75"), Error::calib_bad_row, 30},
      {"a row of 3 fields", replace_line(t, 30, "75,75,1"), Error::calib_bad_row, 30},
      {"a letter", replace_line(t, 30, "75,7S"), Error::calib_bad_number, 30},
      {"channel 0", replace_line(t, 30, "0,75"), Error::calib_bad_channel, 30},
      {"channel 129", replace_line(t, 30, "75,129"), Error::calib_bad_channel, 30},
      {"a duplicate", replace_line(t, 30, "74,75"), Error::calib_bad_channel, 30},
      {"a duplicate in Loop2", replace_line(t, 30, "75,74"), Error::calib_bad_channel, 30},
      {"a row after the hash", t + "\n1,1\n", Error::calib_channel_count, 85},
      {"two hash lines", t + "\n1\n", Error::calib_channel_count, 85},
      {"an extra channel row", rows_only + "1,1\n", Error::calib_channel_count, 84},
      {"a hash of 65 characters", rows_only + std::string(65, 'f'), Error::calib_bad_row, 84},
      {"a hash of 64 characters", rows_only + std::string(64, 'f'), Error::ok, 0},
      {"empty", "", Error::calib_bad_header, 1},
  };
  for (const Case& c : cases) {
    ChannelConfig out;
    const ParseResult r = channel_config(c.text, out);
    EXPECT_EQ(r.error, c.error) << c.what << ": " << hesai::error_name(r.error) << " at " << r.line;
    EXPECT_EQ(r.line, c.line) << c.what;
    EXPECT_EQ(out.laser_num, c.error == Error::ok ? 80u : 0u) << c.what;
  }
}

// ---------------------------------------------------------------------------------------------
// Truncations and random damage of every shipped file: an error or (only when every row is
// there, the last field possibly cut short) success; never a read outside the buffer (asan).

enum class Kind { angles, firetimes, channel_config };

struct ShippedFile {
  const char* name;
  Kind kind;
  std::size_t channels;
  int last_data_line;  // the last row that is neither padding nor the optional hash
};

const ShippedFile kShipped[] = {
    {"pandar40p_unit_a_angles.csv", Kind::angles, 40, 41},
    {"pandar40p_unit_b_angles.csv", Kind::angles, 40, 41},
    {"pandar64_unit_a_angles.csv", Kind::angles, 64, 65},
    {"pandar64_unit_b_angles.csv", Kind::angles, 64, 65},
    {"qt128c2x_unit_a_angles.csv", Kind::angles, 128, 129},
    {"pandar40p_firetimes.csv", Kind::firetimes, 40, 41},
    {"pandar64_firetimes.csv", Kind::firetimes, 64, 65},
    {"qt128c2x_firetimes.csv", Kind::firetimes, 128, 99},
    {"qt128c2x_channel_config.csv", Kind::channel_config, 128, 83},
};

void PrintTo(const ShippedFile& f, std::ostream* os) { *os << f.name; }

// The parsed values of a file as one list of numbers, to compare two parses.
struct Parsed {
  ParseResult result;
  std::vector<double> values;
};

Parsed parse_any(const ShippedFile& f, const std::uint8_t* data, std::size_t size) {
  Parsed p;
  const hesai::ByteView v(data, size);
  switch (f.kind) {
    case Kind::angles: {
      AngleCorrection out;
      p.result = hesai::parse_angle_csv(v, f.channels, out);
      p.values.assign(out.elevation_deg.begin(), out.elevation_deg.end());
      p.values.insert(p.values.end(), out.azimuth_deg.begin(), out.azimuth_deg.end());
      if (p.result.error == Error::ok) {
        EXPECT_EQ(out.channels, f.channels);
      }
      break;
    }
    case Kind::firetimes: {
      FiretimeCorrection out;
      p.result = hesai::parse_firetime_csv(v, f.channels, out);
      for (std::size_t k = 0; k < 2; ++k) {
        p.values.insert(p.values.end(), out.firetime_us[k].begin(), out.firetime_us[k].end());
        for (bool b : out.fires[k]) p.values.push_back(b ? 1.0 : 0.0);
      }
      if (p.result.error == Error::ok) {
        EXPECT_EQ(out.channels, f.channels);
      }
      break;
    }
    case Kind::channel_config: {
      ChannelConfig out;
      p.result = hesai::parse_channel_config_csv(v, out);
      for (std::size_t k = 0; k < 2; ++k) p.values.insert(p.values.end(), out.channel[k].begin(), out.channel[k].end());
      p.values.push_back(out.laser_num);
      break;
    }
  }
  return p;
}

std::uint32_t count_lines(const std::uint8_t* data, std::size_t size) {
  std::uint32_t n = 1;
  for (std::size_t i = 0; i < size; ++i) n += data[i] == '\n' ? 1 : 0;
  return n;
}

class ShippedFileTest : public testing::TestWithParam<ShippedFile> {};

TEST_P(ShippedFileTest, EveryTruncationIsAnErrorOrTheWholeTable) {
  const ShippedFile& f = GetParam();
  const std::string text = read_calibration(f.name);
  const std::vector<std::uint8_t> bytes(text.begin(), text.end());
  const Parsed full = parse_any(f, bytes.data(), bytes.size());
  ASSERT_EQ(full.result.error, Error::ok);
  // The last field of the last data row starts after the last comma of that line.
  const std::size_t last_row = line_start(text, f.last_data_line);
  const std::size_t last_field = text.rfind(',', text.find_first_of("\r\n", last_row)) + 1;
  int ok = 0;
  for (std::size_t n = 0; n <= bytes.size(); ++n) {
    // A buffer of exactly n bytes (none at all for n = 0), so that asan sees a read past it.
    std::vector<std::uint8_t> prefix(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n));
    if (n == 0) prefix.shrink_to_fit();
    const Parsed p = parse_any(f, n == 0 ? nullptr : prefix.data(), n);
    if (p.result.error == Error::ok) {
      ++ok;
      EXPECT_EQ(p.result.line, 0u);
      EXPECT_GE(n, last_field) << f.name << ": a prefix of " << n << " bytes parsed";
      int differ = 0;
      for (std::size_t i = 0; i < full.values.size(); ++i) differ += p.values[i] != full.values[i] ? 1 : 0;
      EXPECT_LE(differ, 1) << f.name << ": a prefix of " << n << " bytes";
    } else {
      EXPECT_GE(p.result.line, 1u);
      EXPECT_LE(p.result.line, count_lines(prefix.data(), n) + 1) << n;
    }
  }
  EXPECT_GE(ok, 1);
}

TEST_P(ShippedFileTest, RandomDamageNeverCrashes) {
  const ShippedFile& f = GetParam();
  const std::string text = read_calibration(f.name);
  std::mt19937 rng(static_cast<unsigned>(text.size()));
  const char alphabet[] = ",,\n\r0123456789.-+eE xEF\xEF\xBB\xBF\xCE";
  std::uniform_int_distribution<std::size_t> pick(0, sizeof alphabet - 2);
  for (int i = 0; i < 3000; ++i) {
    std::vector<std::uint8_t> bytes(text.begin(), text.end());
    const int changes = 1 + i % 4;
    for (int c = 0; c < changes; ++c) {
      std::uniform_int_distribution<std::size_t> at(0, bytes.size() - 1);
      const std::size_t pos = at(rng);
      switch (rng() % 3) {
        case 0: bytes[pos] = static_cast<std::uint8_t>(alphabet[pick(rng)]); break;
        case 1: bytes.erase(bytes.begin() + static_cast<std::ptrdiff_t>(pos)); break;
        default: bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(pos), static_cast<std::uint8_t>(alphabet[pick(rng)]));
      }
    }
    const Parsed p = parse_any(f, bytes.data(), bytes.size());
    if (p.result.error != Error::ok) {
      EXPECT_GE(p.result.line, 1u);
      EXPECT_LE(p.result.line, count_lines(bytes.data(), bytes.size()) + 1);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ShippedFiles, ShippedFileTest, testing::ValuesIn(kShipped),
                         [](const testing::TestParamInfo<ShippedFile>& param_info) {
                           std::string n = param_info.param.name;
                           return n.substr(0, n.find('.'));
                         });

}  // namespace
