// The sensors' own reports allocate nothing: the functional-safety monitor on the built stream
// (every state, faults, a stall), the status and GPS-lock counters.
#include <gtest/gtest.h>

#include "../safety_stream.h"
#include "alloc_counter.h"
#include "hesai/decoder.h"
#include "hesai/safety.h"
#include "hesai/stats.h"

TEST(ZeroAllocation, SafetyMonitorAndStatusCounters) {
  const hesai_test::SafetyStream s = hesai_test::build_safety_stream();  // building may allocate
  const hesai_test::GpsBytes gps = hesai_test::gps_rmc64();
  hesai::Stats stats{};
  hesai::Error worst = hesai::Error::ok;
  const std::size_t n = hesai_test::allocations_during([&] {
    hesai::Decoder dec(hesai::Model::qt128c2x);
    hesai::SafetyMonitor monitor;
    hesai::PacketInfo info;
    for (const auto& p : s.packets) {
      const hesai::Error e = dec.validate(hesai::ByteView{p.data(), p.size()}, info);
      if (e != hesai::Error::ok) worst = e;
      hesai::count_status(stats, info);
      hesai::count_safety(stats.safety, info.safety, monitor.observe(info.safety, info.time_ns));
    }
    hesai::GpsPacket g;
    if (hesai::parse_gps_packet(hesai::ByteView{gps.data(), gps.size()}, g) == hesai::Error::ok) hesai::count_gps(stats, g);
    monitor.reset();
  });
  EXPECT_EQ(n, 0u);
  EXPECT_EQ(worst, hesai::Error::ok);
  EXPECT_EQ(stats.safety.packets, s.expect.packets);
  EXPECT_EQ(stats.safety.counter_stalls, s.expect.stalls);
  EXPECT_EQ(stats.gps_packets, 1u);
}
