// Spot checks of the built-in calibration tables against values read by hand from the manuals;
// each test names the manual's section and table it reads.
// The vendor-file tests compare whole tables against the files the lidars ship
// (data/calibration/), which are independent of the manual text.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "hesai/detail/tables/block_times.h"
#include "hesai/detail/tables/pandar40_tables.h"
#include "hesai/detail/tables/pandar64_tables.h"
#include "hesai/detail/tables/qt128_tables.h"
#include "pandar64_manual.h"

namespace {

struct AngleCase {
  int channel;
  double elevation_deg;
  double azimuth_deg;
};

struct TimeCase {
  int channel;
  double time_us;
};

template <std::size_t N>
void expect_angles(const std::array<hesai::tables::ChannelAngle, N>& table, const std::vector<AngleCase>& cases) {
  for (const auto& c : cases) {
    SCOPED_TRACE("channel " + std::to_string(c.channel));
    const auto& a = table[static_cast<std::size_t>(c.channel - 1)];
    EXPECT_DOUBLE_EQ(a.elevation_deg, c.elevation_deg);
    EXPECT_DOUBLE_EQ(a.azimuth_deg, c.azimuth_deg);
  }
}

template <std::size_t N>
void expect_times(const std::array<double, N>& table, const std::vector<TimeCase>& cases) {
  for (const auto& c : cases) {
    SCOPED_TRACE("channel " + std::to_string(c.channel));
    EXPECT_DOUBLE_EQ(table[static_cast<std::size_t>(c.channel - 1)], c.time_us);
  }
}

// Reads a CSV file of the bundled calibration data into rows of fields (CR stripped).
std::vector<std::vector<std::string>> read_csv(const std::string& name) {
  std::ifstream in(std::string(HESAI_DATA_DIR) + "/calibration/" + name);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::vector<std::string> fields;
    std::stringstream ss(line);
    std::string f;
    while (std::getline(ss, f, ',')) fields.push_back(f);
    rows.push_back(fields);
  }
  return rows;
}

// ---- Sizes -----------------------------------------------------------------------------------

TEST(Tables, Sizes) {
  EXPECT_EQ(hesai::tables::pandar64_channel_angles.size(), 64u);
  EXPECT_EQ(hesai::tables::pandar64_fire_rows.size(), 64u);
  EXPECT_EQ(hesai::tables::pandar64_firetime_us.size(), 64u);
  EXPECT_EQ(hesai::tables::pandar64_nonlinear_reflectivity_pct.size(), 256u);
  EXPECT_EQ(hesai::tables::pandar40_channel_angles.size(), 40u);
  EXPECT_EQ(hesai::tables::pandar40_fire_rows.size(), 40u);
  EXPECT_EQ(hesai::tables::pandar40_firetime_us.size(), 40u);
  EXPECT_EQ(hesai::tables::qt128_channel_angles.size(), 128u);
  EXPECT_EQ(hesai::tables::qt128_fire_rows.size(), 96u);  // QT128C2X App. II: "96 channel rows"
  EXPECT_EQ(hesai::tables::qt128_firetime_us_loop1.size(), 128u);
  EXPECT_EQ(hesai::tables::qt128_firetime_us_loop2.size(), 128u);
  EXPECT_EQ(hesai::tables::qt128_fires_in_loop1.size(), 128u);
  EXPECT_EQ(hesai::tables::qt128_fires_in_loop2.size(), 128u);
  EXPECT_EQ(hesai::tables::pandar40_block_end_us_single.size(), 10u);
  EXPECT_EQ(hesai::tables::pandar64_block_end_us_single.size(), 6u);
  EXPECT_EQ(hesai::tables::qt128_block_start_us_single.size(), 2u);
}

// ---- Pandar64 ----------------------------------------------------------------------------------

// Pandar64 manual, Appendix A "Channel distribution data".
TEST(Pandar64Tables, ChannelAngles) {
  expect_angles(hesai::tables::pandar64_channel_angles, {
      {1, 14.882, -1.042},
      {5, 3.040, -1.042},     // and the worked example, Section 3.1.4
      {7, 1.860, 1.042},
      {10, 1.351, -5.208},
      {18, 0.000, -1.042},
      {23, -0.845, -3.125},
      {33, -2.536, 5.208},
      {39, -3.548, 5.208},
      {41, -3.884, -3.125},
      {53, -5.898, -3.125},
      {58, -9.885, -1.042},   // doubtful value, kept as printed
      {62, -13.930, -1.042},
      {64, -24.897, -1.042},
  });
}

// Pandar64 manual, Appendix B.4 "Laser firing time of each channel".
TEST(Pandar64Tables, FireTimes) {
  expect_times(hesai::tables::pandar64_firetime_us, {
      {12, -54.668},
      {40, -54.668},
      {26, -50.732},
      {37, -33.02},
      {33, -25.148},
      {1, -23.18},
      {52, -20.572},
      {5, -17.964},   // and the worked example, Section 3.1.4.2
      {64, -12.748},
      {9, -7.532},
      {51, -3.62},
      {61, -3.62},
  });
  // The printed rows: {firing sequence, channel, dt}.
  EXPECT_EQ(hesai::tables::pandar64_fire_rows[0].order, 1);        // the first row
  EXPECT_EQ(hesai::tables::pandar64_fire_rows[0].channel, 12);
  EXPECT_EQ(hesai::tables::pandar64_fire_rows[63].order, 32);      // the last row
  EXPECT_EQ(hesai::tables::pandar64_fire_rows[63].channel, 61);
  for (double t : hesai::tables::pandar64_firetime_us) {
    EXPECT_LT(t, 0.0);  // relative to the block END time
  }
}

// Pandar64 manual, Appendix D "Nonlinear reflectivity mapping".
TEST(Pandar64Tables, NonlinearReflectivity) {
  const auto& r = hesai::tables::pandar64_nonlinear_reflectivity_pct;
  EXPECT_DOUBLE_EQ(r[0], 0.0);
  EXPECT_DOUBLE_EQ(r[6], 0.08);
  EXPECT_DOUBLE_EQ(r[17], 0.5);
  EXPECT_DOUBLE_EQ(r[75], 9.1);
  EXPECT_DOUBLE_EQ(r[76], 9.3);
  EXPECT_DOUBLE_EQ(r[113], 20.25);
  EXPECT_DOUBLE_EQ(r[155], 38.25);
  EXPECT_DOUBLE_EQ(r[160], 40.5);
  EXPECT_DOUBLE_EQ(r[199], 62.5);
  EXPECT_DOUBLE_EQ(r[235], 87.25);
  EXPECT_DOUBLE_EQ(r[236], 87.75);
  EXPECT_DOUBLE_EQ(r[251], 99.5);
  EXPECT_DOUBLE_EQ(r[252], 132.0);
  EXPECT_DOUBLE_EQ(r[254], 242.0);
  // 255: the manual prints "- -".
  EXPECT_DOUBLE_EQ(r[255], hesai::tables::pandar64_reflectivity_undefined);
}

// Every entry of the core's Appendix A offsets, B.4 firing times and Appendix D mapping against
// the tests' own transcription of the manual (tests/pandar64_manual.h).
TEST(Pandar64Tables, EveryEntryMatchesTheTestsTranscription) {
  namespace manual = hesai_test::pandar64_manual;
  for (std::size_t ch = 0; ch < 64; ++ch) {
    EXPECT_DOUBLE_EQ(hesai::tables::pandar64_channel_angles[ch].azimuth_deg, manual::kAzimuthOffsetDeg[ch]) << ch + 1;
    EXPECT_DOUBLE_EQ(hesai::tables::pandar64_firetime_us[ch], manual::kFiringOffsetUs[ch]) << ch + 1;
  }
  for (std::size_t b = 0; b < manual::kNonlinearReflectivityHundredths.size(); ++b)
    EXPECT_NEAR(hesai::tables::pandar64_nonlinear_reflectivity_pct[b] * 100.0,
                manual::kNonlinearReflectivityHundredths[b], 1e-9) << b;
}

TEST(Pandar64Tables, MatchesVendorFiretimeFile) {
  const auto rows = read_csv("pandar64_firetimes.csv");
  ASSERT_EQ(rows.size(), 65u);
  EXPECT_EQ(rows[0][0], "Channel");
  for (std::size_t i = 1; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), 2u);
    const int ch = std::stoi(rows[i][0]);
    ASSERT_GE(ch, 1);
    ASSERT_LE(ch, 64);
    EXPECT_DOUBLE_EQ(hesai::tables::pandar64_firetime_us[static_cast<std::size_t>(ch - 1)], std::stod(rows[i][1]))
        << "channel " << ch;
  }
}

// The real units' angle files: azimuths equal the design values; each unit's elevations are the
// design values shifted by one constant (its mounting tilt), except unit A's channel 58, which
// sits 0.16 deg lower than the manual's -9.885 (see pandar64_tables.h).
TEST(Pandar64Tables, MatchesUnitFiles) {
  for (const char* name : {"pandar64_unit_a_angles.csv", "pandar64_unit_b_angles.csv"}) {
    const auto rows = read_csv(name);
    ASSERT_EQ(rows.size(), 65u) << name;
    ASSERT_EQ(std::stoi(rows[1][0]), 1);
    const double tilt = std::stod(rows[1][1]) - hesai::tables::pandar64_channel_angles[0].elevation_deg;
    for (std::size_t i = 1; i < rows.size(); ++i) {
      const int ch = std::stoi(rows[i][0]);
      const auto& a = hesai::tables::pandar64_channel_angles[static_cast<std::size_t>(ch - 1)];
      EXPECT_DOUBLE_EQ(a.azimuth_deg, std::stod(rows[i][2])) << name << " channel " << ch;
      const double residual = std::stod(rows[i][1]) - tilt - a.elevation_deg;
      if (std::string(name) == "pandar64_unit_a_angles.csv" && ch == 58) {
        EXPECT_NEAR(residual, -0.16, 0.0015);
      } else {
        EXPECT_NEAR(residual, 0.0, 0.0015) << name << " channel " << ch;
      }
    }
  }
}

// ---- Pandar40 / Pandar40P ----------------------------------------------------------------------

// Pandar40 manual, Appendix I, Table I.1 "Pandar40 Channel Distribution".
TEST(Pandar40Tables, ChannelAngles) {
  expect_angles(hesai::tables::pandar40_channel_angles, {
      {1, 15.00, -1.042},    // "Top Line"
      {5, 3.00, -1.042},
      {7, 1.67, 3.125},
      {12, 0.00, -1.042},    // "Horizontal Line"
      {14, -0.67, -5.208},
      {15, -1.00, -1.042},
      {16, -1.33, 3.125},
      {29, -5.67, -5.208},   // OCR glued "-5.208-5.67" (repaired)
      {30, -6.00, -1.042},   // OCR glued "-1.042-6.00" (repaired)
      {31, -7.00, -1.042},   // OCR glued "-1.042-7.00" (repaired)
      {32, -8.00, -1.042},
      {34, -10.00, -1.042},
      {39, -19.00, -1.042},
      {40, -25.00, -1.042},  // "Bottom Line"
  });
  // Section 1.1.3 "Pandar40 Channel Vertical Distribution": 1/3 deg steps between channels 6 and
  // 30, 1 deg steps between channels 30 and 38.
  const auto& a = hesai::tables::pandar40_channel_angles;
  for (std::size_t i = 6; i < 30; ++i) EXPECT_NEAR(a[i - 1].elevation_deg - a[i].elevation_deg, 1.0 / 3.0, 0.011) << i;
  for (std::size_t i = 30; i < 38; ++i) EXPECT_DOUBLE_EQ(a[i - 1].elevation_deg - a[i].elevation_deg, 1.0) << i;
}

// Pandar40 manual, Appendix II, 2 "Laser Firing Time Calculation".
TEST(Pandar40Tables, FireTimes) {
  // The manual prints (t6 - x); the table stores -x.
  expect_times(hesai::tables::pandar40_firetime_us, {
      {4, -3.62},
      {40, -3.62},
      {12, -8.19},
      {17, -14.74},
      {3, -16.04},
      {14, -27.16},
      {2, -28.47},
      {11, -40.91},
      {1, -42.22},
      {27, -48.76},
      {20, -52.7},
      {8, -54.67},
  });
  EXPECT_DOUBLE_EQ(hesai::tables::pandar40_fire_rows[0].time_us, 3.62);  // the first item, as printed
}

TEST(Pandar40Tables, MatchesPandar40PVendorFiles) {
  const auto ft = read_csv("pandar40p_firetimes.csv");
  ASSERT_EQ(ft.size(), 41u);
  for (std::size_t i = 1; i < ft.size(); ++i) {
    const int ch = std::stoi(ft[i][0]);
    ASSERT_GE(ch, 1);
    ASSERT_LE(ch, 40);
    EXPECT_DOUBLE_EQ(hesai::tables::pandar40_firetime_us[static_cast<std::size_t>(ch - 1)], std::stod(ft[i][1]))
        << "channel " << ch;
  }
  // Same design: equal azimuth offsets; elevations of the real units within 0.45 deg.
  for (const char* name : {"pandar40p_unit_a_angles.csv", "pandar40p_unit_b_angles.csv"}) {
    const auto rows = read_csv(name);
    ASSERT_EQ(rows.size(), 41u) << name;
    for (std::size_t i = 1; i < rows.size(); ++i) {
      const int ch = std::stoi(rows[i][0]);
      const auto& a = hesai::tables::pandar40_channel_angles[static_cast<std::size_t>(ch - 1)];
      EXPECT_DOUBLE_EQ(a.azimuth_deg, std::stod(rows[i][2])) << name << " channel " << ch;
      EXPECT_NEAR(a.elevation_deg, std::stod(rows[i][1]), 0.45) << name << " channel " << ch;
    }
  }
}

// ---- QT128C2X ----------------------------------------------------------------------------------

// QT128C2X manual, Appendix I "Channel Distribution".
TEST(Qt128Tables, ChannelAngles) {
  expect_angles(hesai::tables::qt128_channel_angles, {
      {1, -52.627, 10.108},
      {5, -46.695, 8.833},    // and the worked example, Section 3.1.3
      {32, -19.191, 6.250},
      {33, -18.331, -6.217},
      {47, -6.688, -5.927},
      {56, 0.606, -5.891},
      {64, 7.094, -5.938},
      {65, 7.910, 5.949},
      {96, 35.549, 7.327},
      {97, 19.191, -6.250},
      {114, 35.030, -7.277},
      {128, 52.627, -10.108},
  });
}

TEST(Qt128Tables, UnitFileWithinRounding) {
  const auto rows = read_csv("qt128c2x_unit_a_angles.csv");
  ASSERT_EQ(rows.size(), 129u);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const int ch = std::stoi(rows[i][0]);
    const auto& a = hesai::tables::qt128_channel_angles[static_cast<std::size_t>(ch - 1)];
    EXPECT_NEAR(a.elevation_deg, std::stod(rows[i][1]), 0.0005) << "channel " << ch;
    EXPECT_NEAR(a.azimuth_deg, std::stod(rows[i][2]), 0.0005) << "channel " << ch;
  }
}

void expect_row(std::size_t index, int l1, double t1, int l2, double t2) {
  SCOPED_TRACE("row " + std::to_string(index));
  const auto& r = hesai::tables::qt128_fire_rows[index];
  EXPECT_EQ(r.loop1_channel, l1);
  EXPECT_DOUBLE_EQ(r.loop1_time_us, t1);
  EXPECT_EQ(r.loop2_channel, l2);
  EXPECT_DOUBLE_EQ(r.loop2_time_us, t2);
}

// QT128C2X manual, Appendix II, "Firetime Correction File" (row index 0 = the first channel row);
// where the English edition's OCR text lost the Loop1 column, the Chinese edition's copy.
TEST(Qt128Tables, FireRows) {
  expect_row(0, 99, 0.6, 65, 0.6);
  expect_row(2, 35, 2.312, 1, 2.312);
  expect_row(20, 59, 21.32, 25, 21.32);
  expect_row(21, 126, 22.776, 96, 22.776);
  expect_row(46, 94, 48.976, 128, 48.976);
  expect_row(47, 64, 49.832, 30, 49.832);       // Loop1 from the Chinese edition
  expect_row(50, 34, 53.0, 4, 53.0);            // Loop1 from the Chinese edition
  expect_row(57, 111, 60.792, 77, 60.792);      // Loop1 from the Chinese edition
  expect_row(58, 77, 61.648, 111, 61.648);      // Loop1 from the Chinese edition ("7", repaired)
  expect_row(72, 100, 76.632, 66, 76.632);      // Loop1 from the Chinese edition
  expect_row(73, 66, 77.488, 100, 77.488);
  expect_row(95, 61, 100.52, 31, 100.52);
}

// QT128C2X manual, Appendix II: "Firing Sequences" and "Firetime Correction File".
TEST(Qt128Tables, PerLoopArrays) {
  using hesai::tables::qt128_fires_in_loop1;
  using hesai::tables::qt128_fires_in_loop2;
  using hesai::tables::qt128_firetime_us_loop1;
  using hesai::tables::qt128_firetime_us_loop2;
  EXPECT_EQ(hesai::tables::qt128_loop1_channel_count, 96u);
  EXPECT_EQ(hesai::tables::qt128_loop2_channel_count, 96u);

  // Banks C and D fire in both sequences, at different times.
  EXPECT_DOUBLE_EQ(qt128_firetime_us_loop1[99 - 1], 0.6);
  EXPECT_DOUBLE_EQ(qt128_firetime_us_loop2[99 - 1], 1.456);
  EXPECT_DOUBLE_EQ(qt128_firetime_us_loop1[128 - 1], 48.12);
  EXPECT_DOUBLE_EQ(qt128_firetime_us_loop2[128 - 1], 48.976);
  EXPECT_DOUBLE_EQ(qt128_firetime_us_loop1[77 - 1], 61.648);  // Chinese edition (repaired)
  EXPECT_DOUBLE_EQ(qt128_firetime_us_loop2[77 - 1], 60.792);
  EXPECT_TRUE(qt128_fires_in_loop1[65 - 1] && qt128_fires_in_loop2[65 - 1]);
  EXPECT_TRUE(qt128_fires_in_loop1[77 - 1] && qt128_fires_in_loop2[77 - 1]);

  // Bank B (33..64) fires only in sequence 1, bank A (1..32) only in sequence 2 ("Firing Sequences").
  for (int ch : {33, 48, 64}) {
    EXPECT_TRUE(qt128_fires_in_loop1[static_cast<std::size_t>(ch - 1)]) << ch;
    EXPECT_FALSE(qt128_fires_in_loop2[static_cast<std::size_t>(ch - 1)]) << ch;
  }
  for (int ch : {1, 7, 32}) {
    EXPECT_FALSE(qt128_fires_in_loop1[static_cast<std::size_t>(ch - 1)]) << ch;
    EXPECT_TRUE(qt128_fires_in_loop2[static_cast<std::size_t>(ch - 1)]) << ch;
  }
  EXPECT_DOUBLE_EQ(qt128_firetime_us_loop1[33 - 1], 27.656);
  EXPECT_DOUBLE_EQ(qt128_firetime_us_loop1[64 - 1], 49.832);  // Chinese edition
  EXPECT_DOUBLE_EQ(qt128_firetime_us_loop1[61 - 1], 100.52);
  EXPECT_DOUBLE_EQ(qt128_firetime_us_loop2[1 - 1], 2.312);
  EXPECT_DOUBLE_EQ(qt128_firetime_us_loop2[7 - 1], 81.512);
  EXPECT_DOUBLE_EQ(qt128_firetime_us_loop2[31 - 1], 100.52);

  int only1 = 0;
  int only2 = 0;
  for (std::size_t i = 0; i < 128; ++i) {
    only1 += (qt128_fires_in_loop1[i] && !qt128_fires_in_loop2[i]) ? 1 : 0;
    only2 += (!qt128_fires_in_loop1[i] && qt128_fires_in_loop2[i]) ? 1 : 0;
  }
  EXPECT_EQ(only1, 32);
  EXPECT_EQ(only2, 32);
}

TEST(Qt128Tables, MatchesVendorFiretimeFile) {
  const auto rows = read_csv("qt128c2x_firetimes.csv");
  ASSERT_GE(rows.size(), 3u + 96u);
  EXPECT_EQ(rows[2][0], "Loop1");
  for (std::size_t i = 0; i < 96; ++i) {
    const auto& f = rows[3 + i];
    ASSERT_GE(f.size(), 4u);
    const auto& r = hesai::tables::qt128_fire_rows[i];
    EXPECT_EQ(r.loop1_channel, std::stoi(f[0])) << "row " << i;
    EXPECT_DOUBLE_EQ(r.loop1_time_us, std::stod(f[1])) << "row " << i;
    EXPECT_EQ(r.loop2_channel, std::stoi(f[2])) << "row " << i;
    EXPECT_DOUBLE_EQ(r.loop2_time_us, std::stod(f[3])) << "row " << i;
  }
  for (std::size_t i = 3 + 96; i < rows.size(); ++i) {
    for (const auto& f : rows[i]) EXPECT_EQ(f, "0") << "padding row " << i;
  }
}

// ---- Block times -------------------------------------------------------------------------------

// Pandar40 manual, Appendix II, 2 "Laser Firing Time Calculation": end of block N in single
// return = t0 - 28.58 - 55.56 x (10 - N); in dual return blocks (9, 10), (7, 8), ... share one.
TEST(BlockTimes, Pandar40) {
  using hesai::tables::pandar40_block_end_us_dual;
  using hesai::tables::pandar40_block_end_us_single;
  EXPECT_NEAR(pandar40_block_end_us_single[10 - 1], -28.58, 1e-9);
  EXPECT_NEAR(pandar40_block_end_us_single[3 - 1], -28.58 - 55.56 * 7, 1e-9);
  EXPECT_NEAR(pandar40_block_end_us_single[2 - 1], -28.58 - 55.56 * 8, 1e-9);
  EXPECT_NEAR(pandar40_block_end_us_single[1 - 1], -28.58 - 55.56 * 9, 1e-9);
  EXPECT_NEAR(pandar40_block_end_us_dual[10 - 1], -28.58, 1e-9);
  EXPECT_NEAR(pandar40_block_end_us_dual[9 - 1], -28.58, 1e-9);
  EXPECT_NEAR(pandar40_block_end_us_dual[8 - 1], -28.58 - 55.56 * 1, 1e-9);
  EXPECT_NEAR(pandar40_block_end_us_dual[7 - 1], -28.58 - 55.56 * 1, 1e-9);
  EXPECT_NEAR(pandar40_block_end_us_dual[6 - 1], -28.58 - 55.56 * 2, 1e-9);
  EXPECT_NEAR(pandar40_block_end_us_dual[5 - 1], -28.58 - 55.56 * 2, 1e-9);
  EXPECT_NEAR(pandar40_block_end_us_dual[4 - 1], -28.58 - 55.56 * 3, 1e-9);
  EXPECT_NEAR(pandar40_block_end_us_dual[3 - 1], -28.58 - 55.56 * 3, 1e-9);
  EXPECT_NEAR(pandar40_block_end_us_dual[2 - 1], -28.58 - 55.56 * 4, 1e-9);
  EXPECT_NEAR(pandar40_block_end_us_dual[1 - 1], -28.58 - 55.56 * 4, 1e-9);
  for (std::size_t n = 1; n <= 10; ++n) {  // end of block N = t0 - 28.58 - 55.56 * (10 - N)
    EXPECT_NEAR(hesai::tables::pandar40_block_end_us(n, false), -28.58 - 55.56 * static_cast<double>(10 - n), 1e-9);
  }
}

// Pandar64 manual, Appendix B.3 "End time of each block".
TEST(BlockTimes, Pandar64) {
  using hesai::tables::pandar64_block_end_us_dual;
  using hesai::tables::pandar64_block_end_us_single;
  EXPECT_NEAR(pandar64_block_end_us_single[6 - 1], -42.58, 1e-9);
  EXPECT_NEAR(pandar64_block_end_us_single[3 - 1], -42.58 - 55.56 * 3, 1e-9);
  EXPECT_NEAR(pandar64_block_end_us_single[2 - 1], -42.58 - 55.56 * 4, 1e-9);
  EXPECT_NEAR(pandar64_block_end_us_single[1 - 1], -42.58 - 55.56 * 5, 1e-9);
  EXPECT_NEAR(pandar64_block_end_us_dual[6 - 1], -42.58, 1e-9);
  EXPECT_NEAR(pandar64_block_end_us_dual[5 - 1], -42.58, 1e-9);
  EXPECT_NEAR(pandar64_block_end_us_dual[4 - 1], -42.58 - 55.56 * 1, 1e-9);
  EXPECT_NEAR(pandar64_block_end_us_dual[3 - 1], -42.58 - 55.56 * 1, 1e-9);
  EXPECT_NEAR(pandar64_block_end_us_dual[2 - 1], -42.58 - 55.56 * 2, 1e-9);
  EXPECT_NEAR(pandar64_block_end_us_dual[1 - 1], -42.58 - 55.56 * 2, 1e-9);
  // Worked example (Section 3.1.4): channel 5 in block 3 fires 17.964 us before block 3 ends.
  EXPECT_NEAR(hesai::tables::pandar64_block_end_us(3, false) + hesai::tables::pandar64_firetime_us[5 - 1],
              -42.58 - 55.56 * 3 - 17.964, 1e-9);
}

// QT128C2X manual, Appendix II, "Start Time of Each Block".
TEST(BlockTimes, Qt128) {
  EXPECT_DOUBLE_EQ(hesai::tables::qt128_block_start_us_single[0], 9.0);
  EXPECT_NEAR(hesai::tables::qt128_block_start_us_single[1], 9.0 + 111.11, 1e-9);
  EXPECT_DOUBLE_EQ(hesai::tables::qt128_block_start_us_dual[0], 9.0);
  EXPECT_DOUBLE_EQ(hesai::tables::qt128_block_start_us_dual[1], 9.0);
}

}  // namespace
