// FrameAssembler: hand-made azimuth streams; every expected count is worked out in the comments.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <vector>

#include "hesai/frame.h"

namespace {

using hesai::Error;
using hesai::FrameAssembler;
using hesai::FrameInfo;

// Feeds one packet; records the frames that close. Each block brings `points_per_block` points.
struct Feeder {
  FrameAssembler fa;
  std::vector<FrameInfo> closed;
  std::vector<std::uint16_t> opened_at;  // azimuth of each block that returned true

  void packet(std::uint64_t index, std::uint32_t lost, std::vector<std::uint16_t> azimuths,
              std::uint32_t points_per_block = 0) {
    fa.begin_packet(index, lost);
    for (std::uint16_t az : azimuths) {
      if (fa.block(az)) {
        closed.push_back(fa.last_closed());
        opened_at.push_back(az);
      }
      fa.add_points(points_per_block);
    }
  }
  void end() {
    FrameInfo f;
    if (fa.finish(f)) closed.push_back(f);
  }
};

// A Pandar40P-like stream: 10 blocks per packet, 0.2 degree (20 cdeg) apart, starting at
// 300.00 degrees, 540 packets = 5400 blocks = exactly 3 turns (1800 blocks per turn).
// Block k (0..5399) has azimuth (30000 + 20 k) mod 36000 and lies in packet k / 10.
// The last block, k = 5399, is at (30000 + 107980) mod 36000 = 29980.
void feed_three_turns(Feeder& f) {
  for (std::uint32_t p = 0; p < 540; ++p) {
    std::vector<std::uint16_t> az;
    for (std::uint32_t b = 0; b < 10; ++b) az.push_back(static_cast<std::uint16_t>((30000 + 20 * (10 * p + b)) % 36000));
    f.packet(p, 0, az, 40);
  }
  f.end();
}

TEST(FrameAssembler, ThreeTurnsCutAtZero) {
  // Cut 0: block k lands on 0 when 30000 + 20k = 36000 m, i.e. k = 300, 2100, 3900 (5700 > 5399).
  // Three crossings, each at block 0 of a packet (packets 30, 210, 390), plus finish(): 4 frames.
  Feeder f;
  feed_three_turns(f);
  ASSERT_EQ(f.closed.size(), 4u);
  EXPECT_EQ(f.opened_at, (std::vector<std::uint16_t>{0, 0, 0}));

  // Frame 1: blocks 0..299 (300 blocks, 12000 points), packets 0..29, a partial first turn.
  EXPECT_EQ(f.closed[0].id, 1u);
  EXPECT_EQ(f.closed[0].first_packet, 0u);
  EXPECT_EQ(f.closed[0].last_packet, 29u);
  EXPECT_EQ(f.closed[0].packets, 30u);
  EXPECT_EQ(f.closed[0].blocks, 300u);
  EXPECT_EQ(f.closed[0].points, 12000u);
  EXPECT_FALSE(f.closed[0].starts_at_cut);
  EXPECT_TRUE(f.closed[0].ends_at_cut);
  EXPECT_EQ(f.closed[0].first_azimuth_cdeg, 30000);
  EXPECT_EQ(f.closed[0].last_azimuth_cdeg, 35980);
  // Frames 2 and 3: whole turns, 1800 blocks, 180 packets, 72000 points.
  for (int i : {1, 2}) {
    EXPECT_EQ(f.closed[static_cast<std::size_t>(i)].id, static_cast<std::uint64_t>(i + 1));
    EXPECT_EQ(f.closed[static_cast<std::size_t>(i)].blocks, 1800u);
    EXPECT_EQ(f.closed[static_cast<std::size_t>(i)].packets, 180u);
    EXPECT_EQ(f.closed[static_cast<std::size_t>(i)].points, 72000u);
    EXPECT_TRUE(f.closed[static_cast<std::size_t>(i)].starts_at_cut);
    EXPECT_TRUE(f.closed[static_cast<std::size_t>(i)].ends_at_cut);
    EXPECT_EQ(f.closed[static_cast<std::size_t>(i)].first_azimuth_cdeg, 0);
    EXPECT_EQ(f.closed[static_cast<std::size_t>(i)].last_azimuth_cdeg, 35980);
    EXPECT_FALSE(f.closed[static_cast<std::size_t>(i)].loss);
  }
  EXPECT_EQ(f.closed[1].first_packet, 30u);
  EXPECT_EQ(f.closed[1].last_packet, 209u);
  EXPECT_EQ(f.closed[2].first_packet, 210u);
  EXPECT_EQ(f.closed[2].last_packet, 389u);
  // Frame 4, closed by finish(): blocks 3900..5399 (1500), packets 390..539 (150).
  EXPECT_EQ(f.closed[3].id, 4u);
  EXPECT_EQ(f.closed[3].first_packet, 390u);
  EXPECT_EQ(f.closed[3].last_packet, 539u);
  EXPECT_EQ(f.closed[3].packets, 150u);
  EXPECT_EQ(f.closed[3].blocks, 1500u);
  EXPECT_EQ(f.closed[3].points, 60000u);
  EXPECT_TRUE(f.closed[3].starts_at_cut);
  EXPECT_FALSE(f.closed[3].ends_at_cut);
  EXPECT_EQ(f.closed[3].last_azimuth_cdeg, 29980);
}

TEST(FrameAssembler, ThreeTurnsCutAt37Degrees) {
  // Cut 3700: 30000 + 20k = 3700 + 36000 m  =>  20k = 9700 + 36000 m  =>  k = 485, 2285, 4085.
  // Block 485 is block 5 of packet 48: the crossing packets 48, 228, 408 straddle two frames.
  Feeder f;
  ASSERT_EQ(f.fa.set_cut_deg(37.0f), Error::ok);
  EXPECT_EQ(f.fa.cut_cdeg(), 3700);
  feed_three_turns(f);
  ASSERT_EQ(f.closed.size(), 4u);
  EXPECT_EQ(f.opened_at, (std::vector<std::uint16_t>{3700, 3700, 3700}));
  // Frame 1: blocks 0..484 (485), packets 0..48 (49), last azimuth 30000 + 20*484 - 36000 = 3680.
  EXPECT_EQ(f.closed[0].blocks, 485u);
  EXPECT_EQ(f.closed[0].first_packet, 0u);
  EXPECT_EQ(f.closed[0].last_packet, 48u);
  EXPECT_EQ(f.closed[0].packets, 49u);
  EXPECT_EQ(f.closed[0].points, 485u * 40u);
  EXPECT_EQ(f.closed[0].last_azimuth_cdeg, 3680);
  // Frame 2: blocks 485..2284 (1800), packets 48..228 (181: both ends shared).
  EXPECT_EQ(f.closed[1].blocks, 1800u);
  EXPECT_EQ(f.closed[1].first_packet, 48u);
  EXPECT_EQ(f.closed[1].last_packet, 228u);
  EXPECT_EQ(f.closed[1].packets, 181u);
  EXPECT_EQ(f.closed[1].points, 72000u);
  EXPECT_EQ(f.closed[1].first_azimuth_cdeg, 3700);
  EXPECT_EQ(f.closed[1].last_azimuth_cdeg, 3680);
  // Frame 3: blocks 2285..4084, packets 228..408 (181).
  EXPECT_EQ(f.closed[2].first_packet, 228u);
  EXPECT_EQ(f.closed[2].last_packet, 408u);
  EXPECT_EQ(f.closed[2].packets, 181u);
  // Frame 4: blocks 4085..5399 (1315), packets 408..539 (132). 49 + 181 + 181 + 132 = 540 + 3.
  EXPECT_EQ(f.closed[3].blocks, 1315u);
  EXPECT_EQ(f.closed[3].first_packet, 408u);
  EXPECT_EQ(f.closed[3].last_packet, 539u);
  EXPECT_EQ(f.closed[3].packets, 132u);
  EXPECT_FALSE(f.closed[3].ends_at_cut);
}

TEST(FrameAssembler, LostPacketStraddlingTheCutStillCloses) {
  // QT128-like packets of 2 blocks, 0.4 degree apart. Packet 2 (35960, 0) is lost: the stream
  // jumps from 35920 to 40, over the cut at 0.
  Feeder f;
  f.packet(0, 0, {35800, 35840}, 10);
  f.packet(1, 0, {35880, 35920}, 10);
  f.packet(3, 1, {40, 80}, 10);
  f.packet(4, 0, {120, 160}, 10);
  f.end();
  ASSERT_EQ(f.closed.size(), 2u);
  EXPECT_EQ(f.opened_at, (std::vector<std::uint16_t>{40}));
  // Frame 1: packets 0, 1; no loss reported inside it, but it ended at the gap.
  EXPECT_EQ(f.closed[0].packets, 2u);
  EXPECT_EQ(f.closed[0].last_packet, 1u);
  EXPECT_EQ(f.closed[0].lost_packets, 0u);
  EXPECT_TRUE(f.closed[0].loss);
  EXPECT_TRUE(f.closed[0].ends_at_cut);
  EXPECT_EQ(f.closed[0].points, 40u);
  // Frame 2: packets 3, 4; the lost packet counts here (it came with packet 3's first block).
  EXPECT_EQ(f.closed[1].first_packet, 3u);
  EXPECT_EQ(f.closed[1].last_packet, 4u);
  EXPECT_EQ(f.closed[1].packets, 2u);
  EXPECT_EQ(f.closed[1].lost_packets, 1u);
  EXPECT_TRUE(f.closed[1].loss);
  EXPECT_TRUE(f.closed[1].starts_at_cut);
}

TEST(FrameAssembler, LossBeforeAPacketThatCrossesLaterStaysInTheOldFrame) {
  // Packet 1 (35880, 35920) is lost; packet 2 (35960, 0) crosses at its second block. The gap
  // lies before 35960, inside frame 1: frame 1 has the lost packet, frame 2 none.
  Feeder f;
  f.packet(0, 0, {35800, 35840});
  f.packet(2, 1, {35960, 0});
  f.packet(3, 0, {40, 80});
  f.end();
  ASSERT_EQ(f.closed.size(), 2u);
  EXPECT_EQ(f.closed[0].lost_packets, 1u);
  EXPECT_TRUE(f.closed[0].loss);
  EXPECT_EQ(f.closed[0].packets, 2u);     // packets 0 and 2
  EXPECT_EQ(f.closed[0].last_packet, 2u);
  EXPECT_EQ(f.closed[1].first_packet, 2u);  // packet 2 straddles
  EXPECT_EQ(f.closed[1].packets, 2u);       // packets 2 and 3
  EXPECT_EQ(f.closed[1].lost_packets, 0u);
  EXPECT_FALSE(f.closed[1].loss);
}

TEST(FrameAssembler, GapOfMoreThanHalfATurnClosesOnlyWithReportedLoss) {
  // 30040 -> 13000 is 18960 clockwise (over 0): half a turn or more. Without a reported loss it
  // reads as a step back (no frame); with 100 lost packets reported it is forward and crosses 0.
  {
    Feeder f;
    f.packet(0, 0, {30000, 30040});
    f.packet(101, 100, {13000, 13040});
    ASSERT_EQ(f.closed.size(), 1u);
    EXPECT_EQ(f.closed[0].ends_at_cut, true);
    EXPECT_EQ(f.fa.current().lost_packets, 100u);
  }
  {
    Feeder f;
    f.packet(0, 0, {30000, 30040});
    f.packet(1, 0, {13000, 13040});
    EXPECT_EQ(f.closed.size(), 0u);
  }
  // Forward without wrap: 1000 -> 21000 is 20000 clockwise and passes a cut at 100 degrees.
  {
    Feeder f;
    ASSERT_EQ(f.fa.set_cut_deg(100.0f), Error::ok);
    f.packet(0, 0, {960, 1000});
    f.packet(51, 50, {21000, 21040});
    EXPECT_EQ(f.opened_at, (std::vector<std::uint16_t>{21000}));
  }
  {
    Feeder f;
    ASSERT_EQ(f.fa.set_cut_deg(100.0f), Error::ok);
    f.packet(0, 0, {960, 1000});
    f.packet(1, 0, {21000, 21040});
    EXPECT_TRUE(f.opened_at.empty());
  }
}

TEST(FrameAssembler, DualReturnEqualAzimuthsCrossOnce) {
  // Dual return: each azimuth comes twice. 35920 35920 | 35960 35960 | 0 0 | 40 40.
  // Only the first 0 crosses (lands on the cut); the second 0 does not move.
  Feeder f;
  f.packet(0, 0, {35920, 35920});
  f.packet(1, 0, {35960, 35960});
  f.packet(2, 0, {0, 0});
  f.packet(3, 0, {40, 40});
  f.end();
  ASSERT_EQ(f.closed.size(), 2u);
  EXPECT_EQ(f.opened_at, (std::vector<std::uint16_t>{0}));
  EXPECT_EQ(f.closed[0].blocks, 4u);
  EXPECT_EQ(f.closed[1].blocks, 4u);
  EXPECT_EQ(f.closed[1].first_packet, 2u);
  EXPECT_EQ(f.closed[0].packets, 2u);  // packet 2 starts at the crossing: not shared
}

TEST(FrameAssembler, JitterDoesNotClose) {
  // 100 after 105 is a step back, not a wrap.
  {
    Feeder f;
    f.packet(0, 0, {100, 105, 100, 110, 108, 120});
    EXPECT_TRUE(f.closed.empty());
  }
  // Around the cut at 0: 35990 -> 5 crosses (1 frame). 35995 after 5 steps back; 10 after it is
  // 5 ahead of the furthest azimuth 5, not a second crossing; 35998 and 20 likewise.
  {
    Feeder f;
    f.packet(0, 0, {35980, 35990, 5, 35995, 10, 35998, 20});
    EXPECT_EQ(f.opened_at, (std::vector<std::uint16_t>{5}));
  }
  // Around a cut at 37 degrees: 3690 -> 3705 crosses; 3695, 3702, 3710 do not.
  {
    Feeder f;
    ASSERT_EQ(f.fa.set_cut_deg(37.0f), Error::ok);
    f.packet(0, 0, {3650, 3690, 3705, 3695, 3702, 3710});
    EXPECT_EQ(f.opened_at, (std::vector<std::uint16_t>{3705}));
  }
  // A step back of exactly half a turn (20000 -> 2000) is not a wrap; 17999 forward over 0 is.
  {
    Feeder f;
    f.packet(0, 0, {20000, 2000});
    EXPECT_TRUE(f.closed.empty());
    f.packet(1, 0, {1999});
    EXPECT_EQ(f.opened_at, (std::vector<std::uint16_t>{1999}));
  }
}

TEST(FrameAssembler, LandingOnTheCutCrossesLeavingDoesNot) {
  Feeder f;
  ASSERT_EQ(f.fa.set_cut_deg(90.0f), Error::ok);
  f.packet(0, 0, {8960, 8980, 9000, 9020, 9040});
  EXPECT_EQ(f.opened_at, (std::vector<std::uint16_t>{9000}));
  // A stream that starts on the cut: its first frame starts at the cut.
  Feeder g;
  ASSERT_EQ(g.fa.set_cut_deg(90.0f), Error::ok);
  g.packet(0, 0, {9000, 9020});
  EXPECT_TRUE(g.closed.empty());
  EXPECT_TRUE(g.fa.current().starts_at_cut);
}

TEST(FrameAssembler, FirstFrameAndFinish) {
  FrameAssembler fa;
  FrameInfo out;
  EXPECT_FALSE(fa.finish(out));  // nothing open
  EXPECT_EQ(fa.last_closed().id, 0u);
  fa.add_points(7);              // before any block: goes to the first frame
  fa.begin_packet(5, 0);
  EXPECT_FALSE(fa.block(1000));  // opens frame 1, closes nothing
  EXPECT_TRUE(fa.is_open());
  fa.add_points(3);
  ASSERT_TRUE(fa.finish(out));
  EXPECT_EQ(out.id, 1u);
  EXPECT_EQ(out.points, 10u);
  EXPECT_EQ(out.first_packet, 5u);
  EXPECT_EQ(out.packets, 1u);
  EXPECT_FALSE(out.starts_at_cut);
  EXPECT_FALSE(out.ends_at_cut);
  EXPECT_FALSE(fa.finish(out));  // already closed
  // After finish the next block opens frame 2 as at the start of a stream: no crossing test.
  fa.begin_packet(6, 0);
  EXPECT_FALSE(fa.block(500));
  EXPECT_EQ(fa.current().id, 2u);
  EXPECT_FALSE(fa.current().starts_at_cut);
  fa.reset();
  fa.begin_packet(0, 0);
  EXPECT_FALSE(fa.block(500));
  EXPECT_EQ(fa.current().id, 1u);
}

TEST(FrameAssembler, PacketWithoutBlocksHandsItsLossOn) {
  Feeder f;
  f.packet(0, 0, {100});
  f.packet(2, 1, {});     // no block: its loss waits for the next packet
  f.packet(4, 1, {140});  // 1 + 1 lost
  EXPECT_EQ(f.fa.current().lost_packets, 2u);
  EXPECT_EQ(f.fa.current().packets, 2u);  // packets 0 and 4
  f.fa.begin_packet(5, 3);                // lost but never followed by a block: counts at finish
  f.end();
  ASSERT_EQ(f.closed.size(), 1u);
  EXPECT_EQ(f.closed[0].lost_packets, 5u);
}

TEST(FrameAssembler, AzimuthOutOfRangeIsIgnored) {
  Feeder f;
  f.packet(0, 0, {35900, 36000, 65535, 35950});
  EXPECT_TRUE(f.closed.empty());
  EXPECT_EQ(f.fa.current().blocks, 2u);
  EXPECT_EQ(f.fa.current().last_azimuth_cdeg, 35950);
}

TEST(FrameAssembler, CutAngleRange) {
  FrameAssembler fa;
  EXPECT_EQ(fa.cut_cdeg(), 0);
  EXPECT_EQ(fa.set_cut_deg(359.99f), Error::ok);
  EXPECT_EQ(fa.cut_cdeg(), 35999);
  EXPECT_EQ(fa.set_cut_deg(359.999f), Error::ok);  // rounds to 360.00 = 0
  EXPECT_EQ(fa.cut_cdeg(), 0);
  EXPECT_EQ(fa.set_cut_deg(12.34f), Error::ok);
  EXPECT_EQ(fa.cut_cdeg(), 1234);
  EXPECT_EQ(fa.set_cut_deg(360.0f), Error::invalid_argument);
  EXPECT_EQ(fa.set_cut_deg(-0.01f), Error::invalid_argument);
  EXPECT_EQ(fa.set_cut_deg(std::numeric_limits<float>::quiet_NaN()), Error::invalid_argument);
  EXPECT_EQ(fa.cut_cdeg(), 1234);  // unchanged by the rejected values
}

TEST(FrameAssembler, FieldOfView) {
  FrameAssembler fa;
  EXPECT_TRUE(fa.in_fov(123.0f));  // no field of view: everything
  // Wrapping: [300, 360) and [0, 60).
  ASSERT_EQ(fa.set_fov_deg(300.0f, 60.0f), Error::ok);
  EXPECT_TRUE(fa.in_fov(300.0f));
  EXPECT_TRUE(fa.in_fov(359.9f));
  EXPECT_TRUE(fa.in_fov(0.0f));
  EXPECT_TRUE(fa.in_fov(59.99f));
  EXPECT_FALSE(fa.in_fov(60.0f));
  EXPECT_FALSE(fa.in_fov(299.99f));
  EXPECT_FALSE(fa.in_fov(180.0f));
  EXPECT_TRUE(fa.in_fov(-10.0f));   // 350
  EXPECT_TRUE(fa.in_fov(370.0f));   // 10
  EXPECT_FALSE(fa.in_fov(420.0f));  // 60
  EXPECT_FALSE(fa.in_fov(std::numeric_limits<float>::quiet_NaN()));
  EXPECT_FALSE(fa.in_fov(1000.0f));
  // Not wrapping: [10, 20).
  ASSERT_EQ(fa.set_fov_deg(10.0f, 20.0f), Error::ok);
  EXPECT_FALSE(fa.in_fov(9.99f));
  EXPECT_TRUE(fa.in_fov(10.0f));
  EXPECT_TRUE(fa.in_fov(19.99f));
  EXPECT_FALSE(fa.in_fov(20.0f));
  EXPECT_FALSE(fa.in_fov(350.0f));
  // Up to 360.
  ASSERT_EQ(fa.set_fov_deg(270.0f, 360.0f), Error::ok);
  EXPECT_TRUE(fa.in_fov(359.99f));
  EXPECT_FALSE(fa.in_fov(0.0f));
  // Rejected: empty, out of range, NaN; the previous field of view stays.
  EXPECT_EQ(fa.set_fov_deg(10.0f, 10.0f), Error::invalid_argument);
  EXPECT_EQ(fa.set_fov_deg(-1.0f, 20.0f), Error::invalid_argument);
  EXPECT_EQ(fa.set_fov_deg(360.0f, 20.0f), Error::invalid_argument);
  EXPECT_EQ(fa.set_fov_deg(0.0f, 360.5f), Error::invalid_argument);
  EXPECT_EQ(fa.set_fov_deg(0.0f, std::numeric_limits<float>::quiet_NaN()), Error::invalid_argument);
  EXPECT_TRUE(fa.in_fov(300.0f));
  fa.clear_fov();
  EXPECT_TRUE(fa.in_fov(100.0f));
}

}  // namespace
