// The stream-health monitor and the decode with a unit scan allocate nothing: the Pandar64 capture cut to its sequence-less
// length, with packets dropped (a gap), one late, one frozen and one redated to 2000.
#include <gtest/gtest.h>

#include <vector>

#include "../test_support.h"
#include "alloc_counter.h"
#include "hesai/decoder.h"
#include "hesai/health.h"

TEST(ZeroAllocation, HealthMonitor) {
  std::vector<std::vector<std::uint8_t>> p = hesai_test::pcap_payloads("pandar64_dual.pcap");  // may allocate
  ASSERT_GT(p.size(), 200u);
  for (auto& q : p) q.resize(1194);
  p.erase(p.begin() + 100, p.begin() + 110);
  std::swap(p[150], p[151]);
  for (std::size_t b = 10; b < 14; ++b) p[160][1172 + b] = p[159][1172 + b];  // the timestamp (same second)
  p[170][1172 + 16] = 0;
  static hesai::HealthCounts counts;
  static hesai::PacketPoints points;
  hesai::Error worst = hesai::Error::ok;
  const std::size_t n = hesai_test::allocations_during([&] {
    hesai::Decoder dec(hesai::Model::pandar64);
    hesai::HealthMonitor monitor;
    hesai::PacketInfo info;
    hesai::UnitScan scan;
    for (const auto& q : p) {
      const hesai::Error e = dec.decode(hesai::ByteView{q.data(), q.size()}, info, points, scan);
      if (e != hesai::Error::ok) worst = e;
      (void)monitor.observe(info);
      monitor.observe_units(scan);
    }
    counts = monitor.counts();
    monitor.reset();
  });
  EXPECT_EQ(n, 0u);
  EXPECT_EQ(worst, hesai::Error::ok);
  EXPECT_EQ(counts.packets, p.size());
  EXPECT_EQ(counts.lost, 10u);
  EXPECT_EQ(counts.reordered, 1u);
  EXPECT_EQ(counts.time_virtual, 1u);
  EXPECT_EQ(counts.time_stalls, 2u);  // 160 (its predecessor's time) and 170 (20 years back)
  EXPECT_EQ(counts.time_jumps, 1u);   // 171, 20 years on from 170
  EXPECT_GT(counts.duplicate_returns, 0u);
}
