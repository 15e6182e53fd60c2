// Zero-allocation proof for frame assembly, sequence accounting and the integrity counters.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>

#include "alloc_counter.h"
#include "hesai/frame.h"
#include "hesai/sequence.h"
#include "hesai/stats.h"

TEST(ZeroAllocation, FramesSequenceStats) {
  hesai::FrameAssembler fa;
  hesai::SequenceTracker seq;
  hesai::Stats stats{};
  std::uint64_t frames = 0;
  hesai::Error cut = hesai::Error::truncated, fov = hesai::Error::truncated, spread = hesai::Error::truncated;
  const std::size_t n = hesai_test::allocations_during([&] {
    cut = fa.set_cut_deg(37.0f);
    fov = fa.set_fov_deg(300.0f, 60.0f);
    spread = fa.set_beam_spread(hesai::AzimuthSpread{-5.0f, 3.0f});
    // Three turns of 10-block packets with one packet in 50 dropped, a far jump and a restart.
    for (std::uint32_t p = 0; p < 540; ++p) {
      if (p % 50 == 49) continue;
      const std::uint32_t lost = seq.observe(p);
      fa.begin_packet(p, lost);
      for (std::uint32_t b = 0; b < 10; ++b) {
        const auto az = static_cast<std::uint16_t>((20 * (10 * p + b)) % 36000);
        if (fa.block(az))
          for (hesai::FrameInfo f; fa.pop_closed(f);) ++frames;
        // Point by point in even packets, the block's points at once (points()) in odd ones.
        float kept[8];
        std::uint64_t ids[8];
        std::size_t count = 0;
        for (int ch = -5; ch < 3; ++ch) {
          const float point_az = static_cast<float>((az + 36000 + 100 * ch) % 36000) / 100.0f;
          if (!fa.in_fov(point_az)) continue;
          if (p % 2 == 0) (void)fa.point(point_az);
          if (p % 2 == 1) kept[count++] = point_az;
        }
        (void)fa.points(kept, count, sizeof(float), ids);
      }
    }
    (void)seq.observe(1000000);
    (void)seq.observe(0);
    (void)seq.observe(1);
    fa.finish();
    for (hesai::FrameInfo f; fa.pop_closed(f);) ++frames;
    stats.frames = frames;
    stats.lost = seq.counts().lost;
    hesai::count_error(stats, hesai::Error::crc_body);
    hesai::count_error(stats, hesai::Error::bad_magic);
    hesai::count_model(stats, hesai::Model::pandar40p);
  });
  EXPECT_EQ(n, 0u);
  EXPECT_EQ(cut, hesai::Error::ok);
  EXPECT_EQ(fov, hesai::Error::ok);
  EXPECT_EQ(spread, hesai::Error::ok);
  // Azimuths 0 .. 3 turns from 0: the cut at 37 degrees is crossed 3 times, plus finish: 4.
  // (The first block, at 0, lies more than 5 degrees from the cut behind it: no frame before it.)
  EXPECT_EQ(frames, 4u);
  // Packets 49, 99, ..., 499, 549 > 539: 10 dropped within 0..539 (49 + 50 i, i = 0..9).
  EXPECT_EQ(seq.counts().lost, 10u);
  EXPECT_EQ(seq.counts().resyncs, 2u);  // 1000000 far ahead; then 0 far behind, confirmed by 1
}
