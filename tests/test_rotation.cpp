// RotationDetector: hand-made azimuth streams (every move worked out in the comments) and the
// bundled captures, as recorded (clockwise) and mirrored (counter-clockwise).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "hesai/held_packets.h"
#include "hesai/rotation.h"
#include "packet_builder.h"
#include "test_support.h"

namespace {

using hesai::Rotation;
using hesai::RotationDetector;

// Observes each azimuth; returns the 0-based indices at which observe() returned true.
std::vector<std::size_t> feed(RotationDetector& d, const std::vector<std::uint16_t>& azimuths) {
  std::vector<std::size_t> decided;
  for (std::size_t i = 0; i < azimuths.size(); ++i)
    if (d.observe(azimuths[i])) decided.push_back(i);
  return decided;
}

TEST(RotationDetector, ClockwiseUntilKnown) {
  RotationDetector d;
  EXPECT_FALSE(d.known());
  EXPECT_EQ(d.rotation(), Rotation::clockwise);
  EXPECT_FALSE(d.observe(1000));  // one packet: no move yet
  EXPECT_FALSE(d.observe(900));   // one move of -100: not yet
  EXPECT_FALSE(d.known());
  EXPECT_EQ(d.rotation(), Rotation::clockwise);
}

TEST(RotationDetector, ThreePacketsAcrossTheWrapAtZero) {
  // Clockwise over 0: 35900 -> 0 is +100, 0 -> 100 is +100: decided at the third packet.
  RotationDetector cw;
  EXPECT_EQ(feed(cw, {35900, 0, 100, 200}), (std::vector<std::size_t>{2}));
  EXPECT_TRUE(cw.known());
  EXPECT_EQ(cw.rotation(), Rotation::clockwise);
  // Counter-clockwise over 0: 100 -> 35950 is -150, 35950 -> 35850 is -100.
  RotationDetector ccw;
  EXPECT_EQ(feed(ccw, {100, 35950, 35850, 35750}), (std::vector<std::size_t>{2}));
  EXPECT_EQ(ccw.rotation(), Rotation::counterclockwise);
}

TEST(RotationDetector, LostPacketOnlyLengthensAMove) {
  // Packet 1900 lost: 2000 -> 1800 is -200, still counter-clockwise.
  RotationDetector d;
  EXPECT_EQ(feed(d, {2000, 1800, 1700}), (std::vector<std::size_t>{2}));
  EXPECT_EQ(d.rotation(), Rotation::counterclockwise);
  // Three packets lost across 0: 35950 -> 250 is +300.
  RotationDetector e;
  EXPECT_EQ(feed(e, {35850, 35950, 250}), (std::vector<std::size_t>{2}));
  EXPECT_EQ(e.rotation(), Rotation::clockwise);
}

TEST(RotationDetector, StationaryMotorDecidesNothing) {
  // The same azimuth, then encoder noise of up to 4 (0.04 degree): no evidence either way.
  RotationDetector d;
  EXPECT_TRUE(feed(d, std::vector<std::uint16_t>(50, 12345)).empty());
  EXPECT_TRUE(feed(d, {12345, 12349, 12346, 12342, 12345, 12341, 12345, 0, 35996, 0, 4}).empty());
  EXPECT_FALSE(d.known());
  EXPECT_EQ(d.rotation(), Rotation::clockwise);
  // The motor starts counter-clockwise: 4 -> 35950 is -54, then -50: decided.
  EXPECT_EQ(feed(d, {35950, 35900}), (std::vector<std::size_t>{1}));
  EXPECT_EQ(d.rotation(), Rotation::counterclockwise);
  // And stops again: the direction stays known.
  EXPECT_TRUE(feed(d, std::vector<std::uint16_t>(20, 35900)).empty());
  EXPECT_EQ(d.rotation(), Rotation::counterclockwise);
}

TEST(RotationDetector, LatePacketNeitherDecidesNorFlips) {
  // Before the decision: 1000, 1200, 1100 (late), 1300, 1400 -> +200, -100, +200, +100. The late
  // packet interrupts the run; two clockwise moves in a row come only at 1400.
  RotationDetector d;
  EXPECT_EQ(feed(d, {1000, 1200, 1100, 1300, 1400}), (std::vector<std::size_t>{4}));
  EXPECT_EQ(d.rotation(), Rotation::clockwise);
  // Once known: 1600, 1500 (late), 1700 -> +200, -100, +200: no change.
  EXPECT_TRUE(feed(d, {1600, 1500, 1700, 1800}).empty());
  EXPECT_EQ(d.rotation(), Rotation::clockwise);
}

TEST(RotationDetector, GapBeyondAQuarterTurnIsNoEvidence) {
  // 1100 -> 20000: +18900 the long way, -17100 the short way: ambiguous, ignored; the run of
  // clockwise moves (+100 before, +100 after) goes on.
  RotationDetector d;
  EXPECT_EQ(feed(d, {1000, 1100, 20000, 20100}), (std::vector<std::size_t>{3}));
  EXPECT_EQ(d.rotation(), Rotation::clockwise);
  // A move of exactly a quarter turn still counts; one more does not.
  RotationDetector e;
  EXPECT_EQ(feed(e, {0, 9000, 18000}), (std::vector<std::size_t>{2}));
  RotationDetector f;
  EXPECT_TRUE(feed(f, {0, 9001, 18002}).empty());
}

TEST(RotationDetector, ReconfiguredUnitChangesAfterEightMovesTheOtherWay) {
  RotationDetector d;
  EXPECT_EQ(feed(d, {0, 100, 200}), (std::vector<std::size_t>{2}));
  // Seven moves of -100: not enough to overturn a known direction.
  EXPECT_TRUE(feed(d, {100, 0, 35900, 35800, 35700, 35600, 35500}).empty());
  EXPECT_EQ(d.rotation(), Rotation::clockwise);
  // The eighth does.
  EXPECT_EQ(feed(d, {35400, 35300}), (std::vector<std::size_t>{0}));
  EXPECT_EQ(d.rotation(), Rotation::counterclockwise);
}

TEST(RotationDetector, NotAnAzimuthIsIgnoredAndResetForgets) {
  RotationDetector d;
  EXPECT_TRUE(feed(d, {1000, 36000, 65535, 1100}).empty());  // one move of +100 only
  EXPECT_EQ(feed(d, {1200}), (std::vector<std::size_t>{0}));
  d.reset();
  EXPECT_FALSE(d.known());
  EXPECT_FALSE(d.observe(1300));  // no move yet after the reset
}

// A PacketInfo with these block azimuths, `returns` blocks per firing.
hesai::PacketInfo packet(std::vector<std::uint16_t> azimuths, std::uint8_t returns) {
  hesai::PacketInfo info;
  info.returns = returns;
  info.blocks = static_cast<std::uint8_t>(azimuths.size());
  for (std::size_t b = 0; b < azimuths.size(); ++b) info.block_azimuth[b] = azimuths[b];
  return info;
}

TEST(RotationDetector, OnePacketDecidesByItsFirings) {
  // Single return, 0.2 degree a firing: three moves of +20.
  RotationDetector cw;
  EXPECT_TRUE(cw.observe(packet({100, 120, 140, 160}, 1)));
  EXPECT_EQ(cw.rotation(), Rotation::clockwise);
  // Dual return: blocks 0, 2, 4 are the firings, 71 -> 35980 -> 35960 (-91, -20) across 0.
  RotationDetector ccw;
  EXPECT_TRUE(ccw.observe(packet({71, 71, 35980, 35980, 35960, 35960}, 2)));
  EXPECT_EQ(ccw.rotation(), Rotation::counterclockwise);
  // Triple return, two firings of three blocks: one move of -18 decides.
  RotationDetector triple;
  EXPECT_TRUE(triple.observe(packet({900, 900, 900, 882, 882, 882}, 3)));
  EXPECT_EQ(triple.rotation(), Rotation::counterclockwise);
}

TEST(RotationDetector, OnePacketWithoutEvidenceDecidesNothing) {
  // One firing (the dual-return QT128C2X): no move within the packet.
  RotationDetector one;
  EXPECT_FALSE(one.observe(packet({1000, 1000}, 2)));
  EXPECT_FALSE(one.known());
  // Moves both ways, a move below 0.05 degree, one beyond a quarter turn: no decision.
  for (const auto& azimuths : {std::vector<std::uint16_t>{100, 120, 110, 130}, std::vector<std::uint16_t>{100, 104, 124, 144},
                               std::vector<std::uint16_t>{100, 120, 9200, 9220}, std::vector<std::uint16_t>{100, 120, 36000, 140}}) {
    RotationDetector d;
    EXPECT_FALSE(d.observe(packet(azimuths, 1))) << azimuths[2];
    EXPECT_FALSE(d.known());
    EXPECT_EQ(d.rotation(), Rotation::clockwise);
  }
  // Such packets still count between packets: 1000, 1100, 1200 decide at the third.
  RotationDetector between;
  EXPECT_FALSE(between.observe(packet({1000, 1000}, 2)));
  EXPECT_FALSE(between.observe(packet({1100, 1100}, 2)));
  EXPECT_TRUE(between.observe(packet({1200, 1200}, 2)));
  EXPECT_EQ(between.rotation(), Rotation::clockwise);
}

TEST(RotationDetector, AKnownDirectionChangesOnlyBetweenPackets) {
  RotationDetector d;
  EXPECT_TRUE(d.observe(packet({1000, 1020, 1040}, 1)));
  // Packets whose firings fall (-20 each) do not overturn it by themselves; the moves between
  // their first blocks do, at the eighth of -100 in a row (1000 -> 900 ... 300 -> 200).
  for (int i = 1; i < 8; ++i)
    EXPECT_FALSE(d.observe(packet({static_cast<std::uint16_t>(1000 - 100 * i), static_cast<std::uint16_t>(980 - 100 * i)}, 1)));
  EXPECT_EQ(d.rotation(), Rotation::clockwise);
  EXPECT_TRUE(d.observe(packet({200, 180}, 1)));
  EXPECT_EQ(d.rotation(), Rotation::counterclockwise);
}

// The bundled captures spin clockwise; mirrored, counter-clockwise. By first block azimuths
// alone the third packet decides; by whole packets the first, except on the dual-return
// QT128C2X, whose packets are one firing each: the third. Nothing changes after.
TEST(RotationDetector, BundledCapturesBothWays) {
  const struct {
    const char* file;
    hesai::Model model;
    std::size_t by_packet;  // index of the packet that decides with observe(PacketInfo)
  } cases[] = {{"pandar40p_dual.pcap", hesai::Model::pandar40p, 0},  {"pandar64_dual.pcap", hesai::Model::pandar64, 0},
               {"qt128c2x_dual.pcap", hesai::Model::qt128c2x, 2},   {"pandar_qt64.pcap", hesai::Model::pandar_qt64, 0},
               {"pandar_xt16.pcap", hesai::Model::pandar_xt16, 0},  {"pandar_xt32.pcap", hesai::Model::pandar_xt32, 0},
               {"pandar_xt32m2x.pcap", hesai::Model::pandar_xt32m2x, 0}};
  for (const auto& c : cases) {
    for (const bool mirrored : {false, true}) {
      RotationDetector first_blocks, packets;
      std::vector<std::size_t> by_first_block, by_packet;
      hesai::Decoder dec(c.model);
      hesai::PacketInfo info;
      hesai::PacketPoints pts;
      std::size_t i = 0;
      for (const auto& recorded : hesai_test::pcap_payloads(c.file)) {
        const auto p = mirrored ? hesai_test::counterclockwise_copy(recorded, c.model) : recorded;
        if (first_blocks.observe(hesai_test::block_azimuths(p, c.model)[0])) by_first_block.push_back(i);
        ASSERT_EQ(dec.decode(hesai_test::view(p), info, pts), hesai::Error::ok);
        if (packets.observe(info)) by_packet.push_back(i);
        ++i;
      }
      const Rotation expected = mirrored ? Rotation::counterclockwise : Rotation::clockwise;
      EXPECT_EQ(by_first_block, (std::vector<std::size_t>{2})) << c.file << (mirrored ? " mirrored" : "");
      EXPECT_EQ(first_blocks.rotation(), expected) << c.file;
      EXPECT_EQ(by_packet, (std::vector<std::size_t>{c.by_packet})) << c.file << (mirrored ? " mirrored" : "");
      EXPECT_EQ(packets.rotation(), expected) << c.file;
    }
  }
}

// HeldPackets: first in, first out, at most its capacity, each packet with its tag.
TEST(HeldPackets, FirstInFirstOutWithinItsCapacity) {
  hesai::HeldPackets<2> held;
  const std::vector<std::uint8_t> a{1, 2, 3}, b{4, 5}, c{6};
  const std::vector<std::uint8_t> too_long(hesai::kMaxPacketBytes + 1, 7);
  EXPECT_TRUE(held.empty());
  EXPECT_EQ(held.front().size, 0u);
  EXPECT_FALSE(held.push(hesai_test::view(too_long), 9));
  EXPECT_TRUE(held.push(hesai_test::view(a), 10));
  EXPECT_TRUE(held.push(hesai_test::view(b), 11));
  EXPECT_TRUE(held.full());
  EXPECT_FALSE(held.push(hesai_test::view(c), 12));
  ASSERT_EQ(held.front().size, 3u);
  EXPECT_EQ(held.front()[2], 3);
  EXPECT_EQ(held.front_tag(), 10u);
  held.pop_front();
  EXPECT_TRUE(held.push(hesai_test::view(c), 12));  // wraps round
  ASSERT_EQ(held.front().size, 2u);
  EXPECT_EQ(held.front()[0], 4);
  EXPECT_EQ(held.front_tag(), 11u);
  held.pop_front();
  ASSERT_EQ(held.size(), 1u);
  EXPECT_EQ(held.front()[0], 6);
  EXPECT_EQ(held.front_tag(), 12u);
  held.clear();
  EXPECT_TRUE(held.empty());
  held.pop_front();  // nothing to drop
  EXPECT_EQ(held.size(), 0u);
  // The longest packet fits.
  const std::vector<std::uint8_t> longest(hesai::kMaxPacketBytes, 8);
  EXPECT_TRUE(held.push(hesai_test::view(longest)));
  EXPECT_EQ(held.front().size, hesai::kMaxPacketBytes);
}

}  // namespace
