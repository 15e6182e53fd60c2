// Zero-allocation proof for the GPS packet parser.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>

#include "alloc_counter.h"
#include "hesai/gps.h"

TEST(ZeroAllocation, GpsPacket) {
  // A Pandar64 GPS packet (Pandar64 manual, Section 3.2.2): FF EE, 2017-06-16 07:22:42, the manual's GPRMC,
  // 404 x 0xDF from byte 102, status 'A', PPS locked.
  std::array<std::uint8_t, 512> p{};
  p[0] = 0xFF;
  p[1] = 0xEE;
  const char wire[] = "716061242270";
  std::memcpy(p.data() + 2, wire, 12);
  const char nmea[] = "$GPRMC,072242,A,3027.3680,N,11423.6975,E,000.0,316.7,160617,004.1,W*67";
  std::memcpy(p.data() + 18, nmea, sizeof nmea - 1);
  for (std::size_t i = 102; i < 506; ++i) p[i] = 0xDF;
  p[506] = 'A';
  p[507] = 1;

  const hesai::ByteView view{p.data(), p.size()};
  hesai::GpsPacket g;
  hesai::Error e = hesai::Error::truncated, short_packet = hesai::Error::ok;
  bool recognised = false;
  const std::size_t n = hesai_test::allocations_during([&] {
    recognised = hesai::is_gps_packet(view);
    e = hesai::parse_gps_packet(view, g);
    short_packet = hesai::parse_gps_packet(hesai::ByteView{p.data(), 511}, g);  // an error path too
  });
  EXPECT_EQ(n, 0u);
  EXPECT_TRUE(recognised);
  EXPECT_EQ(e, hesai::Error::ok);
  EXPECT_EQ(short_packet, hesai::Error::bad_length);  // GPS packets are 512 bytes
  EXPECT_TRUE(g.nmea_checksum_ok);
}
