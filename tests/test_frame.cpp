// FrameAssembler: hand-made azimuth streams (every expected count is worked out in the comments),
// then every point of the bundled captures, in both directions, against this file's own reckoning.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "hesai/frame.h"
#include "packet_builder.h"
#include "test_support.h"

namespace {

using hesai::Error;
using hesai::FrameAssembler;
using hesai::FrameInfo;

// Feeds one packet; records the frames that close. Each block brings `points_per_block` points
// at the block's own azimuth (no beam spread unless a test sets one).
struct Feeder {
  FrameAssembler fa;
  std::vector<FrameInfo> closed;
  std::vector<std::uint16_t> opened_at;  // azimuth of each block that returned true

  void take() {
    for (FrameInfo f; fa.pop_closed(f);) closed.push_back(f);
  }
  void packet(std::uint64_t index, std::uint32_t lost, std::vector<std::uint16_t> azimuths,
              std::uint32_t points_per_block = 0) {
    fa.begin_packet(index, lost);
    for (std::uint16_t az : azimuths) {
      if (fa.block(az)) {
        take();
        opened_at.push_back(az);
      }
      for (std::uint32_t i = 0; i < points_per_block; ++i) fa.point(static_cast<float>(az) / 100.0f);
    }
  }
  void end() {
    fa.finish();
    take();
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
  EXPECT_FALSE(fa.finish());  // nothing open
  EXPECT_FALSE(fa.pop_closed(out));
  EXPECT_EQ(fa.current().id, 0u);
  for (int i = 0; i < 7; ++i) EXPECT_EQ(fa.point(10.0f), 1u);  // before any block: the first frame
  fa.begin_packet(5, 0);
  EXPECT_FALSE(fa.block(1000));  // opens frame 1, closes nothing
  EXPECT_TRUE(fa.is_open());
  for (int i = 0; i < 3; ++i) EXPECT_EQ(fa.point(10.0f), 1u);
  ASSERT_TRUE(fa.finish());
  ASSERT_TRUE(fa.pop_closed(out));
  EXPECT_FALSE(fa.pop_closed(out));
  EXPECT_EQ(out.id, 1u);
  EXPECT_EQ(out.points, 10u);
  EXPECT_EQ(out.first_packet, 5u);
  EXPECT_EQ(out.packets, 1u);
  EXPECT_FALSE(out.starts_at_cut);
  EXPECT_FALSE(out.ends_at_cut);
  EXPECT_FALSE(fa.finish());  // already closed
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

namespace {

using hesai::AzimuthSpread;
using hesai::Rotation;

// ---- Points by their own azimuth ----

// A block and the points it brings, each as an offset from the block in 0.01 degree.
struct Shot {
  std::uint16_t block;
  std::vector<int> offsets;
};

// Feeds packets of shots; records each point's frame id and the frames as they close.
struct PointFeeder {
  FrameAssembler fa;
  std::vector<FrameInfo> closed;
  std::vector<std::uint64_t> ids;        // frame of each point, in order
  std::vector<std::size_t> closed_at;    // index of the block at which each frame closed
  std::size_t blocks = 0;
  Rotation rotation = Rotation::clockwise;

  // The azimuth as this direction's stream would carry it: mirrored (36000 - a) for
  // counter-clockwise, so that one scenario can run both ways.
  std::uint16_t as_sent(int cdeg) const {
    const int a = ((rotation == Rotation::clockwise ? cdeg : -cdeg) % 36000 + 36000) % 36000;
    return static_cast<std::uint16_t>(a);
  }
  void take() {
    for (FrameInfo f; fa.pop_closed(f);) {
      closed.push_back(f);
      closed_at.push_back(blocks);
    }
  }
  void packet(std::uint64_t index, std::uint32_t lost, const std::vector<Shot>& shots) {
    fa.begin_packet(index, lost);
    for (const Shot& s : shots) {
      if (fa.block(as_sent(s.block))) take();
      ++blocks;
      for (int off : s.offsets) ids.push_back(fa.point(static_cast<float>(as_sent(s.block + off)) / 100.0f));
    }
  }
  void end() {
    fa.finish();
    take();
  }
};

class PointFrames : public ::testing::TestWithParam<Rotation> {
 protected:
  void SetUp() override { set_up(f); }
  // The direction, and the spread of a clockwise scenario (beams from -2 to +1 degrees from their
  // block), mirrored for counter-clockwise.
  void set_up(PointFeeder& feeder) const {
    const bool cw = GetParam() == Rotation::clockwise;
    feeder.rotation = GetParam();
    feeder.fa.set_rotation(GetParam());
    ASSERT_EQ(feeder.fa.set_beam_spread(cw ? AzimuthSpread{-2.0f, 1.0f} : AzimuthSpread{-1.0f, 2.0f}), Error::ok);
  }
  PointFeeder f;
};

// Cut 0; beams at -2, 0 and +1 degree from their block; blocks 0.5 degree apart. In rotation
// order (clockwise as written; counter-clockwise runs the mirror image and must give the same).
TEST_P(PointFrames, StraddlingPacketsGiveEachPointToItsOwnRotation) {
  // Packet 0, blocks 356.0 and 356.5: points 354.0 356.0 357.0 | 354.5 356.5 357.5: frame 1.
  f.packet(0, 0, {{35600, {-200, 0, 100}}, {35650, {-200, 0, 100}}});
  // Packet 1, blocks 359.0 and 359.5: 357.0 359.0 | 357.5 359.5 in frame 1; 360.0 (on the cut)
  // and 360.5 past it: frame 2 opens early, before any block reaches the cut.
  f.packet(1, 0, {{35900, {-200, 0, 100}}, {35950, {-200, 0, 100}}});
  EXPECT_EQ(f.ids, (std::vector<std::uint64_t>{1, 1, 1, 1, 1, 1, 1, 1, 2, 1, 1, 2}));
  // Packet 2, blocks 0.0 and 0.5: the reference passes the cut, but frame 1 stays open: the
  // -2 degree beams (358.0, 358.5) still land in it.
  f.packet(2, 0, {{0, {-200, 0, 100}}, {50, {-200, 0, 100}}});
  EXPECT_TRUE(f.closed.empty());
  // Packet 3, blocks 1.5 and 2.0: 359.5 still in frame 1; at 2.0 the reference is the spread
  // behind (2 degrees) past the cut: frame 1 closes before that block's points (0.0: frame 2).
  f.packet(3, 0, {{150, {-200, 0, 100}}, {200, {-200, 0, 100}}});
  f.end();
  EXPECT_EQ(f.ids, (std::vector<std::uint64_t>{1, 1, 1, 1, 1, 1, 1, 1, 2, 1, 1, 2,  //
                                                1, 2, 2, 1, 2, 2, 1, 2, 2, 2, 2, 2}));
  ASSERT_EQ(f.closed.size(), 2u);
  EXPECT_EQ(f.closed_at, (std::vector<std::size_t>{7, 8}));  // frame 1 at block 7 (2.0), frame 2 at the end
  const FrameInfo& a = f.closed[0];
  const FrameInfo& b = f.closed[1];
  EXPECT_EQ(a.id, 1u);
  EXPECT_EQ(a.points, 13u);  // 6 + 2 + 2 + 1 + 1 + 1 by packet and block, as listed above
  EXPECT_EQ(a.blocks, 4u);   // 356.0 356.5 359.0 359.5
  EXPECT_EQ(a.first_packet, 0u);
  EXPECT_EQ(a.last_packet, 3u);  // packet 3 gave it the 359.5 point
  EXPECT_EQ(a.packets, 4u);
  EXPECT_EQ(a.late_points, 0u);
  EXPECT_FALSE(a.starts_at_cut);
  EXPECT_TRUE(a.ends_at_cut);
  EXPECT_EQ(a.first_azimuth_cdeg, f.as_sent(35600));
  EXPECT_EQ(a.last_azimuth_cdeg, f.as_sent(35950));
  EXPECT_EQ(b.id, 2u);
  EXPECT_EQ(b.points, 11u);
  EXPECT_EQ(b.blocks, 4u);       // 0.0 0.5 1.5 2.0
  EXPECT_EQ(b.first_packet, 1u);  // its first points came with packet 1
  EXPECT_EQ(b.last_packet, 3u);
  EXPECT_EQ(b.packets, 3u);
  EXPECT_TRUE(b.starts_at_cut);  // the stream began 4 degrees before its cut, more than the 1 ahead
  EXPECT_FALSE(b.ends_at_cut);
  EXPECT_EQ(b.first_azimuth_cdeg, f.as_sent(0));
  EXPECT_EQ(a.points + b.points, f.ids.size());
}

// A stream whose first block lies less than the spread behind past the cut: its first points
// behind the cut belong to the rotation before, which opens first as frame 1.
TEST_P(PointFrames, StreamStartingJustPastTheCutOpensTheRotationBefore) {
  f.packet(0, 0, {{100, {-200, 0}}, {150, {-200, 0}}});  // 359.0 1.0 | 359.5 1.5
  f.packet(1, 0, {{200, {-200, 0}}});                      // the reference 2 degrees past: frame 1 closes
  EXPECT_EQ(f.ids, (std::vector<std::uint64_t>{1, 2, 1, 2, 2, 2}));
  ASSERT_EQ(f.closed.size(), 1u);
  EXPECT_EQ(f.closed[0].id, 1u);
  EXPECT_EQ(f.closed[0].points, 2u);
  EXPECT_EQ(f.closed[0].blocks, 0u);  // no block of it was seen
  EXPECT_EQ(f.closed[0].packets, 1u);
  EXPECT_FALSE(f.closed[0].starts_at_cut);
  EXPECT_TRUE(f.closed[0].ends_at_cut);
  EXPECT_EQ(f.fa.current().id, 2u);
  EXPECT_FALSE(f.fa.current().starts_at_cut);  // beams 1 degree ahead of blocks before 1.0 were not seen
  // The same start where no point lands behind the cut: frame 1 closes empty.
  PointFeeder g;
  set_up(g);
  g.packet(0, 0, {{100, {0}}, {200, {0}}});
  g.end();
  ASSERT_EQ(g.closed.size(), 2u);
  EXPECT_EQ(g.closed[0].points + g.closed[0].packets + g.closed[0].blocks, 0u);
  EXPECT_EQ(g.closed[1].points, 2u);
  // A first block the spread behind or more past the cut: no frame before it.
  PointFeeder h;
  set_up(h);
  h.packet(0, 0, {{200, {-200, 0}}});
  EXPECT_EQ(h.ids, (std::vector<std::uint64_t>{1, 1}));
}

// A packet that steps back after a frame closed: its points behind the cut cannot go to their
// own (closed) frame; they go to the oldest open one and are counted there.
TEST_P(PointFrames, StepBackPastTheSpreadCountsLatePoints) {
  f.packet(0, 0, {{35800, {0}}, {35900, {0}}});
  f.packet(1, 0, {{0, {0}}, {250, {0}}});  // 2.5 degrees past the cut: frame 1 closes
  ASSERT_EQ(f.closed.size(), 1u);
  f.packet(2, 0, {{35950, {0, 100}}});     // late: 359.5 belongs to frame 1; 0.5 to frame 2
  f.packet(3, 0, {{300, {0}}});
  f.end();
  EXPECT_EQ(f.ids, (std::vector<std::uint64_t>{1, 1, 2, 2, 2, 2, 2}));
  ASSERT_EQ(f.closed.size(), 2u);
  EXPECT_EQ(f.closed[0].points, 2u);
  EXPECT_EQ(f.closed[1].points, 5u);
  EXPECT_EQ(f.closed[1].late_points, 1u);
  EXPECT_EQ(f.closed[1].blocks, 4u);  // the step back does not move the reference: no new frame
}

// Lost packets straddling the cut: the frame before closes as soon as the reference is the
// spread past it, and both frames are marked.
TEST_P(PointFrames, GapAcrossTheCut) {
  f.packet(0, 0, {{35000, {0}}});
  f.packet(10, 9, {{500, {-200, 0}}});  // 3.0 and 5.0 past the cut, 15 degrees after the last block
  ASSERT_EQ(f.closed.size(), 1u);
  EXPECT_TRUE(f.closed[0].loss);
  EXPECT_EQ(f.closed[0].lost_packets, 0u);
  EXPECT_EQ(f.ids, (std::vector<std::uint64_t>{1, 2, 2}));
  EXPECT_EQ(f.fa.current().lost_packets, 9u);
}

INSTANTIATE_TEST_SUITE_P(BothWays, PointFrames, ::testing::Values(Rotation::clockwise, Rotation::counterclockwise),
                         [](const auto& i) { return i.param == Rotation::clockwise ? "clockwise" : "counterclockwise"; });

TEST(FrameAssembler, BeamSpreadRange) {
  FrameAssembler fa;
  EXPECT_EQ(fa.set_beam_spread({-180.0f, 180.0f}), Error::ok);
  EXPECT_EQ(fa.set_beam_spread({1.0f, -1.0f}), Error::invalid_argument);
  EXPECT_EQ(fa.set_beam_spread({-181.0f, 0.0f}), Error::invalid_argument);
  EXPECT_EQ(fa.set_beam_spread({0.0f, 180.5f}), Error::invalid_argument);
  EXPECT_EQ(fa.set_beam_spread({std::numeric_limits<float>::quiet_NaN(), 0.0f}), Error::invalid_argument);
}

// The direction learnt after the stream began (RotationDetector): the blocks seen clockwise
// stepped back and stayed in frame 1; counter-clockwise from there, the stream passes the cut.
TEST(FrameAssembler, RotationChangedWhileStreaming) {
  Feeder f;
  f.packet(0, 0, {1000, 960}, 1);  // 960 after 1000: a step back clockwise
  f.packet(1, 0, {920, 880}, 1);
  EXPECT_TRUE(f.closed.empty());
  f.fa.set_rotation(Rotation::counterclockwise);
  EXPECT_EQ(f.fa.rotation(), Rotation::counterclockwise);
  f.packet(2, 0, {40, 0}, 1);      // 0 lies on the cut: frame 2 starts there
  f.packet(3, 0, {35960}, 1);
  f.end();
  EXPECT_EQ(f.opened_at, (std::vector<std::uint16_t>{0}));
  ASSERT_EQ(f.closed.size(), 2u);
  EXPECT_EQ(f.closed[0].blocks, 5u);
  EXPECT_EQ(f.closed[0].points, 5u);
  EXPECT_EQ(f.closed[1].blocks, 2u);
  EXPECT_EQ(f.closed[1].points, 2u);
  EXPECT_EQ(f.closed[1].first_azimuth_cdeg, 0);
}

// reset() forgets the stream and the frames not taken, and keeps the configuration.
TEST(FrameAssembler, ResetKeepsTheConfiguration) {
  FrameAssembler fa;
  ASSERT_EQ(fa.set_cut_deg(90.0f), Error::ok);
  ASSERT_EQ(fa.set_fov_deg(10.0f, 20.0f), Error::ok);
  ASSERT_EQ(fa.set_beam_spread({-1.0f, 2.0f}), Error::ok);
  fa.set_rotation(Rotation::counterclockwise);
  fa.begin_packet(0, 3);
  fa.block(9100);
  fa.block(8900);  // 1 degree counter-clockwise past the cut at 90: frame 2; frame 1 stays open
  fa.block(8700);  // 3 degrees past, more than the 2 a beam can lie behind: frame 1 closes, not taken
  fa.reset();
  FrameInfo f;
  EXPECT_FALSE(fa.pop_closed(f));
  EXPECT_FALSE(fa.is_open());
  EXPECT_EQ(fa.cut_cdeg(), 9000);
  EXPECT_EQ(fa.rotation(), Rotation::counterclockwise);
  EXPECT_FALSE(fa.in_fov(25.0f));
  // The spread is kept: 1 degree counter-clockwise past the cut (89.0) is within the 2 degrees a
  // beam can lie behind its block (clockwise of it): the rotation before opens first, as frame 1.
  fa.begin_packet(0, 0);
  fa.block(8900);
  EXPECT_EQ(fa.current().id, 2u);
  EXPECT_EQ(fa.point(90.5f), 1u);
  EXPECT_EQ(fa.current().lost_packets, 0u);  // the 3 lost before the reset are forgotten
}

// Frames must be taken after each block: one that is not is overwritten and counted.
TEST(FrameAssembler, FramesNotTakenAreCountedWhenDropped) {
  FrameAssembler fa;
  fa.begin_packet(0, 0);
  // Moves of 17000 forward: every second block passes the cut (100, 17000, 34000 | 15000 ...).
  for (const int az : {100, 17000, 34000, 15000, 32000, 13000, 30000, 11000, 28000, 9000, 26000, 7000})
    fa.block(static_cast<std::uint16_t>(az));
  // Frames 1..5 closed, 6 open: four slots hold 3, 4, 5 and 6; 1 and 2 were dropped.
  EXPECT_EQ(fa.frames_dropped(), 2u);
  std::vector<std::uint64_t> ids;
  for (FrameInfo f; fa.pop_closed(f);) ids.push_back(f.id);
  EXPECT_EQ(ids, (std::vector<std::uint64_t>{3, 4, 5}));
  EXPECT_EQ(fa.current().id, 6u);
}

}  // namespace

namespace {

// ---- The bundled captures, both ways ----

struct SeamCase {
  const char* capture;
  hesai::Model model;
  Rotation rotation;
  float cut_deg;
};

void PrintTo(const SeamCase& c, std::ostream* os) {
  *os << hesai::model_name(c.model) << (c.rotation == Rotation::clockwise ? " cw" : " ccw") << " cut " << c.cut_deg;
}

class CaptureFrames : public ::testing::TestWithParam<SeamCase> {};

// Every point of a capture (mirrored for counter-clockwise) through the decoder and the assembler,
// against this test's own reckoning: it unwraps the block azimuths (each move forward from the
// last, from the first block's distance past the cut), places each point at its block plus the
// short way to its own azimuth, and takes the rotation floor(position / 360). Then:
// - every point is in the frame of its rotation (one id per rotation, in order): a frame's points
//   lie within [cut, cut + 360) from its start and neighbouring frames do not overlap;
// - the frames are the rotations: their count is the number of rotations the points span;
// - nothing is lost or counted twice: each frame's count is the points of its rotation, and
//   together the capture's points; no point came late;
// - a frame closes within the spread behind (plus a packet) of the packet that ended it.
TEST_P(CaptureFrames, SeamsFollowEachPointsAzimuth) {
  const SeamCase& c = GetParam();
  const bool cw = c.rotation == Rotation::clockwise;
  auto packets = hesai_test::pcap_payloads(c.capture);
  if (!cw)
    for (auto& p : packets) p = hesai_test::counterclockwise_copy(p, c.model);
  hesai::Decoder dec(c.model);
  dec.set_rotation(c.rotation);
  FrameAssembler fa;
  fa.set_rotation(c.rotation);
  ASSERT_EQ(fa.set_cut_deg(c.cut_deg), Error::ok);
  const double cut = fa.cut_cdeg();
  auto forward = [&](double from, double to) { return std::fmod((cw ? to - from : from - to) + 72000.0, 36000.0); };

  struct Placed {
    std::uint64_t id;
    double at;  // position past the stream's first cut, 0.01 degree, unwrapped
  };
  std::vector<Placed> placed;
  std::vector<FrameInfo> frames;
  std::vector<std::uint64_t> closed_in;  // packet index during which each frame closed
  double block_at = 0, first_block_at = 0, last_block = 0, behind = 0, ahead = 0, move_per_packet = 36000;
  bool first = true;
  hesai::PacketPoints pts;
  hesai::PacketInfo info;
  for (std::uint64_t i = 0; i < packets.size(); ++i) {
    ASSERT_EQ(dec.decode(hesai_test::view(packets[static_cast<std::size_t>(i)]), info, pts), Error::ok);
    ASSERT_EQ(fa.set_beam_spread(dec.beam_spread()), Error::ok);
    behind = std::max(behind, 100.0 * (cw ? -dec.beam_spread().min_deg : dec.beam_spread().max_deg));
    ahead = std::max(ahead, 100.0 * (cw ? dec.beam_spread().max_deg : -dec.beam_spread().min_deg));
    fa.begin_packet(i, 0);
    std::size_t next = 0;
    for (std::size_t b = 0; b < info.blocks; ++b) {
      const double az = info.block_azimuth[b];
      if (first) {
        first_block_at = block_at = forward(cut, az);
        first = false;
      } else {
        const double move = forward(last_block, az);
        ASSERT_LT(move, 18000.0) << "the captures only move forward";
        block_at += move;
        if (b == 0 && move > 0) move_per_packet = std::min(move_per_packet, move);
      }
      last_block = az;
      if (fa.block(info.block_azimuth[b]))
        for (FrameInfo f; fa.pop_closed(f);) {
          frames.push_back(f);
          closed_in.push_back(i);
        }
      for (; next < pts.count && pts.points[next].block == b; ++next) {
        const float point_az = pts.points[next].azimuth_deg;
        double off = std::fmod(point_az * 100.0 - az + 54000.0, 36000.0) - 18000.0;  // clockwise, short way
        placed.push_back({fa.point(point_az), block_at + (cw ? off : -off)});
      }
    }
  }
  fa.finish();
  for (FrameInfo f; fa.pop_closed(f);) {
    frames.push_back(f);
    closed_in.push_back(packets.size());
  }

  // The rotation of each point, and its frame id: one id per rotation. A point within 0.001
  // degree of a cut may fall either side (float against this test's double).
  auto rotation_of = [](double at) { return static_cast<std::int64_t>(std::floor(at / 36000.0)); };
  auto on_a_cut = [](double at) { return std::fabs(at - 36000.0 * std::round(at / 36000.0)) < 0.1; };
  std::int64_t shift = 0, lo = INT64_MAX, hi = INT64_MIN;
  bool have_shift = false;
  for (const Placed& p : placed) {
    if (on_a_cut(p.at)) continue;
    if (!have_shift) shift = static_cast<std::int64_t>(p.id) - rotation_of(p.at);
    have_shift = true;
    ASSERT_EQ(static_cast<std::int64_t>(p.id) - rotation_of(p.at), shift) << "point at " << p.at / 100 << " degrees";
  }
  std::map<std::uint64_t, std::uint64_t> per_frame;
  std::map<std::uint64_t, std::pair<double, double>> extent;
  for (const Placed& p : placed) {
    lo = std::min(lo, rotation_of(p.at));
    hi = std::max(hi, rotation_of(p.at));
    ++per_frame[p.id];
    auto [it, fresh] = extent.emplace(p.id, std::make_pair(p.at, p.at));
    if (!fresh) it->second = {std::min(it->second.first, p.at), std::max(it->second.second, p.at)};
  }
  // The frames are the rotations, in order, each with exactly its points.
  ASSERT_EQ(frames.size(), static_cast<std::size_t>(hi - lo + 1));
  std::uint64_t sum = 0;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const FrameInfo& f = frames[k];
    EXPECT_EQ(f.id, k + 1);
    EXPECT_EQ(f.points, per_frame[f.id]) << "frame " << f.id;
    EXPECT_EQ(f.late_points, 0u);
    sum += f.points;
    // Within one turn from its cut, and before the next frame's first point.
    const auto [first_at, last_at] = extent[f.id];
    const double start = 36000.0 * static_cast<double>(static_cast<std::int64_t>(f.id) - shift);
    EXPECT_GE(first_at, start - 0.1) << "frame " << f.id;
    EXPECT_LT(last_at, start + 36000.0 + 0.1) << "frame " << f.id;
    if (k + 1 < frames.size() && extent.count(f.id + 1)) {
      EXPECT_LT(last_at, extent[f.id + 1].first + 0.2) << "frame " << f.id;
    }
    // Closed within the spread behind, and a packet, after the last packet that gave it a point.
    if (f.ends_at_cut) {
      EXPECT_LE(closed_in[k] - f.last_packet, static_cast<std::uint64_t>(behind / move_per_packet) + 2);
    }
    // A rotation whose every beam the stream covered (blocks from the spread ahead before its cut
    // to the spread behind past its end) is a whole turn; the others are partial.
    const bool whole = start - ahead >= first_block_at && start + 36000.0 + behind <= block_at;
    EXPECT_EQ(f.starts_at_cut && f.ends_at_cut, whole) << "frame " << f.id;
  }
  EXPECT_EQ(sum, placed.size());
  RecordProperty("frames", std::to_string(frames.size()));
}

INSTANTIATE_TEST_SUITE_P(
    Bundled, CaptureFrames,
    ::testing::Values(SeamCase{"pandar40p_dual.pcap", hesai::Model::pandar40p, Rotation::clockwise, 0.0f},
                      SeamCase{"pandar40p_dual.pcap", hesai::Model::pandar40p, Rotation::counterclockwise, 0.0f},
                      SeamCase{"pandar40p_dual.pcap", hesai::Model::pandar40p, Rotation::counterclockwise, 123.45f},
                      SeamCase{"pandar64_dual.pcap", hesai::Model::pandar64, Rotation::clockwise, 0.0f},
                      SeamCase{"pandar64_dual.pcap", hesai::Model::pandar64, Rotation::counterclockwise, 0.0f},
                      SeamCase{"pandar64_dual.pcap", hesai::Model::pandar64, Rotation::clockwise, 123.45f},
                      SeamCase{"qt128c2x_dual.pcap", hesai::Model::qt128c2x, Rotation::clockwise, 0.0f},
                      SeamCase{"qt128c2x_dual.pcap", hesai::Model::qt128c2x, Rotation::counterclockwise, 0.0f},
                      SeamCase{"qt128c2x_dual.pcap", hesai::Model::qt128c2x, Rotation::clockwise, 10.5f},
                      SeamCase{"qt128c2x_dual.pcap", hesai::Model::qt128c2x, Rotation::counterclockwise, 350.0f}),
    [](const auto& i) {
      return std::string(hesai::model_name(i.param.model)) + (i.param.rotation == Rotation::clockwise ? "_cw_" : "_ccw_") +
             std::to_string(static_cast<int>(i.param.cut_deg * 100));
    });

}  // namespace
