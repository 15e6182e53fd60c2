// Zero-allocation proof for the calibration parsers: the files are read before counting starts.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>

#include "alloc_counter.h"
#include "hesai/calibration.h"

namespace {

std::string read_calibration(const char* name) {
  std::ifstream in(std::string(HESAI_DATA_DIR) + "/calibration/" + name, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

hesai::ByteView view(const std::string& s) { return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()}; }

}  // namespace

TEST(ZeroAllocation, CalibrationParsers) {
  const std::string angles = read_calibration("qt128c2x_unit_a_angles.csv");
  const std::string pandar_firetimes = read_calibration("pandar64_firetimes.csv");
  const std::string qt_firetimes = read_calibration("qt128c2x_firetimes.csv");
  const std::string config = read_calibration("qt128c2x_channel_config.csv");
  const std::string bad = "Laser id,Elevation,Azimuth\n1,1.5,x\n";
  ASSERT_FALSE(angles.empty());
  ASSERT_FALSE(config.empty());

  static hesai::AngleCorrection angle_out;
  static hesai::FiretimeCorrection firetime_out;
  static hesai::ChannelConfig config_out;
  hesai::ParseResult r[5];
  double d = 0.0;
  bool decimal_ok = false;
  const char number[] = "1.7976931348623157e308";
  const std::size_t n = hesai_test::allocations_during([&] {
    r[0] = hesai::parse_angle_csv(view(angles), 128, angle_out);
    r[1] = hesai::parse_firetime_csv(view(pandar_firetimes), 64, firetime_out);
    r[2] = hesai::parse_firetime_csv(view(qt_firetimes), 128, firetime_out);
    r[3] = hesai::parse_channel_config_csv(view(config), config_out);
    r[4] = hesai::parse_angle_csv(view(bad), 1, angle_out);
    decimal_ok = hesai::parse_decimal(number, number + sizeof number - 1, d);
  });
  EXPECT_EQ(n, 0u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(r[i].error, hesai::Error::ok) << i;
  EXPECT_EQ(r[4].error, hesai::Error::calib_bad_number);
  EXPECT_TRUE(decimal_ok);
}
