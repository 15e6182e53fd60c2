// Decoder::set_angles / set_firetimes refuse geometry no sensor has (found by fuzz_angles_csv and
// fuzz_firetimes_csv: a parsed file with an elevation of 2952 degrees or a firing time of 13227 us
// was taken as is; a firing time beyond +-2147 s would have overflowed the int32 ns conversion).
#include <gtest/gtest.h>

#include "hesai/calibration.h"
#include "hesai/decoder.h"

namespace {

using hesai::Error;
using hesai::Model;

hesai::AngleCorrection flat_angles(std::uint16_t channels) {
  hesai::AngleCorrection a;
  a.channels = channels;
  return a;
}

hesai::FiretimeCorrection firetimes(std::uint16_t channels, std::uint8_t loops) {
  hesai::FiretimeCorrection f;
  f.channels = channels;
  f.loops = loops;
  for (std::size_t loop = 0; loop < loops; ++loop)
    for (std::size_t i = 0; i < channels; ++i) f.fires[loop][i] = true;
  return f;
}

TEST(CalibrationRange, AnglesAtTheLimitsAreAccepted) {
  hesai::Decoder d(Model::pandar64);
  hesai::AngleCorrection a = flat_angles(64);
  a.elevation_deg[0] = 90.0;
  a.elevation_deg[1] = -90.0;
  a.azimuth_deg[2] = 360.0;
  a.azimuth_deg[3] = -360.0;
  EXPECT_EQ(d.set_angles(a), Error::ok);
}

TEST(CalibrationRange, ElevationBeyondVerticalIsRefused) {
  hesai::Decoder d(Model::pandar64);
  hesai::AngleCorrection a = flat_angles(64);
  a.elevation_deg[4] = 2952.0;
  EXPECT_EQ(d.set_angles(a), Error::invalid_argument);
  a.elevation_deg[4] = -90.001;
  EXPECT_EQ(d.set_angles(a), Error::invalid_argument);
}

TEST(CalibrationRange, AzimuthOffsetBeyondOneTurnIsRefused) {
  hesai::Decoder d(Model::pandar40p);
  hesai::AngleCorrection a = flat_angles(40);
  a.azimuth_deg[39] = 360.5;
  EXPECT_EQ(d.set_angles(a), Error::invalid_argument);
}

TEST(CalibrationRange, FiretimesWithinOneMillisecondAreAccepted) {
  hesai::Decoder d(Model::qt128c2x);
  hesai::FiretimeCorrection f = firetimes(128, 2);
  f.firetime_us[0][0] = 1000.0;
  f.firetime_us[1][127] = -1000.0;
  EXPECT_EQ(d.set_firetimes(f), Error::ok);
}

TEST(CalibrationRange, FiretimeBeyondOneMillisecondIsRefused) {
  hesai::Decoder d(Model::qt128c2x);
  hesai::FiretimeCorrection f = firetimes(128, 2);
  f.firetime_us[1][14] = 13227.0;
  EXPECT_EQ(d.set_firetimes(f), Error::invalid_argument);
  hesai::Decoder p(Model::pandar64);
  hesai::FiretimeCorrection g = firetimes(64, 1);
  g.firetime_us[0][3] = -1e13;  // would overflow the int32 ns value
  EXPECT_EQ(p.set_firetimes(g), Error::invalid_argument);
}

TEST(CalibrationRange, TimeOfAChannelThatDoesNotFireIsIgnored) {
  hesai::Decoder d(Model::qt128c2x);
  hesai::FiretimeCorrection f = firetimes(128, 2);
  f.fires[0][5] = false;
  f.firetime_us[0][5] = 1e9;
  EXPECT_EQ(d.set_firetimes(f), Error::ok);
}

}  // namespace
