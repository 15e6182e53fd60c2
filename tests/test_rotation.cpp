// RotationDetector: hand-made azimuth streams (every move worked out in the comments) and the
// bundled captures, as recorded (clockwise) and mirrored (counter-clockwise).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

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

// The bundled captures spin clockwise; mirrored, counter-clockwise. Either way the third packet
// decides and nothing changes after it.
TEST(RotationDetector, BundledCapturesBothWays) {
  const struct {
    const char* file;
    hesai::Model model;
    std::size_t azimuth;  // offset of block 1's azimuth in the payload
  } cases[] = {{"pandar40p_dual.pcap", hesai::Model::pandar40p, 2},
               {"pandar64_dual.pcap", hesai::Model::pandar64, 8},
               {"qt128c2x_dual.pcap", hesai::Model::qt128c2x, 12}};
  for (const auto& c : cases) {
    for (const bool mirrored : {false, true}) {
      RotationDetector d;
      std::vector<std::size_t> decided;
      std::size_t i = 0;
      for (const auto& recorded : hesai_test::pcap_payloads(c.file)) {
        const auto p = mirrored ? hesai_test::counterclockwise_copy(recorded, c.model) : recorded;
        if (d.observe(hesai::load_le16(&p[c.azimuth]))) decided.push_back(i);
        ++i;
      }
      EXPECT_EQ(decided, (std::vector<std::size_t>{2})) << c.file << (mirrored ? " mirrored" : "");
      EXPECT_EQ(d.rotation(), mirrored ? Rotation::counterclockwise : Rotation::clockwise) << c.file;
    }
  }
}

}  // namespace
