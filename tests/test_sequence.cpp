// SequenceTracker: hand-made sequence streams; every expected count is worked out in the comments.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "hesai/sequence.h"

namespace {

using hesai::kSequenceWindow;
using hesai::SequenceEvent;
using hesai::SequenceTracker;

// Observes each number; returns what observe() returned for each.
std::vector<std::uint32_t> run(SequenceTracker& t, const std::vector<std::uint32_t>& seqs) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t s : seqs) out.push_back(t.observe(s));
  return out;
}

// Observes first..last inclusive, in order, skipping `skip`.
void run_range(SequenceTracker& t, std::uint32_t first, std::uint32_t last, std::uint32_t skip = 0xFFFFFFFFu) {
  for (std::uint32_t s = first;; ++s) {
    if (s != skip) t.observe(s);
    if (s == last) break;
  }
}

TEST(SequenceTracker, InOrder) {
  SequenceTracker t;
  EXPECT_EQ(t.last_event(), SequenceEvent::none);
  EXPECT_EQ(run(t, {10, 11, 12, 13}), (std::vector<std::uint32_t>{0, 0, 0, 0}));
  EXPECT_EQ(t.last_event(), SequenceEvent::in_order);
  EXPECT_EQ(t.counts().packets, 4u);
  EXPECT_EQ(t.counts().lost, 0u);
  EXPECT_EQ(t.counts().duplicates, 0u);
  EXPECT_EQ(t.counts().reordered, 0u);
  EXPECT_EQ(t.newest(), 13u);
}

TEST(SequenceTracker, FirstNumberIsNotALoss) {
  SequenceTracker t;
  EXPECT_EQ(t.observe(1000), 0u);
  EXPECT_EQ(t.last_event(), SequenceEvent::first);
  EXPECT_EQ(t.counts().lost, 0u);
}

TEST(SequenceTracker, Drops) {
  // 1 2 5 6 9: 3 and 4 missing before 5, 7 and 8 before 9: lost 4.
  SequenceTracker t;
  EXPECT_EQ(run(t, {1, 2, 5, 6, 9}), (std::vector<std::uint32_t>{0, 0, 2, 0, 2}));
  EXPECT_EQ(t.last_event(), SequenceEvent::gap);
  EXPECT_EQ(t.counts().lost, 4u);
  EXPECT_EQ(t.counts().reordered, 0u);
}

TEST(SequenceTracker, Duplicates) {
  // 1 2 2 3 1: the second 2 and the second 1 are copies.
  SequenceTracker t;
  run(t, {1, 2, 2});
  EXPECT_EQ(t.last_event(), SequenceEvent::duplicate);
  run(t, {3, 1});
  EXPECT_EQ(t.last_event(), SequenceEvent::duplicate);
  EXPECT_EQ(t.counts().duplicates, 2u);
  EXPECT_EQ(t.counts().lost, 0u);
  EXPECT_EQ(t.counts().reordered, 0u);
}

TEST(SequenceTracker, LateArrivalIsReorderedNotLost) {
  // 1 2 4: 3 lost (lost 1). 3 arrives: reordered 1, lost 0. 3 again: duplicate.
  SequenceTracker t;
  EXPECT_EQ(run(t, {1, 2, 4}), (std::vector<std::uint32_t>{0, 0, 1}));
  EXPECT_EQ(t.counts().lost, 1u);
  EXPECT_EQ(t.observe(3), 0u);
  EXPECT_EQ(t.last_event(), SequenceEvent::late);
  EXPECT_EQ(t.counts().lost, 0u);
  EXPECT_EQ(t.counts().reordered, 1u);
  t.observe(3);
  EXPECT_EQ(t.counts().duplicates, 1u);
  EXPECT_EQ(t.counts().reordered, 1u);
  EXPECT_EQ(t.newest(), 4u);
}

TEST(SequenceTracker, Mixed) {
  // 1 2 3 5 4 4 7 8 6 10:
  //   5: 4 missing (lost 1); 4: late (lost 0, reordered 1); 4: duplicate (1);
  //   7: 6 missing (lost 1); 6: late (lost 0, reordered 2); 10: 9 missing (lost 1).
  SequenceTracker t;
  EXPECT_EQ(run(t, {1, 2, 3, 5, 4, 4, 7, 8, 6, 10}), (std::vector<std::uint32_t>{0, 0, 0, 1, 0, 0, 1, 0, 0, 1}));
  EXPECT_EQ(t.counts().packets, 10u);
  EXPECT_EQ(t.counts().lost, 1u);
  EXPECT_EQ(t.counts().duplicates, 1u);
  EXPECT_EQ(t.counts().reordered, 2u);
  EXPECT_EQ(t.counts().stale, 0u);
  EXPECT_EQ(t.counts().resyncs, 0u);
}

TEST(SequenceTracker, WrapAt2To32) {
  // 0xFFFFFFFE 0xFFFFFFFF 0 1: consecutive across the wrap.
  SequenceTracker t;
  EXPECT_EQ(run(t, {0xFFFFFFFEu, 0xFFFFFFFFu, 0, 1}), (std::vector<std::uint32_t>{0, 0, 0, 0}));
  EXPECT_EQ(t.counts().lost, 0u);
  EXPECT_EQ(t.counts().resyncs, 0u);
  // 0xFFFFFFFE 1: 0xFFFFFFFF and 0 missing (lost 2). Then 0 and 0xFFFFFFFF late: lost 0, reordered 2.
  SequenceTracker u;
  EXPECT_EQ(run(u, {0xFFFFFFFEu, 1}), (std::vector<std::uint32_t>{0, 2}));
  EXPECT_EQ(u.counts().lost, 2u);
  u.observe(0);
  EXPECT_EQ(u.counts().lost, 1u);
  u.observe(0xFFFFFFFFu);
  EXPECT_EQ(u.counts().lost, 0u);
  EXPECT_EQ(u.counts().reordered, 2u);
  EXPECT_EQ(u.counts().resyncs, 0u);
  EXPECT_EQ(u.newest(), 1u);
}

TEST(SequenceTracker, LateAtTheEdgeOfTheWindow) {
  // 0, 2..4096: 1 lost. Newest 4096; 1 is 4095 behind: inside the 4096-number window.
  static_assert(kSequenceWindow == 4096, "the numbers below assume a 4096 window");
  SequenceTracker t;
  run_range(t, 0, 4096, 1);
  EXPECT_EQ(t.counts().lost, 1u);
  t.observe(1);
  EXPECT_EQ(t.last_event(), SequenceEvent::late);
  EXPECT_EQ(t.counts().lost, 0u);
  EXPECT_EQ(t.counts().reordered, 1u);
  EXPECT_EQ(t.counts().stale, 0u);
}

TEST(SequenceTracker, FarLateBeyondTheWindow) {
  // 0, 2..4097: 1 lost. Newest 4097; 1 is 4096 behind: outside the window. It counts as
  // reordered and stale; lost stays 1 (the tracker no longer knows it was counted lost).
  SequenceTracker t;
  run_range(t, 0, 4097, 1);
  EXPECT_EQ(t.counts().lost, 1u);
  EXPECT_EQ(t.observe(1), 0u);
  EXPECT_EQ(t.last_event(), SequenceEvent::stale);
  // The stream goes on at 4098: 1 was a late packet, not a restart.
  EXPECT_EQ(t.observe(4098), 0u);
  EXPECT_EQ(t.last_event(), SequenceEvent::in_order);
  EXPECT_EQ(t.counts().lost, 1u);
  EXPECT_EQ(t.counts().reordered, 1u);
  EXPECT_EQ(t.counts().stale, 1u);
  EXPECT_EQ(t.counts().resyncs, 0u);
  EXPECT_EQ(t.newest(), 4098u);
}

TEST(SequenceTracker, FarLateCopiesCountEachTime) {
  // 0..5000, then 100 twice (each far behind; the second does not follow the first), then 5001.
  SequenceTracker t;
  run_range(t, 0, 5000);
  run(t, {100, 100, 5001});
  EXPECT_EQ(t.counts().reordered, 2u);
  EXPECT_EQ(t.counts().stale, 2u);
  EXPECT_EQ(t.counts().resyncs, 0u);
  EXPECT_EQ(t.counts().lost, 0u);
}

TEST(SequenceTracker, NumbersBeforeTheFirstAreReorderedNotLost) {
  // 1000, then 999: never counted lost, so lost stays 0 (and does not wrap below 0).
  SequenceTracker t;
  run(t, {1000, 999});
  EXPECT_EQ(t.last_event(), SequenceEvent::late);
  EXPECT_EQ(t.counts().lost, 0u);
  EXPECT_EQ(t.counts().reordered, 1u);
  t.observe(999);
  EXPECT_EQ(t.counts().duplicates, 1u);
  // 1000 1002 (1001 lost: lost 1), then 998 from before the start: lost stays 1.
  SequenceTracker u;
  run(u, {1000, 1002, 998});
  EXPECT_EQ(u.counts().lost, 1u);
  EXPECT_EQ(u.counts().reordered, 1u);
  u.observe(1001);  // this one was counted lost
  EXPECT_EQ(u.counts().lost, 0u);
  EXPECT_EQ(u.counts().reordered, 2u);
}

TEST(SequenceTracker, RestartToZero) {
  // 100000..100009, then the sensor restarts: 0 1 2 4.
  //   0: far behind, held (counted stale for now); 1 follows 0: restart at 0, the stale count is
  //   undone, resyncs 1; 2 in order; 4: 3 missing (lost 1).
  SequenceTracker t;
  run_range(t, 100000, 100009);
  EXPECT_EQ(run(t, {0, 1}), (std::vector<std::uint32_t>{0, 0}));
  EXPECT_EQ(t.last_event(), SequenceEvent::resync);
  EXPECT_EQ(t.counts().resyncs, 1u);
  EXPECT_EQ(t.counts().reordered, 0u);
  EXPECT_EQ(t.counts().stale, 0u);
  EXPECT_EQ(run(t, {2, 4}), (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(t.counts().lost, 1u);
  EXPECT_EQ(t.counts().packets, 14u);
  EXPECT_EQ(t.newest(), 4u);
}

TEST(SequenceTracker, RestartWithALossRightAfter) {
  // 100000..100009, 0, 3: restart at 0, and 1, 2 missing in the new series (lost 2).
  SequenceTracker t;
  run_range(t, 100000, 100009);
  EXPECT_EQ(run(t, {0, 3}), (std::vector<std::uint32_t>{0, 2}));
  EXPECT_EQ(t.counts().resyncs, 1u);
  EXPECT_EQ(t.counts().lost, 2u);
  // 1 arrives late in the new series.
  t.observe(1);
  EXPECT_EQ(t.counts().lost, 1u);
  EXPECT_EQ(t.counts().reordered, 1u);
}

TEST(SequenceTracker, JumpAheadBeyondTheWindowIsAResync) {
  // 0, 4096: a gap of exactly the window, 4095 lost.
  SequenceTracker t;
  EXPECT_EQ(run(t, {0, 4096}), (std::vector<std::uint32_t>{0, 4095}));
  EXPECT_EQ(t.counts().lost, 4095u);
  EXPECT_EQ(t.counts().resyncs, 0u);
  // 0, 4097: one more: a resync, nothing lost.
  SequenceTracker u;
  EXPECT_EQ(run(u, {0, 4097, 4098}), (std::vector<std::uint32_t>{0, 0, 0}));
  EXPECT_EQ(u.counts().resyncs, 1u);
  EXPECT_EQ(u.counts().lost, 0u);
  // 10, 11, 2000000000 (a restart far ahead): resync; not two billion lost.
  SequenceTracker v;
  run(v, {10, 11, 2000000000u, 2000000001u});
  EXPECT_EQ(v.counts().resyncs, 1u);
  EXPECT_EQ(v.counts().lost, 0u);
  EXPECT_EQ(v.newest(), 2000000001u);
}

TEST(SequenceTracker, StrayNumberFarAheadReadsAsTwoResyncs) {
  // 10 11 3000000 12 13: 3000000 resyncs there (1); 12 is then far behind, held; 13 follows 12:
  // resync back (2), and 12's stale count is undone. Nothing lost.
  SequenceTracker t;
  run(t, {10, 11, 3000000, 12, 13});
  EXPECT_EQ(t.counts().resyncs, 2u);
  EXPECT_EQ(t.counts().lost, 0u);
  EXPECT_EQ(t.counts().reordered, 0u);
  EXPECT_EQ(t.counts().stale, 0u);
  EXPECT_EQ(t.newest(), 13u);
}

TEST(SequenceTracker, TwoConsecutiveFarLatePacketsReadAsARestart) {
  // 0..5000, then 100 101 (held up together), then 5001: 101 follows 100 (resync 1); 5001 is
  // 4900 ahead of 101, beyond the window (resync 2). Documented limit.
  SequenceTracker t;
  run_range(t, 0, 5000);
  run(t, {100, 101, 5001});
  EXPECT_EQ(t.counts().resyncs, 2u);
  EXPECT_EQ(t.counts().reordered, 0u);
  EXPECT_EQ(t.counts().lost, 0u);
}

TEST(SequenceTracker, FollowerExactlyAWindowBehindTheNewestConfirmsARestart) {
  // 0..5000, 100 (far behind: held), then 904 = 5000 - 4096: outside the main window by one,
  // and 804 ahead of 100: the series restarted at 100 (resync 1); 101..903 lost (803).
  SequenceTracker t;
  run_range(t, 0, 5000);
  run(t, {100});
  EXPECT_EQ(t.observe(904), 803u);
  EXPECT_EQ(t.last_event(), SequenceEvent::resync);
  EXPECT_EQ(t.counts().resyncs, 1u);
  EXPECT_EQ(t.counts().lost, 803u);
  EXPECT_EQ(t.counts().stale, 0u);
}

TEST(SequenceTracker, HalfTheNumberSpaceIsFar) {
  // 0 then 0x80000000: RFC 1982 leaves this undefined; it is far (held as behind), and
  // 0x80000001 following it makes it a restart.
  SequenceTracker t;
  run(t, {0, 0x80000000u});
  EXPECT_EQ(t.last_event(), SequenceEvent::stale);
  t.observe(0x80000001u);
  EXPECT_EQ(t.last_event(), SequenceEvent::resync);
  EXPECT_EQ(t.counts().resyncs, 1u);
  EXPECT_EQ(t.counts().reordered, 0u);
  EXPECT_EQ(t.counts().lost, 0u);
}

TEST(SequenceTracker, Reset) {
  SequenceTracker t;
  run(t, {1, 5});
  t.reset();
  EXPECT_EQ(t.counts().lost, 0u);
  EXPECT_EQ(t.counts().packets, 0u);
  EXPECT_EQ(t.observe(100), 0u);
  EXPECT_EQ(t.last_event(), SequenceEvent::first);
}

}  // namespace
