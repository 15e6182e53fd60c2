// HealthMonitor: loss without a UDP sequence, reordering, frozen, backward, stepped and virtual
// clocks, on streams built from the bundled captures. Every expected count is what the test did to
// the stream (the packets it dropped, moved, froze or redated), or what the captures' own sequence
// numbers say, read by the test; never a value printed by the monitor.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "hesai/decoder.h"
#include "hesai/health.h"
#include "hesai/sequence.h"
#include "packet_builder.h"
#include "test_support.h"

namespace {

using hesai::Error;
using hesai::HealthCounts;
using hesai::HealthMonitor;
using hesai::Model;
using hesai::Rotation;
using hesai_test::pcap_payloads;
using hesai_test::view;
using Packets = std::vector<std::vector<std::uint8_t>>;

// Pandar64 tail (manual 3.1.2.3): at 1172, motor speed u16 @8, timestamp u32 @10, date-time 6 @16
// (year, month, day, hour, minute, second); the UDP sequence in the 4 bytes after the tail.
constexpr std::size_t kP64Tail = 1172;
// Pandar40P tail (Pandar40 manual 3.1.2): timestamp u32 @1250, date-time @1256.
constexpr std::size_t kP40Timestamp = 1250;
constexpr std::size_t kP40Date = 1256;

// The packets of the bundled Pandar64 capture cut to 1194 bytes: the same packets with the UDP
// sequence off, the unit's default (Pandar64 manual, Chapter 3).
Packets pandar64_without_sequence() {
  Packets out = pcap_payloads("pandar64_dual.pcap");
  for (auto& p : out) p.resize(1194);
  return out;
}

// Validates every packet (each must pass) and feeds the monitor in order.
HealthCounts run(const Packets& packets, Model model, Rotation rotation = Rotation::clockwise) {
  hesai::Decoder d(model);
  HealthMonitor m;
  m.set_rotation(rotation);
  for (const auto& p : packets) {
    hesai::PacketInfo info;
    EXPECT_EQ(d.validate(view(p), info), Error::ok);
    m.observe(info);
  }
  return m.counts();
}

// Removes packets [first, first + n).
void drop(Packets& p, std::size_t first, std::size_t n) {
  p.erase(p.begin() + static_cast<long>(first), p.begin() + static_cast<long>(first + n));
}

// The first index whose first block azimuth is below its predecessor's by more than half a turn
// (a wrap through 0 clockwise), read from the bytes.
std::size_t first_wrap(const Packets& p, Model model, std::size_t from = 1) {
  for (std::size_t i = from; i < p.size(); ++i)
    if (hesai_test::block_azimuths(p[i - 1], model)[0] > hesai_test::block_azimuths(p[i], model)[0] + 18000) return i;
  ADD_FAILURE() << "no wrap";
  return 0;
}

void expect_clean(const HealthCounts& c) {
  EXPECT_EQ(c.reordered, 0u);
  EXPECT_EQ(c.duplicates, 0u);
  EXPECT_EQ(c.time_stalls, 0u);
  EXPECT_EQ(c.time_virtual, 0u);
  EXPECT_EQ(c.time_jumps, 0u);
}

static_assert([] {
  std::uint64_t c = UINT64_MAX - 1;
  hesai::saturating_add(c, 5);
  return c == UINT64_MAX;
}(), "a counter stops at its largest value");

TEST(Health, BundledCapturesAsRecorded) {
  // Every bundled capture unchanged: the monitor's loss is what the UDP sequence numbers say (the
  // XT32M2X capture's three gaps; none elsewhere; the Pandar40P has no sequence and no gap by its
  // 1439 packets over its rotations), and no clock fault.
  const struct {
    const char* file;
    Model model;
  } captures[] = {
      {"pandar40p_dual.pcap", Model::pandar40p}, {"pandar64_dual.pcap", Model::pandar64},
      {"qt128c2x_dual.pcap", Model::qt128c2x},   {"pandar_qt64.pcap", Model::pandar_qt64},
      {"pandar_xt16.pcap", Model::pandar_xt16},  {"pandar_xt32.pcap", Model::pandar_xt32},
      {"pandar_xt32m2x.pcap", Model::pandar_xt32m2x},
  };
  for (const auto& c : captures) {
    SCOPED_TRACE(c.file);
    const Packets packets = pcap_payloads(c.file);
    std::uint64_t gaps = 0;  // numbers skipped, from the sequence field as the test reads it
    hesai::Decoder d(c.model);
    std::uint32_t previous = 0;
    for (std::size_t i = 0; i < packets.size(); ++i) {
      hesai::PacketInfo info;
      ASSERT_EQ(d.validate(view(packets[i]), info), Error::ok);
      if (info.has_sequence && i > 0) gaps += info.sequence - previous - 1;
      previous = info.sequence;
    }
    const HealthCounts h = run(packets, c.model);
    EXPECT_EQ(h.packets, packets.size());
    EXPECT_EQ(h.lost, gaps);
    expect_clean(h);
  }
}

TEST(Health, Pandar64WithoutSequenceRunAcrossTheWrap) {
  // 100 packets dropped across the wrap through 0 (50 before it, 50 after), 20 single packets
  // dropped one in every 7 elsewhere, and 3 in a row at the start of the second wrap.
  Packets p = pandar64_without_sequence();
  const std::size_t wrap2 = first_wrap(p, Model::pandar64, first_wrap(p, Model::pandar64) + 1);
  drop(p, wrap2, 3);
  for (std::size_t i = 0; i < 20; ++i) drop(p, 900 + 6 * i, 1);  // after each drop the next index is 7 on
  const std::size_t wrap = first_wrap(p, Model::pandar64);
  ASSERT_GT(wrap, 50u);
  drop(p, wrap - 50, 100);
  const HealthCounts h = run(p, Model::pandar64);
  EXPECT_EQ(h.lost, 100u + 20u + 3u);
  expect_clean(h);
}

TEST(Health, CounterClockwisePandar64) {
  // The same drops on the capture mirrored (a -> 36000 - a) and watched counter-clockwise.
  Packets p = pandar64_without_sequence();
  for (auto& q : p) q = hesai_test::counterclockwise_copy(q, Model::pandar64);
  std::size_t wrap = 0;  // counter-clockwise, the azimuth wraps from below 90 to above 270 degrees
  for (std::size_t i = 1; i < p.size() && wrap == 0; ++i)
    if (hesai_test::block_azimuths(p[i], Model::pandar64)[0] > hesai_test::block_azimuths(p[i - 1], Model::pandar64)[0] + 18000)
      wrap = i;
  ASSERT_GT(wrap, 50u);
  drop(p, wrap - 50, 100);
  drop(p, 1500, 7);
  const HealthCounts h = run(p, Model::pandar64, Rotation::counterclockwise);
  EXPECT_EQ(h.lost, 107u);
  expect_clean(h);
}

TEST(Health, AgreesWithTheUdpSequenceOnEveryCaptureThatHasOne) {
  // The two methods on the same streams: packets dropped by the test (every 40th from 100, and 37
  // in a row at 1000), plus the capture's own gaps. Both must give the count the test reads off the
  // sequence numbers of the packets it kept.
  const struct {
    const char* file;
    Model model;
  } captures[] = {
      {"pandar64_dual.pcap", Model::pandar64},   {"qt128c2x_dual.pcap", Model::qt128c2x},
      {"pandar_qt64.pcap", Model::pandar_qt64},  {"pandar_xt16.pcap", Model::pandar_xt16},
      {"pandar_xt32.pcap", Model::pandar_xt32},  {"pandar_xt32m2x.pcap", Model::pandar_xt32m2x},
  };
  for (const auto& c : captures) {
    SCOPED_TRACE(c.file);
    Packets p = pcap_payloads(c.file);
    drop(p, 1000, 37);
    for (std::size_t i = 100; i < 900; i += 39) drop(p, i, 1);
    hesai::Decoder d(c.model);
    HealthMonitor monitor;
    hesai::SequenceTracker tracker;
    std::uint64_t expected = 0;
    std::uint32_t previous = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      hesai::PacketInfo info;
      ASSERT_EQ(d.validate(view(p[i]), info), Error::ok);
      ASSERT_TRUE(info.has_sequence);
      if (i > 0) expected += info.sequence - previous - 1;
      previous = info.sequence;
      const std::uint32_t by_sequence = tracker.observe(info.sequence);
      EXPECT_EQ(monitor.observe(info), by_sequence) << "packet " << i;  // the same gap before each packet
    }
    EXPECT_GE(expected, 37u + 20u);
    EXPECT_EQ(tracker.counts().lost, expected);
    EXPECT_EQ(monitor.counts().lost, expected);
    expect_clean(monitor.counts());
  }
}

TEST(Health, Pandar40PGapLongerThanARotationCountsByTime) {
  // 360 packets make a rotation at 600 rpm (1 800 firings, 5 a dual-return packet). A gap of 500
  // (1.4 rotations) and one of 380 (the block azimuth alone would see 20 of the 380).
  Packets p = pcap_payloads("pandar40p_dual.pcap");
  drop(p, 900, 380);
  drop(p, 200, 500);
  const HealthCounts h = run(p, Model::pandar40p);
  EXPECT_EQ(h.lost, 880u);
  expect_clean(h);
}

TEST(Health, Pandar40PGapOfTwoAndAHalfRotations) {
  Packets p = pcap_payloads("pandar40p_dual.pcap");
  drop(p, 100, 900);
  const HealthCounts h = run(p, Model::pandar40p);
  EXPECT_EQ(h.lost, 900u);
  expect_clean(h);
}

TEST(Health, LatePacketsAreReorderedNotLost) {
  // Packets 500..509 taken out; 503 and 505 put back after 515 (late), 700 swapped with 701, 1200
  // moved 5 places later, and 1500 sent twice: lost 10 - 2 = 8, reordered 4 (503, 505, 700, 1200),
  // one duplicate, no time stall (each late packet is earlier in time and behind in azimuth).
  const Packets original = pandar64_without_sequence();
  Packets p;
  for (std::size_t i = 0; i < original.size(); ++i) {
    if (i >= 500 && i < 510) continue;
    if (i == 700 || i == 1200) continue;
    p.push_back(original[i]);
    if (i == 515) {
      p.push_back(original[503]);
      p.push_back(original[505]);
    }
    if (i == 701) p.push_back(original[700]);
    if (i == 1205) p.push_back(original[1200]);
    if (i == 1500) p.push_back(original[1500]);
  }
  const HealthCounts h = run(p, Model::pandar64);
  EXPECT_EQ(h.lost, 8u);
  EXPECT_EQ(h.reordered, 4u);
  EXPECT_EQ(h.duplicates, 1u);
  EXPECT_EQ(h.time_stalls, 0u);
  EXPECT_EQ(h.time_jumps, 0u);
}

// Copies packet `from`'s timestamp and date-time into packet `to` (Pandar64).
void copy_time(Packets& p, std::size_t from, std::size_t to) {
  for (std::size_t b = 10; b < 14; ++b) p[to][kP64Tail + b] = p[from][kP64Tail + b];
  for (std::size_t b = 16; b < 22; ++b) p[to][kP64Tail + b] = p[from][kP64Tail + b];
}

TEST(Health, FrozenAndBackwardTimestampsAreStalls) {
  // Packets 301..309 carry packet 300's time (frozen: 9 stalls); packet 800 carries packet 770's
  // (5 ms back: 1 stall); packets 1200..1204 carry packet 1100's (5 stalls). Time resumes after each,
  // so nothing is lost and no clock stepped; 10 packets dropped right after the first freeze still
  // count, by the azimuth and by the time of packet 300.
  Packets p = pandar64_without_sequence();
  for (std::size_t i = 301; i <= 309; ++i) copy_time(p, 300, i);
  copy_time(p, 770, 800);
  for (std::size_t i = 1200; i <= 1204; ++i) copy_time(p, 1100, i);
  drop(p, 310, 10);
  const HealthCounts h = run(p, Model::pandar64);
  EXPECT_EQ(h.time_stalls, 9u + 1u + 5u);
  EXPECT_EQ(h.lost, 10u);
  EXPECT_EQ(h.time_jumps, 0u);
  EXPECT_EQ(h.reordered, 0u);
  EXPECT_EQ(h.duplicates, 0u);
}

TEST(Health, YearTwoThousandIsTheVirtualClock) {
  // Pandar64: year byte 0 (2000 + byte, the manual's reading); QT128C2X: tm_year byte 100 (1900 +
  // byte), CRCs resealed. Every packet counts; nothing else changes.
  Packets p = pandar64_without_sequence();
  for (auto& q : p) q[kP64Tail + 16] = 0;
  HealthCounts h = run(p, Model::pandar64);
  EXPECT_EQ(h.time_virtual, p.size());
  EXPECT_EQ(h.lost, 0u);
  EXPECT_EQ(h.time_stalls, 0u);

  Packets q = pcap_payloads("qt128c2x_dual.pcap");
  for (auto& x : q) {
    x[hesai_test::qt128_offsets(x).tail + 15] = 100;
    hesai_test::qt128_seal(x);
  }
  h = run(q, Model::qt128c2x);
  EXPECT_EQ(h.time_virtual, q.size());
  EXPECT_EQ(h.lost, 0u);
  EXPECT_EQ(h.time_stalls, 0u);

  // One year later (byte 1, 2001) is no longer the virtual date.
  for (auto& x : p) x[kP64Tail + 16] = 1;
  EXPECT_EQ(run(p, Model::pandar64).time_virtual, 0u);
}

TEST(Health, ClockStepIsAJumpNotALoss) {
  // From packet 1000 on, every packet an hour later (the hour byte + 1): one time jump, and the 6
  // packets dropped across the step still count, by the azimuth.
  Packets p = pandar64_without_sequence();
  for (std::size_t i = 1000; i < p.size(); ++i) ++p[i][kP64Tail + 19];
  drop(p, 997, 6);
  const HealthCounts h = run(p, Model::pandar64);
  EXPECT_EQ(h.time_jumps, 1u);
  EXPECT_EQ(h.lost, 6u);
  EXPECT_EQ(h.time_stalls, 0u);
}

TEST(Health, ZeroSpinRateIsNotDividedByLossesByTime) {
  // Packets 100..120 report 0 rpm; 105..107 dropped among them: counted by time alone (3).
  // Packet 500 reports 1200 rpm, a jump from ~600, after 497..499 dropped: by time (3).
  Packets p = pandar64_without_sequence();
  for (std::size_t i = 100; i <= 120; ++i) hesai::store_le16(&p[i][kP64Tail + 8], 0);
  hesai::store_le16(&p[500][kP64Tail + 8], 1200);
  drop(p, 497, 3);
  drop(p, 105, 3);
  const HealthCounts h = run(p, Model::pandar64);
  EXPECT_EQ(h.lost, 6u);
  expect_clean(h);
}

TEST(Health, ZeroSpinRateWithAFrozenClockCountsNoLoss) {
  // 0 rpm and a frozen clock: neither the azimuth nor the time can say anything; the packets are
  // stalls, one ahead each, nothing lost. Packets 200..209 report 0 rpm and packet 199's time.
  Packets p = pandar64_without_sequence();
  for (std::size_t i = 200; i <= 209; ++i) {
    hesai::store_le16(&p[i][kP64Tail + 8], 0);
    copy_time(p, 199, i);
  }
  const HealthCounts h = run(p, Model::pandar64);
  EXPECT_EQ(h.time_stalls, 10u);
  EXPECT_EQ(h.lost, 0u);
}

TEST(Health, Pandar40PFrozenTime) {
  // Pandar40P packets 400..419 carry packet 399's timestamp and date: 20 stalls, nothing lost.
  Packets p = pcap_payloads("pandar40p_dual.pcap");
  for (std::size_t i = 400; i < 420; ++i) {
    for (std::size_t b = 0; b < 4; ++b) p[i][kP40Timestamp + b] = p[399][kP40Timestamp + b];
    for (std::size_t b = 0; b < 6; ++b) p[i][kP40Date + b] = p[399][kP40Date + b];
  }
  const HealthCounts h = run(p, Model::pandar40p);
  EXPECT_EQ(h.time_stalls, 20u);
  EXPECT_EQ(h.lost, 0u);
  EXPECT_EQ(h.time_jumps, 0u);
}

TEST(Health, ResetForgetsEverything) {
  const Packets p = pandar64_without_sequence();
  hesai::Decoder d(Model::pandar64);
  HealthMonitor m;
  hesai::PacketInfo info;
  ASSERT_EQ(d.validate(view(p[0]), info), Error::ok);
  m.observe(info);
  ASSERT_EQ(d.validate(view(p[10]), info), Error::ok);
  EXPECT_EQ(m.observe(info), 9u);
  m.reset();
  EXPECT_EQ(m.counts().packets, 0u);
  EXPECT_EQ(m.observe(info), 0u);  // a first packet again
  EXPECT_EQ(m.counts().lost, 0u);
}

TEST(Health, AzimuthFovIsNotLoss) {
  // A sequence-less Pandar64 whose packets with a first block azimuth in [90, 150) degrees are
  // missing on every rotation (an FOV set on the unit), and 5 packets dropped near 270 degrees once:
  // lost 5, and the FOV from the last azimuth before 90 to the first at or after 150.
  const Packets original = pandar64_without_sequence();
  Packets p;
  std::uint16_t before = 0, after = 0;  // the edges as the test reads them, at the last occurrence
  bool in_gap = false;
  std::size_t dropped_near_270 = 0;
  for (std::size_t i = 0; i < original.size(); ++i) {
    const std::uint16_t az = hesai_test::block_azimuths(original[i], Model::pandar64)[0];
    if (az >= 9000 && az < 15000) {
      if (!in_gap && !p.empty()) before = hesai_test::block_azimuths(p.back(), Model::pandar64)[0];
      in_gap = true;
      continue;
    }
    if (in_gap) after = az;
    in_gap = false;
    if (i > 1200 && az >= 27000 && dropped_near_270 < 5) {
      ++dropped_near_270;
      continue;
    }
    p.push_back(original[i]);
  }
  ASSERT_EQ(dropped_near_270, 5u);
  hesai::Decoder d(Model::pandar64);
  HealthMonitor m;
  for (const auto& q : p) {
    hesai::PacketInfo info;
    ASSERT_EQ(d.validate(view(q), info), Error::ok);
    m.observe(info);
  }
  const HealthCounts& h = m.counts();
  EXPECT_EQ(h.lost, 5u);
  ASSERT_TRUE(h.fov_gap);
  EXPECT_EQ(h.fov_gap_from, before);
  EXPECT_EQ(h.fov_gap_to, after);
  EXPECT_LT(before, 9000);
  EXPECT_GE(after, 15000);
  expect_clean(h);

  // The same gap once only (the first rotation's packets): counted as lost, no FOV.
  Packets once;
  std::uint64_t missing = 0;
  for (std::size_t i = 0; i < 600; ++i) {
    const std::uint16_t az = hesai_test::block_azimuths(original[i], Model::pandar64)[0];
    if (az >= 9000 && az < 15000) ++missing;
    else once.push_back(original[i]);
  }
  ASSERT_GT(missing, 90u);
  const HealthCounts h1 = run(once, Model::pandar64);
  EXPECT_EQ(h1.lost, missing);
  EXPECT_FALSE(h1.fov_gap);
}

// ---- From the units: blockage markers, repeated returns, distances beyond the rated range ----

// The test's own reading of the layouts (offsets typed in from the manuals): where unit `u`
// (0-based) of block `b` starts, and the unit size. Pandar40P (manual 3.1.2): blocks of 124 bytes,
// units of 3 after a 2-byte preamble and the azimuth; Pandar64 (3.1.2): 8-byte header, blocks of
// 194, units of 3 after the azimuth; QT128C2X with flags 0x1D (3.1.2): 12-byte header, blocks of
// 2 + 128 x 4 bytes (a confidence byte a unit).
struct UnitLayout {
  std::size_t first, block, unit, units, blocks;
  std::size_t at(std::size_t b, std::size_t u) const { return first + b * block + unit * u; }
};
UnitLayout unit_layout(Model m) {
  switch (m) {
    case Model::pandar64: return {8 + 2, 194, 3, 64, 6};
    case Model::qt128c2x: return {12 + 2, 514, 4, 128, 2};
    default: return {4, 124, 3, 40, 10};  // Pandar40P
  }
}

// Decodes every packet with a UnitScan into a monitor; the points too.
struct UnitRun {
  HealthCounts counts;
  std::uint64_t points = 0;
};
UnitRun run_units(const Packets& packets, Model model) {
  hesai::Decoder d(model);
  HealthMonitor m;
  hesai::PacketPoints pts;
  UnitRun r;
  for (const auto& p : packets) {
    hesai::PacketInfo info;
    hesai::UnitScan scan;
    EXPECT_EQ(d.decode(view(p), info, pts, scan), Error::ok);
    m.observe(info);
    m.observe_units(scan);
    r.points += pts.count;
  }
  r.counts = m.counts();
  return r;
}

TEST(HealthUnits, DuplicateReturnsCountedFromTheRawBytes) {
  // Dual-return captures: the blocks of a firing are 2i and 2i + 1; a pair repeats when both
  // distances are equal and at least the smallest kept (1; 2 on the QT128C2X, whose 1 is a marker)
  // and the reflectivities are equal. Counted here from the bytes.
  const struct {
    const char* file;
    Model model;
    std::uint16_t smallest;
  } captures[] = {{"pandar40p_dual.pcap", Model::pandar40p, 1},
                  {"pandar64_dual.pcap", Model::pandar64, 1},
                  {"qt128c2x_dual.pcap", Model::qt128c2x, 2}};
  for (const auto& c : captures) {
    SCOPED_TRACE(c.file);
    const Packets p = pcap_payloads(c.file);
    const UnitLayout l = unit_layout(c.model);
    std::uint64_t expected = 0;
    for (const auto& q : p)
      for (std::size_t b = 0; b + 1 < l.blocks; b += 2)
        for (std::size_t u = 0; u < l.units; ++u) {
          const std::size_t a0 = l.at(b, u), a1 = l.at(b + 1, u);
          const std::uint16_t d0 = hesai::load_le16(&q[a0]);
          expected += d0 >= c.smallest && d0 == hesai::load_le16(&q[a1]) && q[a0 + 2] == q[a1 + 2];
        }
    EXPECT_GT(expected, 0u);
    const UnitRun r = run_units(p, c.model);
    EXPECT_EQ(r.counts.duplicate_returns, expected);
    EXPECT_EQ(r.counts.blockage_units, 0u);      // no capture holds a 1
    EXPECT_EQ(r.counts.beyond_rated_range, 0u);  // nor a distance beyond the rated range (below)
  }
}

TEST(HealthUnits, Qt128BlockageMarkersByChannel) {
  // Distance 1 written into units of channels that fire in both sequences (65..128: the manual's
  // banks rest 1..64), CRCs resealed: channel 70 in both blocks of packets 10..14 (10 units) and
  // channel 100 in block 1 of packets 20..22 (3 units). Each was a point or not before: the points
  // fall by exactly those that were.
  Packets p = pcap_payloads("qt128c2x_dual.pcap");
  const UnitLayout l = unit_layout(Model::qt128c2x);
  std::uint64_t were_points = 0;
  auto mark = [&](std::size_t packet, std::size_t block, std::size_t channel) {
    const std::size_t at = l.at(block, channel - 1);
    were_points += hesai::load_le16(&p[packet][at]) >= 2;
    hesai::store_le16(&p[packet][at], 1);
  };
  for (std::size_t i = 10; i < 15; ++i) {
    mark(i, 0, 70);
    mark(i, 1, 70);
  }
  for (std::size_t i = 20; i < 23; ++i) mark(i, 0, 100);
  for (std::size_t i = 10; i < 23; ++i) hesai_test::qt128_seal(p[i]);
  const UnitRun before = run_units(pcap_payloads("qt128c2x_dual.pcap"), Model::qt128c2x);
  const UnitRun r = run_units(p, Model::qt128c2x);
  EXPECT_EQ(r.counts.blockage_units, 13u);
  for (std::size_t ch = 0; ch < hesai::kMaxChannels; ++ch)
    EXPECT_EQ(r.counts.blockage_by_channel[ch], ch == 69 ? 10u : ch == 99 ? 3u : 0u) << "channel " << ch + 1;
  EXPECT_EQ(r.points, before.points - were_points);
}

TEST(HealthUnits, BeyondTheRatedRange) {
  // Pandar64 (rated 200 m, distance unit 4 mm, header byte 5): raw 50 001 (200.004 m) in 5 units,
  // 50 000 (200 m exactly, not beyond) in 3. QT128C2X (50 m): raw 12 501 in 4 units of channels
  // 65..128, 12 500 in 2; resealed. The Pandar40P (200 m, unit 4 mm): 50 001 in 2 units.
  Packets p64 = pandar64_without_sequence();
  ASSERT_EQ(p64[0][5], 4);
  const UnitLayout l64 = unit_layout(Model::pandar64);
  for (std::size_t i = 0; i < 5; ++i) hesai::store_le16(&p64[100 + i][l64.at(i, 10)], 50001);
  for (std::size_t i = 0; i < 3; ++i) hesai::store_le16(&p64[200 + i][l64.at(i, 20)], 50000);
  EXPECT_EQ(run_units(p64, Model::pandar64).counts.beyond_rated_range, 5u);

  Packets qt = pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_EQ(qt[0][9], 4);
  const UnitLayout lqt = unit_layout(Model::qt128c2x);
  for (std::size_t i = 0; i < 4; ++i) hesai::store_le16(&qt[50 + i][lqt.at(i % 2, 80 + i)], 12501);
  for (std::size_t i = 0; i < 2; ++i) hesai::store_le16(&qt[60 + i][lqt.at(0, 90)], 12500);
  for (std::size_t i = 50; i < 62; ++i) hesai_test::qt128_seal(qt[i]);
  EXPECT_EQ(run_units(qt, Model::qt128c2x).counts.beyond_rated_range, 4u);

  Packets p40 = pcap_payloads("pandar40p_dual.pcap");
  const UnitLayout l40 = unit_layout(Model::pandar40p);
  hesai::store_le16(&p40[7][l40.at(3, 5)], 50001);
  hesai::store_le16(&p40[8][l40.at(9, 39)], 50001);
  EXPECT_EQ(run_units(p40, Model::pandar40p).counts.beyond_rated_range, 2u);

  // The models without a manual here are rated 0: nothing counted.
  EXPECT_EQ(hesai::rated_range_m(Model::pandar_xt32), 0);
  EXPECT_EQ(hesai::rated_range_m(Model::pandar_qt64), 0);
}

TEST(HealthUnits, ReturnsDistinctLeavesOutExactlyTheRepeatedSecondReturns) {
  // Every packet of the three dual-return captures decoded both ways: the distinct points are the
  // Returns::all points, in order, less each second-return point (odd block) whose first return
  // (the even block before, same channel) has the same distance and intensity; their number is
  // the scan's duplicate_returns.
  for (const auto& [file, model] : {std::pair<const char*, Model>{"pandar40p_dual.pcap", Model::pandar40p},
                                    {"pandar64_dual.pcap", Model::pandar64},
                                    {"qt128c2x_dual.pcap", Model::qt128c2x}}) {
    SCOPED_TRACE(file);
    hesai::Decoder d(model);
    static hesai::PacketPoints all, distinct;
    std::uint64_t left_out = 0;
    for (const auto& p : pcap_payloads(file)) {
      hesai::PacketInfo info;
      hesai::UnitScan scan_all, scan;
      ASSERT_EQ(d.decode(view(p), info, all, scan_all, hesai::Returns::all), Error::ok);
      ASSERT_EQ(d.decode(view(p), info, distinct, scan, hesai::Returns::distinct), Error::ok);
      std::vector<const hesai::Point*> expected;
      for (std::size_t i = 0; i < all.count; ++i) {
        const hesai::Point& q = all.points[i];
        bool repeated = false;
        if (q.block % 2 == 1)
          for (std::size_t j = 0; j < all.count; ++j) {
            const hesai::Point& f = all.points[j];
            if (f.block + 1 == q.block && f.channel == q.channel && f.distance_m == q.distance_m && f.intensity == q.intensity)
              repeated = true;
          }
        if (!repeated) expected.push_back(&q);
      }
      ASSERT_EQ(distinct.count, expected.size());
      EXPECT_EQ(all.count - distinct.count, scan.duplicate_returns);
      for (std::size_t i = 0; i < distinct.count; ++i) {
        EXPECT_EQ(distinct.points[i].block, expected[i]->block);
        EXPECT_EQ(distinct.points[i].channel, expected[i]->channel);
        EXPECT_EQ(distinct.points[i].x, expected[i]->x);
      }
      left_out += all.count - distinct.count;
    }
    EXPECT_GT(left_out, 0u);
  }
}

TEST(HealthUnits, ColumnsScanEqualsThePointsScan) {
  // The columns form with a UnitScan scans the same units: every field equal on every packet of
  // every capture (and the QT128C2X with blockage markers), and the same points as without a scan.
  Packets qt = pcap_payloads("qt128c2x_dual.pcap");
  hesai::store_le16(&qt[3][12 + 2 + 4 * 100], 1);
  hesai_test::qt128_seal(qt[3]);
  const std::pair<Packets, Model> streams[] = {
      {pcap_payloads("pandar40p_dual.pcap"), Model::pandar40p}, {pandar64_without_sequence(), Model::pandar64},
      {qt, Model::qt128c2x}, {pcap_payloads("pandar_xt32m2x.pcap"), Model::pandar_xt32m2x}};
  for (const auto& [packets, model] : streams) {
    SCOPED_TRACE(hesai::model_name(model));
    hesai::Decoder d(model);
    static hesai::PacketPoints pts;
    static hesai::PacketColumns<hesai::kMaxPointsPerPacket> cols;
    std::uint64_t blockage = 0;
    for (const auto& p : packets) {
      hesai::PacketInfo info;
      hesai::UnitScan a, b;
      ASSERT_EQ(d.decode(view(p), info, pts, a), Error::ok);
      ASSERT_EQ(d.decode(view(p), info, cols.columns(), cols.count, b), Error::ok);
      EXPECT_EQ(cols.count, pts.count);
      EXPECT_EQ(a.blockage_units, b.blockage_units);
      EXPECT_EQ(a.duplicate_returns, b.duplicate_returns);
      EXPECT_EQ(a.beyond_rated_range, b.beyond_rated_range);
      EXPECT_TRUE(a.blockage_by_channel == b.blockage_by_channel);
      EXPECT_TRUE(a.repeated == b.repeated);
      blockage += b.blockage_units;
    }
    EXPECT_EQ(blockage, model == Model::qt128c2x ? 1u : 0u);
  }
}

}  // namespace
