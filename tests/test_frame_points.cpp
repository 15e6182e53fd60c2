// FrameAssembler::points(), a block's points at once, against point() for each of them in order:
// hand-made blocks at the fast path's edges (every expected id worked out in the comments), long
// pseudo-random streams, and every block of the bundled captures, both ways, at several cuts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "hesai/frame.h"
#include "packet_builder.h"
#include "test_support.h"

namespace {

using hesai::AzimuthSpread;
using hesai::Error;
using hesai::FrameAssembler;
using hesai::FrameInfo;
using hesai::Rotation;

// Field by field; `where` says which frame of which stream.
::testing::AssertionResult same_frame(const FrameInfo& a, const FrameInfo& b) {
  auto fail = [&](const char* field, std::uint64_t x, std::uint64_t y) {
    return ::testing::AssertionFailure() << "frame " << a.id << ": " << field << " " << x << " (point) vs " << y
                                         << " (points)";
  };
  if (a.id != b.id) return fail("id", a.id, b.id);
  if (a.first_packet != b.first_packet) return fail("first_packet", a.first_packet, b.first_packet);
  if (a.last_packet != b.last_packet) return fail("last_packet", a.last_packet, b.last_packet);
  if (a.packets != b.packets) return fail("packets", a.packets, b.packets);
  if (a.blocks != b.blocks) return fail("blocks", a.blocks, b.blocks);
  if (a.points != b.points) return fail("points", a.points, b.points);
  if (a.late_points != b.late_points) return fail("late_points", a.late_points, b.late_points);
  if (a.lost_packets != b.lost_packets) return fail("lost_packets", a.lost_packets, b.lost_packets);
  if (a.loss != b.loss) return fail("loss", a.loss, b.loss);
  if (a.starts_at_cut != b.starts_at_cut) return fail("starts_at_cut", a.starts_at_cut, b.starts_at_cut);
  if (a.ends_at_cut != b.ends_at_cut) return fail("ends_at_cut", a.ends_at_cut, b.ends_at_cut);
  if (a.first_azimuth_cdeg != b.first_azimuth_cdeg) return fail("first_azimuth_cdeg", a.first_azimuth_cdeg, b.first_azimuth_cdeg);
  if (a.last_azimuth_cdeg != b.last_azimuth_cdeg) return fail("last_azimuth_cdeg", a.last_azimuth_cdeg, b.last_azimuth_cdeg);
  return ::testing::AssertionSuccess();
}

// Two assemblers fed the same stream: `one` with point() for each point, `block` with points().
// Every call's result, every closed frame and the counters are compared as they come.
struct Twins {
  FrameAssembler one, block;
  std::uint64_t frames = 0, single = 0, mixed = 0;  // frames compared; blocks points() gave one id / 0

  template <typename F>
  void both(F f) {
    f(one);
    f(block);
  }
  ::testing::AssertionResult take() {
    for (;;) {
      FrameInfo a, b;
      const bool ha = one.pop_closed(a), hb = block.pop_closed(b);
      if (ha != hb) return ::testing::AssertionFailure() << "pop_closed " << ha << " (point) vs " << hb << " (points)";
      if (!ha) break;
      ++frames;
      if (auto r = same_frame(a, b); !r) return r;
    }
    return state();
  }
  ::testing::AssertionResult state() {
    if (one.frames_dropped() != block.frames_dropped())
      return ::testing::AssertionFailure() << "frames_dropped " << one.frames_dropped() << " vs " << block.frames_dropped();
    if (one.is_open() != block.is_open()) return ::testing::AssertionFailure() << "is_open differs";
    return same_frame(one.current(), block.current());
  }
  ::testing::AssertionResult block_azimuth(std::uint16_t cdeg, bool pop = true) {
    const bool a = one.block(cdeg), b = block.block(cdeg);
    if (a != b) return ::testing::AssertionFailure() << "block(" << cdeg << ") " << a << " vs " << b;
    return pop ? take() : state();
  }
  // The points of the last block: `first` and `stride` as points() takes them; ids_out or null.
  ::testing::AssertionResult points(const float* first, std::size_t count, std::size_t stride, bool want_ids) {
    std::vector<std::uint64_t> want(count), got(count, ~0ull);
    bool all_one = true;
    for (std::size_t i = 0; i < count; ++i) {
      float az;
      std::memcpy(&az, reinterpret_cast<const unsigned char*>(first) + i * stride, sizeof az);
      want[i] = one.point(az);
      all_one = all_one && want[i] == want[0];
    }
    const std::uint64_t id = block.points(first, count, stride, want_ids ? got.data() : nullptr);
    if (count == 0) {
      if (id != 0) return ::testing::AssertionFailure() << "no points, id " << id;
    } else if (all_one) {
      if (id != want[0]) return ::testing::AssertionFailure() << "one frame " << want[0] << ", points() gave " << id;
      ++single;
    } else {
      if (id != 0) return ::testing::AssertionFailure() << "several frames, points() gave " << id;
      ++mixed;
      for (std::size_t i = 0; want_ids && i < count; ++i)
        if (got[i] != want[i]) return ::testing::AssertionFailure() << "point " << i << ": " << want[i] << " vs " << got[i];
    }
    return state();
  }
  ::testing::AssertionResult points(const std::vector<float>& az, bool want_ids = true) {
    return points(az.data(), az.size(), sizeof(float), want_ids);
  }
  ::testing::AssertionResult finish() {
    const bool a = one.finish(), b = block.finish();
    if (a != b) return ::testing::AssertionFailure() << "finish " << a << " vs " << b;
    return take();
  }
};

// ---- Hand-made blocks at the edges of the fast path ----

// Cut 0 clockwise, no spread: blocks 350.00, 350.10 ... 359.90 (100 blocks), each with one point
// at its own azimuth. The stream starts 10 degrees before the cut: frame 1, a partial turn.
Twins ten_degrees_before_the_cut(Rotation rotation) {
  Twins t;
  t.both([&](FrameAssembler& fa) { fa.set_rotation(rotation); });
  const bool cw = rotation == Rotation::clockwise;
  for (std::uint16_t k = 0; k < 100; ++k) {
    const std::uint16_t az = static_cast<std::uint16_t>(cw ? 35000 + 10 * k : 1000 - 10 * k);
    t.both([&](FrameAssembler& fa) { fa.begin_packet(k, 0); });
    EXPECT_TRUE(t.block_azimuth(az));
    EXPECT_TRUE(t.points({static_cast<float>(az) / 100.0f}));
  }
  return t;
}

class EdgeCases : public ::testing::TestWithParam<Rotation> {
 protected:
  bool cw() const { return GetParam() == Rotation::clockwise; }
  // Clockwise the blocks climb to 359.90 and the next is 0.00; counter-clockwise they fall to
  // 0.10 and the next is 0.00 again (the cut is where a rotation starts either way).
  float before_cut(float by) const { return cw() ? 360.0f - by : by; }
  std::uint16_t last_block() const { return static_cast<std::uint16_t>(cw() ? 35990 : 10); }
};

TEST_P(EdgeCases, BlockWhosePointsAllLieJustBeforeTheCut) {
  Twins t = ten_degrees_before_the_cut(GetParam());
  // The last block before the cut (359.90 clockwise, 0.10 counter-clockwise), its points up to
  // 0.001 degree short of the cut: all in frame 1, and frame 2 not opened.
  t.both([](FrameAssembler& fa) { fa.begin_packet(100, 0); });
  ASSERT_TRUE(t.block_azimuth(last_block()));
  const std::vector<float> az{before_cut(0.1f), before_cut(0.05f), before_cut(0.01f), before_cut(0.001f)};
  std::uint64_t ids[4] = {};
  EXPECT_EQ(t.block.points(az.data(), az.size(), sizeof(float), ids), 1u);
  for (float a : az) EXPECT_EQ(t.one.point(a), 1u);
  ASSERT_TRUE(t.state());
  // The block at 0.00 passes the cut and closes frame 1 (no spread): 100 + 1 blocks (the last
  // one twice, as a dual return's), 100 + 4 points.
  t.both([](FrameAssembler& fa) { fa.begin_packet(101, 0); });
  ASSERT_TRUE(t.block.block(0));
  ASSERT_TRUE(t.one.block(0));
  FrameInfo f;
  ASSERT_TRUE(t.block.pop_closed(f));
  EXPECT_EQ(f.id, 1u);
  EXPECT_EQ(f.blocks, 101u);
  EXPECT_EQ(f.points, 104u);
  EXPECT_EQ(f.late_points, 0u);
  EXPECT_TRUE(f.ends_at_cut);
  EXPECT_EQ(t.block.current().id, 2u);
  EXPECT_EQ(t.block.current().points, 0u);  // no point of the last block went ahead
  EXPECT_TRUE(t.block.current().starts_at_cut);
}

TEST_P(EdgeCases, BlockExactlyOnTheCut) {
  Twins t = ten_degrees_before_the_cut(GetParam());
  // The block at 0.00 starts frame 2; its points at 0.00 and up to 0.05 forward are all in it.
  t.both([](FrameAssembler& fa) { fa.begin_packet(100, 0); });
  ASSERT_TRUE(t.block_azimuth(0));
  EXPECT_EQ(t.frames, 1u);
  const std::vector<float> az{0.0f, cw() ? 0.01f : 359.99f, cw() ? 0.05f : 359.95f};
  // 359.99 from a block at 0.00 is 0.01 forward counter-clockwise, but its raw offset (35999)
  // needs the half-turn fold: point by point, the same frame.
  EXPECT_EQ(t.block.points(az.data(), 1, sizeof(float), nullptr), 2u);
  EXPECT_EQ(t.one.point(az[0]), 2u);
  EXPECT_TRUE(t.points({az[1], az[2]}));
  EXPECT_EQ(t.block.current().id, 2u);
  EXPECT_EQ(t.block.current().points, 3u);
  // As Points (stride 40), ids_out null.
  hesai::Point p[2];
  p[0].azimuth_deg = 0.0f;
  p[1].azimuth_deg = 0.0f;
  EXPECT_EQ(t.block.points(&p[0].azimuth_deg, 2, sizeof(hesai::Point), nullptr), 2u);
  EXPECT_EQ(t.block.current().points, 5u);
}

TEST_P(EdgeCases, OnePointExactlyOnTheCutOpensTheNextFrame) {
  Twins t = ten_degrees_before_the_cut(GetParam());
  t.both([](FrameAssembler& fa) { fa.begin_packet(100, 0); });
  ASSERT_TRUE(t.block_azimuth(last_block()));
  // Points 0.1 and 0.05 short of the cut, then one exactly on it: that one belongs to the
  // rotation that starts there, frame 2, which it opens early. Clockwise the cut as 360.00 is
  // +0.10 from the block (no fold), as 0.00 it is -359.90 (folded); counter-clockwise 0.00 is
  // -0.10 from 0.10, forward +0.10.
  const std::vector<float> az{before_cut(0.1f), before_cut(0.05f), cw() ? 360.0f : 0.0f};
  std::uint64_t ids[3] = {};
  EXPECT_EQ(t.block.points(az.data(), az.size(), sizeof(float), ids), 0u);
  EXPECT_EQ(ids[0], 1u);
  EXPECT_EQ(ids[1], 1u);
  EXPECT_EQ(ids[2], 2u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(t.one.point(az[i]), ids[i]);
  ASSERT_TRUE(t.state());
  EXPECT_TRUE(t.block.is_open());
  // The same with the cut written 0.00 clockwise (a fold): frame 2 again, now open.
  if (cw()) {
    const std::vector<float> folded{359.95f, 0.0f};
    EXPECT_EQ(t.block.points(folded.data(), 2, sizeof(float), ids), 0u);
    EXPECT_EQ(ids[0], 1u);
    EXPECT_EQ(ids[1], 2u);
    for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(t.one.point(folded[i]), ids[i]);
    // Frame 2 open, every point of a block on the cut's far side goes there in one step.
    const float ahead[2] = {360.0f, 360.05f};
    EXPECT_EQ(t.block.points(ahead, 2, sizeof(float), nullptr), 2u);
    for (float a : ahead) EXPECT_EQ(t.one.point(a), 2u);
  }
  // The block at the cut: frame 1 closes with 100 + 1 blocks and 100 + 2 (+ 1) points.
  t.both([](FrameAssembler& fa) { fa.begin_packet(101, 0); });
  ASSERT_TRUE(t.block.block(0));
  ASSERT_TRUE(t.one.block(0));
  FrameInfo a, b;
  ASSERT_TRUE(t.one.pop_closed(a));
  ASSERT_TRUE(t.block.pop_closed(b));
  EXPECT_TRUE(same_frame(a, b));
  EXPECT_EQ(b.points, cw() ? 103u : 102u);
  EXPECT_EQ(t.block.current().points, cw() ? 4u : 1u);
}

TEST_P(EdgeCases, EveryPointAheadPastTheCutOpensTheNextFrame) {
  Twins t = ten_degrees_before_the_cut(GetParam());
  t.both([](FrameAssembler& fa) { fa.begin_packet(100, 0); });
  ASSERT_TRUE(t.block_azimuth(last_block()));
  // Every point of the block 0.10 short of the cut lies past it (a calibration wider than the
  // spread, none here): all in frame 2, which the first of them opens.
  const std::vector<float> az{cw() ? 360.0f : 0.0f, cw() ? 360.05f : 359.95f, cw() ? 360.5f : 359.5f};
  std::uint64_t ids[3] = {};
  EXPECT_EQ(t.block.points(az.data(), az.size(), sizeof(float), ids), 2u);
  for (float a : az) EXPECT_EQ(t.one.point(a), 2u);
  ASSERT_TRUE(t.state());
  EXPECT_TRUE(t.block.is_open());
  // Open now: the next such block goes there in one step.
  EXPECT_TRUE(t.points(az));
  // The block at the cut enters frame 2, which holds the 6 points.
  t.both([](FrameAssembler& fa) { fa.begin_packet(101, 0); });
  EXPECT_TRUE(t.block_azimuth(0));
  EXPECT_EQ(t.block.current().id, 2u);
  EXPECT_EQ(t.block.current().points, 6u);
  EXPECT_TRUE(t.finish());
}

TEST_P(EdgeCases, PointsHalfATurnFromTheirBlock) {
  // Cut 0, a stream from 170.00 to 180.00 in steps of 0.25 degree (exact in binary): block
  // 180.00 lies 180.00 past the cut either way. point() takes offsets in (-180, 180] clockwise.
  // Clockwise: a point at 0.00 is -180 from the block, folded to +180: 360.00 past the cut, the
  // next rotation (frame 2, which it opens); 360.00 is +180 unfolded, the same. Counter-clockwise
  // +180 clockwise is 180 behind: both lie 0.00 past the cut, on it, in frame 1.
  Twins t;
  t.both([&](FrameAssembler& fa) { fa.set_rotation(GetParam()); });
  for (std::uint16_t k = 0; k <= 40; ++k) {
    t.both([&](FrameAssembler& fa) { fa.begin_packet(k, 0); });
    ASSERT_TRUE(t.block_azimuth(static_cast<std::uint16_t>(cw() ? 17000 + 25 * k : 19000 - 25 * k)));
  }
  const std::uint64_t half_turn_frame = cw() ? 2 : 1;
  for (float a : {0.0f, 360.0f}) {
    std::uint64_t id = 0;
    EXPECT_EQ(t.block.points(&a, 1, sizeof(float), &id), half_turn_frame);
    EXPECT_EQ(t.one.point(a), half_turn_frame);
    ASSERT_TRUE(t.state());
  }
  EXPECT_TRUE(t.points({0.0f, 360.0f, 180.0f, 0.0f}));  // 180.00, on its block, in frame 1
  EXPECT_TRUE(t.points({180.0f, 90.0f, 270.0f}));       // all within the frame of their block
  EXPECT_TRUE(t.points({0.0f, 360.0f}));
  EXPECT_EQ(t.block.current().id, 1u);
  // Clockwise the 180.00, 90.00 and 270.00 points; counter-clockwise all 11.
  EXPECT_EQ(t.block.current().points, cw() ? 4u : 11u);
}

TEST_P(EdgeCases, NotAnAzimuthAndBeforeTheFirstBlock) {
  Twins t;
  t.both([&](FrameAssembler& fa) { fa.set_rotation(GetParam()); });
  t.both([](FrameAssembler& fa) { fa.begin_packet(0, 0); });
  // Before any block: counted in the first frame to open (id 1).
  EXPECT_TRUE(t.points({10.0f, 20.0f}));
  ASSERT_TRUE(t.block_azimuth(1000));
  EXPECT_EQ(t.block.current().points, 2u);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  // NaN, infinities and azimuths beyond two turns count as their block's, wherever they stand.
  for (float bad : {nan, -nan, inf, -inf, 720.0f, -360.5f, 1e30f}) {
    EXPECT_TRUE(t.points({10.0f, bad}));
    EXPECT_TRUE(t.points({bad, 10.0f, 10.01f}));
    EXPECT_TRUE(t.points({bad}));
  }
  // -360 and 719.99 are azimuths (a turn either side).
  EXPECT_TRUE(t.points({-350.0f, 370.0f, 10.0f}));
  EXPECT_TRUE(t.points({}));
  EXPECT_EQ(t.block.points(nullptr, 0, sizeof(float), nullptr), 0u);
}

INSTANTIATE_TEST_SUITE_P(BothWays, EdgeCases, ::testing::Values(Rotation::clockwise, Rotation::counterclockwise),
                         [](const auto& i) { return i.param == Rotation::clockwise ? "clockwise" : "counterclockwise"; });

TEST(FramePoints, NegativeAzimuthsGoPointByPoint) {
  // Cut 350 clockwise, spread +-10 degrees: blocks 340.00, 341.00 ... 359.00, 0.00, 1.00, one a
  // packet. Frame 2 starts at 350.00 and frame 1 closes at 0.00 (10 past the cut): block 1.00 lies
  // 11.00 into frame 2. Its points 0.50 and -0.50 lie 10.50 and 9.50 past the cut (frame 2);
  // 200.00 is +199 raw, folded to 161 behind: frame 1, closed, so late, counted in frame 2.
  // Sorted as unsigned bits, -0.50 comes above 200.00: a sign bit must send the block point by point.
  Twins t;
  t.both([](FrameAssembler& fa) {
    EXPECT_EQ(fa.set_cut_deg(350.0f), Error::ok);
    EXPECT_EQ(fa.set_beam_spread(AzimuthSpread{-10.0f, 10.0f}), Error::ok);
  });
  for (std::uint16_t k = 0; k <= 22; ++k) {
    t.both([&](FrameAssembler& fa) { fa.begin_packet(k, 0); });
    ASSERT_TRUE(t.block_azimuth(static_cast<std::uint16_t>((34000 + 100 * k) % 36000)));
  }
  EXPECT_EQ(t.frames, 1u);
  EXPECT_EQ(t.block.current().id, 2u);
  const float az[3] = {0.5f, -0.5f, 200.0f};
  EXPECT_EQ(t.block.points(az, 3, sizeof(float), nullptr), 2u);
  for (float a : az) EXPECT_EQ(t.one.point(a), 2u);
  EXPECT_TRUE(t.state());
  EXPECT_EQ(t.block.current().points, 3u);
  EXPECT_EQ(t.block.current().late_points, 1u);
}

// ---- Pseudo-random streams ----

// splitmix64: the same numbers on every platform and standard library.
struct Random {
  std::uint64_t s;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>(next() % n); }
  bool chance(std::uint32_t percent) { return below(100) < percent; }
  float uniform(float lo, float hi) {
    return lo + (hi - lo) * static_cast<float>(static_cast<double>(next() >> 40) / static_cast<double>(1ull << 24));
  }
};

// One stream: rotation, cut, spread and the habits of its blocks and points drawn from `seed`.
// Blocks move forward by a step (with equal azimuths, jitter back, big jumps, gaps with
// lost_before > 0, azimuths >= 36000); points lie within the spread of their block, and some
// wider, on the cut exactly, a turn away, folded into [0, 360) or not, NaN, infinite, or beyond
// two turns. Fed to both assemblers as a float column or as Points, with or without ids_out;
// now and then the cut, the rotation or the spread changes, the stream finishes and starts
// again, or closed frames are left untaken (frames_dropped).
::testing::AssertionResult random_stream(std::uint64_t seed, Twins& t) {
  Random r{seed};
  const bool cw = r.chance(50);
  const float cuts[] = {0.0f, 359.99f, 90.0f, 180.5f, 0.01f, 359.0f, r.uniform(0.0f, 360.0f)};
  const float cut = cuts[r.below(7)];
  const float spreads[][2] = {{0, 0}, {-1, 1}, {-15, 15}, {-10, 0}, {0, 5}, {-3, 12}, {-0.5f, 0.25f}};
  float lo = spreads[r.below(7)][0], hi = spreads[r.below(7)][1];
  if (r.chance(20)) {
    lo = -r.uniform(0.0f, 15.0f);
    hi = r.uniform(0.0f, 15.0f);
  }
  t.both([&](FrameAssembler& fa) {
    fa.set_rotation(cw ? Rotation::clockwise : Rotation::counterclockwise);
    EXPECT_EQ(fa.set_cut_deg(cut), Error::ok);
    EXPECT_EQ(fa.set_beam_spread(AzimuthSpread{lo, hi}), Error::ok);
  });
  // A third of the streams keep their blocks on multiples of 0.25 degree, which binary floats
  // hold exactly: their points half a turn away are exactly there, where point() folds.
  const std::int64_t grid = r.chance(30) ? 25 : 1;
  const std::uint32_t step = static_cast<std::uint32_t>(grid) * (1 + r.below(r.chance(30) ? 400 : 60));  // cdeg a block, forward
  const std::uint32_t blocks_per_packet = 1 + r.below(12);
  const std::uint32_t max_points = r.below(70);
  const std::uint32_t wild = r.below(8);  // percent of points not within the spread
  std::int64_t az = grid * r.below(36000 / static_cast<std::uint32_t>(grid));
  const std::uint32_t packets = 20 + r.below(100);

  std::vector<float> column;
  std::vector<hesai::Point> pts;
  for (std::uint32_t p = 0; p < packets; ++p) {
    const std::uint32_t lost = r.chance(3) ? 1 + r.below(r.chance(30) ? 2000 : 20) : 0;
    if (r.chance(1)) {
      const float c = r.uniform(0.0f, 360.0f);
      t.both([&](FrameAssembler& fa) { EXPECT_EQ(fa.set_cut_deg(c), Error::ok); });
    }
    if (r.chance(1)) {
      const bool now_cw = r.chance(50);
      t.both([&](FrameAssembler& fa) { fa.set_rotation(now_cw ? Rotation::clockwise : Rotation::counterclockwise); });
    }
    if (r.chance(1)) {
      const AzimuthSpread s{-r.uniform(0.0f, 15.0f), r.uniform(0.0f, 15.0f)};
      lo = s.min_deg;
      hi = s.max_deg;
      t.both([&](FrameAssembler& fa) { EXPECT_EQ(fa.set_beam_spread(s), Error::ok); });
    }
    if (r.chance(1))
      if (auto e = t.finish(); !e) return e;
    const bool pop = !r.chance(2);
    t.both([&](FrameAssembler& fa) { fa.begin_packet(p, lost); });
    if (r.chance(2)) {  // points before the packet's first block (before the stream's, or of the last block)
      const std::uint32_t n = 1 + r.below(5);
      column.assign(n, r.uniform(0.0f, 360.0f));
      if (auto e = t.points(column); !e) return e;
    }
    if (lost > 0) az += static_cast<std::int64_t>(lost) * step * blocks_per_packet;
    for (std::uint32_t b = 0; b < blocks_per_packet; ++b) {
      const std::uint32_t how = r.below(100);
      if (how < 3) {
        az -= grid * (1 + r.below(300 / static_cast<std::uint32_t>(grid)));  // a step back: jitter or a late block
      } else if (how < 5) {
        az += grid * ((9000 + r.below(18000)) / grid);  // a jump of a quarter to three quarters of a turn
      } else if (how >= 15) {
        az += step;  // else the same azimuth (a dual return's second block)
      }
      az = ((az % 36000) + 36000) % 36000;
      // The blocks as sent: their values grow clockwise, fall counter-clockwise.
      std::uint16_t sent = static_cast<std::uint16_t>(cw ? az : (36000 - az) % 36000);
      if (r.chance(1)) sent = static_cast<std::uint16_t>(36000 + r.below(29536));  // not an azimuth: ignored
      if (auto e = t.block_azimuth(sent, pop); !e) return e << " (packet " << p << ", block " << b << ")";
      const float block_deg = static_cast<float>(sent % 36000) / 100.0f;
      const std::uint32_t n = r.below(max_points + 1);
      column.resize(n);
      for (std::uint32_t i = 0; i < n; ++i) {
        float a = block_deg + r.uniform(lo, hi);
        if (r.below(100) < wild) {
          switch (r.below(10)) {
            case 0: a = std::numeric_limits<float>::quiet_NaN(); break;
            case 1: a = r.chance(50) ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity(); break;
            case 2: a = r.chance(50) ? 720.0f + r.uniform(0.0f, 100.0f) : -360.5f - r.uniform(0.0f, 100.0f); break;
            case 3: a = block_deg + r.uniform(-40.0f, 40.0f); break;  // wider than the spread
            case 4: a += r.chance(50) ? 360.0f : -360.0f; break;      // a turn away
            case 5: a = block_deg + r.uniform(-179.0f, 181.0f); break;
            case 6: a = block_deg + (r.chance(50) ? 180.0f : -180.0f); break;  // half a turn
            default: a = static_cast<float>(t.one.cut_cdeg()) / 100.0f + (r.chance(50) ? 0.0f : 360.0f); break;  // the cut
          }
        } else if (r.chance(50)) {
          if (a >= 360.0f) a -= 360.0f;  // folded into [0, 360), as the decoder gives them
          if (a < 0.0f) a += 360.0f;
        }
        column[i] = a;
      }
      // Points sorted by azimuth are what a fast path might wrongly take by their ends alone; the
      // decoder's come in channel order. Half the blocks each.
      if (r.chance(50))
        for (std::size_t i = 1; i < column.size(); ++i)
          for (std::size_t j = i; j > 0 && column[j - 1] > column[j]; --j) std::swap(column[j - 1], column[j]);
      ::testing::AssertionResult e = ::testing::AssertionSuccess();
      if (r.chance(50)) {
        e = t.points(column, !r.chance(20));
      } else {
        pts.resize(n);
        for (std::uint32_t i = 0; i < n; ++i) pts[i].azimuth_deg = column[i];
        e = t.points(n == 0 ? nullptr : &pts[0].azimuth_deg, n, sizeof(hesai::Point), !r.chance(20));
      }
      if (!e) return e << " (packet " << p << ", block " << b << ")";
    }
  }
  return t.finish();
}

TEST(FramePoints, RandomStreamsGiveWhatPointGives) {
  // 400 streams, about 2.5 million points: each id, each closed frame field by field, the
  // counters after every call.
  std::uint64_t frames = 0, single = 0, mixed = 0;
  for (std::uint64_t seed = 1; seed <= 400; ++seed) {
    Twins t;
    ASSERT_TRUE(random_stream(seed, t)) << "seed " << seed;
    frames += t.frames;
    single += t.single;
    mixed += t.mixed;
  }
  // The streams reach both outcomes often: one frame a block, and several.
  EXPECT_GT(frames, 1000u);
  EXPECT_GT(single, 10000u);
  EXPECT_GT(mixed, 1000u);
  RecordProperty("frames", std::to_string(frames));
  RecordProperty("blocks_one_frame", std::to_string(single));
  RecordProperty("blocks_several_frames", std::to_string(mixed));
}

// ---- The bundled captures ----

struct CaptureCase {
  const char* capture;
  hesai::Model model;
  Rotation rotation;
  float cut_deg;
};

void PrintTo(const CaptureCase& c, std::ostream* os) {
  *os << hesai::model_name(c.model) << (c.rotation == Rotation::clockwise ? " cw" : " ccw") << " cut " << c.cut_deg;
}

class CapturePoints : public ::testing::TestWithParam<CaptureCase> {};

// Every block of a capture (mirrored for counter-clockwise) through the decoder, its Points to
// one assembler point by point and to the other with points(): the same ids and frames.
TEST_P(CapturePoints, SameFramesAsPointByPoint) {
  const CaptureCase& c = GetParam();
  auto packets = hesai_test::pcap_payloads(c.capture);
  if (c.rotation == Rotation::counterclockwise)
    for (auto& p : packets) p = hesai_test::counterclockwise_copy(p, c.model);
  hesai::Decoder dec(c.model);
  dec.set_rotation(c.rotation);
  Twins t;
  t.both([&](FrameAssembler& fa) {
    fa.set_rotation(c.rotation);
    EXPECT_EQ(fa.set_cut_deg(c.cut_deg), Error::ok);
  });
  hesai::PacketPoints pts;
  hesai::PacketInfo info;
  std::uint64_t blocks = 0;
  for (std::uint64_t i = 0; i < packets.size(); ++i) {
    ASSERT_EQ(dec.decode(hesai_test::view(packets[static_cast<std::size_t>(i)]), info, pts), Error::ok);
    t.both([&](FrameAssembler& fa) {
      EXPECT_EQ(fa.set_beam_spread(dec.beam_spread()), Error::ok);
      fa.begin_packet(i, 0);
    });
    std::size_t next = 0;
    for (std::size_t b = 0; b < info.blocks; ++b) {
      ASSERT_TRUE(t.block_azimuth(info.block_azimuth[b])) << "packet " << i;
      const std::size_t start = next;
      while (next < pts.count && pts.points[next].block == b) ++next;
      if (next == start) continue;
      ++blocks;
      ASSERT_TRUE(t.points(&pts.points[start].azimuth_deg, next - start, sizeof(hesai::Point), true)) << "packet " << i;
    }
  }
  ASSERT_TRUE(t.finish());
  EXPECT_GE(t.frames, 3u);
  // Only the blocks within the spread of a cut give points to two frames: 2.4 % (Pandar40P) to
  // 5.3 % (QT128C2X) of the blocks here.
  EXPECT_EQ(t.single + t.mixed, blocks);
  EXPECT_LT(t.mixed * 10, blocks);
  RecordProperty("blocks_several_frames", std::to_string(t.mixed));
}

INSTANTIATE_TEST_SUITE_P(
    Bundled, CapturePoints,
    ::testing::Values(CaptureCase{"pandar64_dual.pcap", hesai::Model::pandar64, Rotation::clockwise, 0.0f},
                      CaptureCase{"pandar64_dual.pcap", hesai::Model::pandar64, Rotation::counterclockwise, 90.0f},
                      CaptureCase{"pandar64_dual.pcap", hesai::Model::pandar64, Rotation::clockwise, 180.5f},
                      CaptureCase{"pandar64_dual.pcap", hesai::Model::pandar64, Rotation::counterclockwise, 359.0f},
                      CaptureCase{"qt128c2x_dual.pcap", hesai::Model::qt128c2x, Rotation::clockwise, 0.0f},
                      CaptureCase{"qt128c2x_dual.pcap", hesai::Model::qt128c2x, Rotation::counterclockwise, 0.0f},
                      CaptureCase{"qt128c2x_dual.pcap", hesai::Model::qt128c2x, Rotation::clockwise, 90.0f},
                      CaptureCase{"qt128c2x_dual.pcap", hesai::Model::qt128c2x, Rotation::counterclockwise, 180.5f},
                      CaptureCase{"qt128c2x_dual.pcap", hesai::Model::qt128c2x, Rotation::clockwise, 359.0f},
                      CaptureCase{"pandar40p_dual.pcap", hesai::Model::pandar40p, Rotation::clockwise, 90.0f},
                      CaptureCase{"pandar40p_dual.pcap", hesai::Model::pandar40p, Rotation::counterclockwise, 359.0f},
                      CaptureCase{"pandar_xt32m2x.pcap", hesai::Model::pandar_xt32m2x, Rotation::clockwise, 180.5f}),
    [](const auto& i) {
      return std::string(hesai::model_name(i.param.model)) + (i.param.rotation == Rotation::clockwise ? "_cw_" : "_ccw_") +
             std::to_string(static_cast<int>(i.param.cut_deg * 100));
    });

}  // namespace
