// ReplayGuard (hesai/replay.h): RFC 4303's anti-replay window over the UDP sequence, and the packet
// time where a packet has no sequence. Expected values from the rule as the header states it.
#include <gtest/gtest.h>

#include <cstdint>

#include "hesai/replay.h"

namespace {

using hesai::kReplayTimes;
using hesai::kReplayWindow;
using hesai::PacketInfo;
using hesai::ReplayGuard;

PacketInfo seq(std::uint32_t n) {
  PacketInfo info;
  info.has_sequence = true;
  info.sequence = n;
  return info;
}

PacketInfo at(std::int64_t time_ns) {
  PacketInfo info;
  info.has_sequence = false;
  info.time_ns = time_ns;
  return info;
}

TEST(ReplayGuard, EachSequenceNumberOnce) {
  ReplayGuard g;
  EXPECT_TRUE(g.accept(seq(100)));
  EXPECT_FALSE(g.accept(seq(100)));  // the same number again
  EXPECT_TRUE(g.accept(seq(105)));   // ahead, 101..104 skipped
  for (std::uint32_t n = 101; n < 105; ++n) {
    EXPECT_TRUE(g.accept(seq(n))) << n;   // reordered: new once
    EXPECT_FALSE(g.accept(seq(n))) << n;  // then a replay
  }
  EXPECT_FALSE(g.accept(seq(105)));
  EXPECT_TRUE(g.accept(seq(106)));
}

TEST(ReplayGuard, TheWindowBehindTheNewest) {
  ReplayGuard g;
  const std::uint32_t newest = 5000;
  EXPECT_TRUE(g.accept(seq(newest - kReplayWindow - 10)));  // the first number of the session
  EXPECT_TRUE(g.accept(seq(newest)));  // ahead by more than the window: the bitmap starts anew
  EXPECT_TRUE(g.accept(seq(newest - (kReplayWindow - 1))));  // the oldest number still in the window, unseen
  EXPECT_FALSE(g.accept(seq(newest - kReplayWindow)));       // one further back: too old to know
  EXPECT_FALSE(g.accept(seq(newest - kReplayWindow - 10)));  // accepted once, now far behind
  EXPECT_FALSE(g.accept(seq(newest - 100000)));
}

// The bitmap holds numbers modulo the window: a number skipped by a step ahead is unseen, though
// the number a window before it (the same bit) was accepted.
TEST(ReplayGuard, ASkippedNumberIsNotTakenForTheOneAWindowBefore) {
  ReplayGuard g;
  for (std::uint32_t n = 0; n < kReplayWindow; ++n) ASSERT_TRUE(g.accept(seq(n))) << n;
  EXPECT_TRUE(g.accept(seq(kReplayWindow + 6)));  // kReplayWindow .. + 5 skipped
  for (std::uint32_t n = kReplayWindow; n < kReplayWindow + 6; ++n) EXPECT_TRUE(g.accept(seq(n))) << n;
  EXPECT_FALSE(g.accept(seq(6)));  // now a window behind the newest
}

TEST(ReplayGuard, AcrossTheWrapOfTheCounter) {
  ReplayGuard g;
  EXPECT_TRUE(g.accept(seq(0xFFFFFFFEu)));
  EXPECT_TRUE(g.accept(seq(1)));  // three ahead, across 0
  EXPECT_TRUE(g.accept(seq(0xFFFFFFFFu)));
  EXPECT_TRUE(g.accept(seq(0)));
  EXPECT_FALSE(g.accept(seq(0xFFFFFFFEu)));
  EXPECT_FALSE(g.accept(seq(0)));
  // Half the counter space away reads as behind (RFC 1982): refused.
  EXPECT_FALSE(g.accept(seq(1u + 0x80000000u)));
}

TEST(ReplayGuard, ResetForgetsTheSession) {
  ReplayGuard g;
  EXPECT_TRUE(g.accept(seq(7)));
  EXPECT_FALSE(g.accept(seq(7)));
  g.reset();
  EXPECT_TRUE(g.accept(seq(7)));  // a new key: the same number is a new packet
}

TEST(ReplayGuard, WithoutASequenceByTheTime) {
  ReplayGuard g;
  const std::int64_t t0 = 1700000000000000000;
  EXPECT_TRUE(g.accept(at(t0)));
  EXPECT_FALSE(g.accept(at(t0)));  // the same time again
  for (std::size_t i = 1; i < kReplayTimes; ++i) EXPECT_TRUE(g.accept(at(t0 + static_cast<std::int64_t>(i) * 1000))) << i;
  // kReplayTimes remembered, t0 the oldest: a time not after it is a replay, one between two
  // remembered ones that was not seen is new (reordered).
  EXPECT_FALSE(g.accept(at(t0 - 1)));
  EXPECT_FALSE(g.accept(at(t0)));
  EXPECT_TRUE(g.accept(at(t0 + 500)));  // t0 leaves the ring: t0 + 500 takes its place
  EXPECT_FALSE(g.accept(at(t0 + 500)));
  EXPECT_FALSE(g.accept(at(t0 + 1000)));  // remembered
  EXPECT_FALSE(g.accept(at(t0 + 400)));   // not after the oldest remembered (t0 + 500)
}

}  // namespace
