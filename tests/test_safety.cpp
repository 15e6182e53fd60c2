// What the sensors report about themselves: QT128 functional safety (SafetyMonitor), the Pandar
// high-temperature shutdown flag and the GPS lock (count_status, count_gps).
//
// Facts: QT128C2X manual, Section 3.1.2 "UDP Data", table "Functional Safety: 17 bytes" (lidar
// states d-0 Init .. d-7 Standby in [7:5]; fault code type [4:3], b-01 current, b-10 past;
// rolling counter [2:0], updated normally every 5 ms); Pandar64 manual Section 3.1.2.3 "Tail" and
// Pandar40 manual Table 3.4 (High Temperature Shutdown Flag, 0x01 high temperature); Pandar64
// manual Section 3.2.2 (PPS Lock Flag 1 locked, 0 unlocked) and 3.2.2.1 (Location Status: A
// valid, V void, NUL GPS unlocked); Pandar40 manual Table 3.6 (A valid, V invalid; PPS 1 locked).
#include <gtest/gtest.h>

#include <cstdint>
#include <iterator>
#include <vector>

#include "hesai/decoder.h"
#include "hesai/safety.h"
#include "hesai/stats.h"
#include "packet_builder.h"
#include "safety_stream.h"
#include "test_support.h"

using namespace hesai;
using namespace hesai_test;

namespace {

constexpr std::int64_t kMs = 1000000;

FunctionalSafety section(std::uint8_t state, std::uint8_t counter, std::uint8_t fault_type = 0) {
  FunctionalSafety fs;
  fs.present = true;
  fs.version = 1;
  fs.lidar_state = state;
  fs.rolling_counter = counter;
  fs.fault_code_type = fault_type;
  return fs;
}

// Feeds packets `period_ns` apart from `t0` with the given counter value; returns the stalls begun.
unsigned feed(SafetyMonitor& m, std::int64_t& t, std::int64_t period_ns, int packets, std::uint8_t counter) {
  unsigned began = 0;
  for (int i = 0; i < packets; ++i, t += period_ns) began += m.observe(section(1, counter), t) ? 1u : 0u;
  return began;
}

TEST(Safety, StateNames) {
  // The manual's eight states, in the order of their codes d-0 .. d-7.
  const char* const names[8] = {"init", "normal", "report_fault", "pre_performance_degradation",
                                "performance_degradation", "pre_shutdown", "shutdown", "standby"};
  for (std::uint8_t s = 0; s < 8; ++s) EXPECT_STREQ(lidar_state_name(s), names[s]);
  EXPECT_STREQ(lidar_state_name(8), "unknown");
}

// The bundled capture: every packet in state Init (counted from the raw bytes here: the top 3
// bits of byte 1 of the functional-safety section at 1044), no fault, and no stall.
TEST(Safety, BundledCaptureIsInitWithoutStall) {
  const auto packets = pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_FALSE(packets.empty());
  std::uint64_t init = 0, with_fault = 0;
  for (const auto& p : packets) {
    ASSERT_EQ(p[11] & 4, 4);  // flags bit 2: the section is present
    init += (p[kQtFs + 1] >> 5) == 0;
    with_fault += ((p[kQtFs + 1] >> 3) & 3) != 0;
  }
  EXPECT_EQ(init, 1800u);
  EXPECT_EQ(init, packets.size());
  Decoder d(Model::qt128c2x);
  SafetyMonitor m;
  PacketInfo info;
  for (const auto& p : packets) {
    ASSERT_EQ(d.validate(view(p), info), Error::ok);
    m.observe(info.safety, info.time_ns);
  }
  const SafetyCounts& c = m.counts();
  EXPECT_EQ(c.packets, packets.size());
  EXPECT_EQ(c.states[static_cast<std::size_t>(LidarState::init)], init);
  EXPECT_EQ(c.current_fault + c.past_fault + c.reserved_fault_type, with_fault);
  EXPECT_EQ(c.last_fault_id, 0);
  EXPECT_EQ(c.counter_stalls, 0u);
}

// The built stream (safety_stream.h): each state, each fault type, one stall and one hold of
// exactly the longest span that is not a stall, decoded (CRC2 re-sealed) and monitored.
TEST(Safety, BuiltStreamCountsStatesFaultsAndOneStall) {
  const SafetyStream s = build_safety_stream();
  ASSERT_FALSE(s.packets.empty());
  const SafetyExpect& e = s.expect;
  // The construction: a hold of more than 20 ms and one of at most 20 ms (about 180 packets of
  // 111 us); expected one stall, and every state present.
  EXPECT_GT(e.longest_hold_ns, kStallLimitNs);
  EXPECT_LE(e.short_hold_ns, kStallLimitNs);
  EXPECT_GT(e.short_hold_ns, kStallLimitNs - 200000);  // within two packets of the limit
  EXPECT_EQ(e.stalls, 1u);
  for (std::uint64_t n : e.states) EXPECT_GT(n, 0u);
  EXPECT_GT(e.current, 0u);
  EXPECT_GT(e.past, 0u);
  EXPECT_GT(e.reserved, 0u);

  Decoder d(Model::qt128c2x);
  SafetyMonitor m;
  PacketInfo info;
  unsigned began = 0;
  for (const auto& p : s.packets) {
    ASSERT_EQ(d.validate(view(p), info), Error::ok);
    began += m.observe(info.safety, info.time_ns) ? 1u : 0u;
  }
  const SafetyCounts& c = m.counts();
  EXPECT_EQ(c.packets, e.packets);
  for (std::size_t st = 0; st < 8; ++st) EXPECT_EQ(c.states[st], e.states[st]) << lidar_state_name(static_cast<std::uint8_t>(st));
  EXPECT_EQ(c.current_fault, e.current);
  EXPECT_EQ(c.past_fault, e.past);
  EXPECT_EQ(c.reserved_fault_type, e.reserved);
  EXPECT_EQ(c.last_fault_code, e.last_code);
  EXPECT_EQ(c.last_fault_id, e.last_id);
  EXPECT_EQ(c.last_fault_total, e.last_total);
  EXPECT_EQ(c.counter_stalls, e.stalls);
  EXPECT_EQ(began, e.stalls);

  // count_safety on a second set of counters, with observe()'s answers, sums the same.
  SafetyMonitor m2;
  SafetyCounts total;
  for (const auto& p : s.packets) {
    ASSERT_EQ(d.validate(view(p), info), Error::ok);
    count_safety(total, info.safety, m2.observe(info.safety, info.time_ns));
  }
  EXPECT_EQ(total.packets, c.packets);
  EXPECT_EQ(total.counter_stalls, c.counter_stalls);
  EXPECT_EQ(total.states, c.states);
  EXPECT_EQ(total.last_fault_code, c.last_fault_code);
}

// ---- The stall rule on hand-set times: 100 us between packets unless said otherwise ----

TEST(Safety, StallIsMoreThan20msAndCountsOnce) {
  SafetyMonitor m;
  std::int64_t t = 1000 * kMs;
  // 201 packets 100 us apart with one value: the last is exactly 20 ms after the first: no stall.
  EXPECT_EQ(feed(m, t, 100000, 201, 3), 0u);
  EXPECT_FALSE(m.stalled());
  // The next is 20.1 ms after the first: a stall, counted at that packet and only there.
  EXPECT_EQ(feed(m, t, 100000, 1, 3), 1u);
  EXPECT_TRUE(m.stalled());
  EXPECT_EQ(feed(m, t, 100000, 1000, 3), 0u);  // 100 ms more of the same stall
  EXPECT_EQ(m.counts().counter_stalls, 1u);
  // The value changes (by 3: jumps are not flagged): the stall ends; a second stall counts again.
  EXPECT_EQ(feed(m, t, 100000, 1, 6), 0u);
  EXPECT_FALSE(m.stalled());
  EXPECT_EQ(feed(m, t, 100000, 300, 6), 1u);
  EXPECT_EQ(m.counts().counter_stalls, 2u);
  EXPECT_EQ(m.counts().packets, 201u + 1 + 1000 + 1 + 300);
}

TEST(Safety, NormalUpdatesNeverStall) {
  // A value every 5 ms (the manual's period) for 10 s, stepping by 1 or 3.
  SafetyMonitor m;
  std::int64_t t = 0;
  std::uint8_t v = 0;
  for (int i = 0; i < 2000; ++i) {
    EXPECT_EQ(feed(m, t, 111000, 45, v), 0u);
    v = static_cast<std::uint8_t>((v + (i % 7 == 0 ? 3 : 1)) % 8);
  }
  EXPECT_EQ(m.counts().counter_stalls, 0u);
}

TEST(Safety, LostPacketsWithin20msDoNotHideAStall) {
  // Packets lost in gaps of 5 ms (< 20 ms: too short for the counter to wrap round): the value
  // held for 25 ms across them is a stall.
  SafetyMonitor m;
  std::int64_t t = 0;
  EXPECT_EQ(feed(m, t, 5 * kMs, 5, 2), 0u);  // 0, 5, 10, 15, 20 ms
  EXPECT_EQ(feed(m, t, 5 * kMs, 1, 2), 1u);  // 25 ms
}

TEST(Safety, GapLongerThan20msIsNotAStall) {
  // Lost packets (or a pause) longer than 20 ms: the counter may have wrapped round; the stall
  // clock restarts at the packet after the gap.
  SafetyMonitor m;
  std::int64_t t = 0;
  EXPECT_EQ(feed(m, t, 100000, 100, 4), 0u);
  t += 50 * kMs;
  EXPECT_EQ(feed(m, t, 100000, 201, 4), 0u);  // 20 ms after the gap: not yet
  EXPECT_EQ(feed(m, t, 100000, 1, 4), 1u);    // 20.1 ms after the gap
  EXPECT_EQ(m.counts().counter_stalls, 1u);
}

TEST(Safety, StallAcrossAGapCountsOnce) {
  SafetyMonitor m;
  std::int64_t t = 0;
  EXPECT_EQ(feed(m, t, 100000, 300, 5), 1u);
  t += 50 * kMs;                                // packets lost in the middle of the stall
  EXPECT_EQ(feed(m, t, 100000, 300, 5), 0u);   // the same value: the same stall
  EXPECT_TRUE(m.stalled());
  EXPECT_EQ(m.counts().counter_stalls, 1u);
}

TEST(Safety, TimeGoingBackwardsRestartsTheClock) {
  SafetyMonitor m;
  std::int64_t t = 500 * kMs;
  EXPECT_EQ(feed(m, t, 100000, 150, 1), 0u);  // 14.9 ms of one value
  t -= 300 * kMs;                              // a clock step back (or a restarted stream)
  EXPECT_EQ(feed(m, t, 100000, 150, 1), 0u);  // 14.9 ms more: 29.8 ms in all, but not measurable
  EXPECT_EQ(feed(m, t, 100000, 60, 1), 1u);   // 20.9 ms since the step: a stall
  // A late packet (a little older than the last) with the same value restarts the clock too;
  // with another value it is a change.
  SafetyMonitor late;
  std::int64_t u = 0;
  EXPECT_EQ(feed(late, u, 100000, 150, 2), 0u);
  std::int64_t back = u - 5 * 100000;
  EXPECT_EQ(feed(late, back, 100000, 1, 2), 0u);
  EXPECT_EQ(feed(late, u, 100000, 150, 2), 0u);  // 29.9 ms after the first, 15.4 ms after the late one
  EXPECT_EQ(late.counts().counter_stalls, 0u);
}

TEST(Safety, StreamRestartFromZero) {
  // A sensor restart: the time jumps (either way) and the counter starts again from 0.
  SafetyMonitor m;
  std::int64_t t = 2000 * kMs;
  EXPECT_EQ(feed(m, t, 100000, 150, 0), 0u);
  t = 100 * kMs;
  EXPECT_EQ(feed(m, t, 100000, 100, 0), 0u);
  EXPECT_EQ(m.counts().counter_stalls, 0u);
  m.reset();
  EXPECT_EQ(m.counts().packets, 0u);
  EXPECT_FALSE(m.stalled());
}

TEST(Safety, AbsentSectionIsIgnored) {
  SafetyMonitor m;
  FunctionalSafety none;  // present == false: flags bit 2 clear, or not a QT128
  for (int i = 0; i < 1000; ++i) EXPECT_FALSE(m.observe(none, i * 100000));
  EXPECT_EQ(m.counts().packets, 0u);
  SafetyCounts c;
  count_safety(c, none, true);
  EXPECT_EQ(c.packets, 0u);
  EXPECT_EQ(c.counter_stalls, 0u);
}

TEST(Safety, LastFaultIsTheLastCurrentOrPastFault) {
  SafetyCounts c;
  FunctionalSafety f = section(2, 0, kFaultCurrent);
  f.total_fault_codes = 3;
  f.fault_code_id = 2;
  f.fault_code = 0x0123;
  count_safety(c, f, false);
  f = section(2, 1, kFaultPast);
  f.total_fault_codes = 3;
  f.fault_code_id = 3;
  f.fault_code = 0x0456;
  count_safety(c, f, false);
  f = section(1, 2, 0);  // no fault: keeps the last one
  f.fault_code = 0x0789;
  count_safety(c, f, false);
  f = section(1, 3, 3);  // b-11, not defined: counted, not a fault code
  f.fault_code = 0x0ABC;
  count_safety(c, f, false);
  EXPECT_EQ(c.packets, 4u);
  EXPECT_EQ(c.current_fault, 1u);
  EXPECT_EQ(c.past_fault, 1u);
  EXPECT_EQ(c.reserved_fault_type, 1u);
  EXPECT_EQ(c.last_fault_code, 0x0456);
  EXPECT_EQ(c.last_fault_id, 3);
  EXPECT_EQ(c.last_fault_total, 3);
  EXPECT_EQ(c.states[2], 2u);
  EXPECT_EQ(c.states[1], 2u);
}

// ---- The Pandars' status fields ----

// The high-temperature shutdown flag (tail byte 5) set in some of the bundled packets.
TEST(SensorStatus, HighTemperatureFlag) {
  struct Case {
    const char* file;
    Model model;
    std::size_t flag;  // offset: the 22-byte tail starts after the body (Pandar64: 8 + 6 x 194)
  };
  for (const Case& k : {Case{"pandar64_dual.pcap", Model::pandar64, 8 + 6 * 194 + 5},
                        Case{"pandar40p_dual.pcap", Model::pandar40p, 10 * 124 + 5}}) {
    auto packets = pcap_payloads(k.file);
    ASSERT_FALSE(packets.empty()) << k.file;
    std::uint64_t set = 0;
    for (std::size_t i = 0; i < packets.size(); ++i) {
      ASSERT_EQ(packets[i][k.flag], 0) << k.file;  // normal operation in the capture
      if (i % 7 == 3) {
        packets[i][k.flag] = 0x01;
        ++set;
      }
    }
    Decoder d(k.model);
    Stats s{};
    PacketInfo info;
    for (const auto& p : packets) {
      ASSERT_EQ(d.validate(view(p), info), Error::ok) << k.file;
      count_status(s, info);
    }
    EXPECT_EQ(s.high_temperature, set) << k.file;
  }
}

// GPS packets of both layouts, built from the manuals: locked, PPS unlocked, NMEA unlocked
// (status NUL), void position ('V', and GPGGA fix quality '0').
TEST(SensorStatus, GpsLock) {
  struct Case {
    bool p40;
    std::uint8_t status, pps;
    bool unlocked, position_invalid;
  };
  const Case cases[] = {
      {false, 'A', 1, false, false}, {false, 'A', 0, true, false}, {false, 0, 1, true, false},
      {false, 0, 0, true, false},    {false, 'V', 1, false, true}, {false, '0', 1, false, true},
      {false, '1', 1, false, false}, {true, 'A', 1, false, false}, {true, 'A', 0, true, false},
      {true, 0, 1, true, false},     {true, 'V', 0, true, true},
  };
  Stats s{};
  std::uint64_t unlocked = 0, invalid = 0;
  for (const Case& c : cases) {
    GpsBytes p = c.p40 ? gps_rmc40() : gps_rmc64();
    p[506] = c.status;
    p[507] = c.pps;
    GpsPacket g;
    ASSERT_EQ(parse_gps_packet(ByteView{p.data(), p.size()}, g), Error::ok);
    EXPECT_EQ(gps_unlocked(g), c.unlocked) << int(c.status) << " " << int(c.pps);
    EXPECT_EQ(gps_position_invalid(g), c.position_invalid) << int(c.status);
    count_gps(s, g);
    unlocked += c.unlocked;
    invalid += c.position_invalid;
  }
  EXPECT_EQ(s.gps_packets, std::size(cases));
  EXPECT_EQ(s.gps_unlocked, unlocked);
  EXPECT_EQ(s.gps_position_invalid, invalid);
}

}  // namespace
