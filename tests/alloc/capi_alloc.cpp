// The C interface (hesai/hesai.h) allocates nothing: set-up from calibration files and the decode
// of a whole capture, with a session key.
#include <gtest/gtest.h>

#include "../test_support.h"
#include "alloc_counter.h"
#include "hesai/hesai.h"

namespace {

TEST(ZeroAllocation, CInterface) {
  const auto packets = hesai_test::pcap_payloads("qt128c2x_dual.pcap");  // reading the file may allocate
  const auto angles = hesai_test::read_file(hesai_test::data_path("calibration/qt128c2x_unit_a_angles.csv"));
  const auto firetimes = hesai_test::read_file(hesai_test::data_path("calibration/qt128c2x_firetimes.csv"));
  ASSERT_FALSE(packets.empty());
  static hesai_decoder decoder;
  static hesai_calibration_scratch scratch;
  static hesai_point points[256];
  const std::uint8_t key[32] = {1, 2, 3};
  std::size_t total = 0;
  hesai_error worst = HESAI_ERROR_ok;
  const std::size_t n = hesai_test::allocations_during([&] {
    hesai_error e = hesai_decoder_init(&decoder, HESAI_MODEL_qt128c2x);
    if (e == HESAI_ERROR_ok) e = hesai_decoder_set_angles_csv(&decoder, angles.data(), angles.size(), &scratch, nullptr);
    if (e == HESAI_ERROR_ok)
      e = hesai_decoder_set_firetimes_csv(&decoder, firetimes.data(), firetimes.size(), &scratch, nullptr);
    if (e == HESAI_ERROR_ok) e = hesai_decoder_set_session_key(&decoder, key);
    if (e == HESAI_ERROR_ok) e = hesai_decoder_set_allow_unsigned(&decoder, 1);
    worst = e;
    for (const auto& p : packets) {
      hesai_packet_info info;
      std::size_t count = 0;
      e = hesai_decoder_decode(&decoder, p.data(), p.size(), &info, points, 256, &count);
      if (e != HESAI_ERROR_ok) worst = e;
      total += count;
    }
    if (hesai_decoder_clear_session_key(&decoder) != HESAI_ERROR_ok) worst = HESAI_ERROR_invalid_argument;
  });
  EXPECT_STREQ(hesai_error_name(worst), "ok");
  EXPECT_GT(total, 0u);
  EXPECT_EQ(n, 0u);
}

}  // namespace
