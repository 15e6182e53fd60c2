// The Pipeline's runs (Sink::points): every kept point of every packet, as a decoder of its own
// makes them, in packet order; one frame a run, a new run of a packet only where the frame changes
// (near a cut the channels' azimuth offsets make a block's points alternate between two frames)
// or a frame closed; every point of a frame before its frame_closed(), as many as the frame
// counted; the return types, when wanted, those of nebula_return_type for each point.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "hesai/decoder.h"
#include "hesai/frame.h"
#include "hesai_port/formats/pointcloud2.h"
#include "hesai_port/pipeline/pipeline.h"
#include "test_support.h"

namespace {

using hesai::FrameInfo;
using hesai::Point;
using hesai::port::NebulaReturnType;
using hesai::port::PointRun;

struct Given {
  Point point;
  std::uint64_t frame, packet;
  NebulaReturnType type;
};

class RunRecorder : public hesai::port::Sink {
 public:
  explicit RunRecorder(bool types) : types_(types) {}
  void sensor_added(std::uint32_t, const std::string&) override {}
  void receive_time(std::uint64_t) override {}
  bool wants_return_types() const override { return types_; }
  void points(const PointRun& run) override {
    ++runs;
    EXPECT_GT(run.count, 0u);
    EXPECT_EQ(run.sensor, 0u);
    EXPECT_EQ(run.return_types != nullptr, types_);
    EXPECT_EQ(closed.count(run.frame), 0u) << "points of frame " << run.frame << " after it closed";
    if (have_last_ && last_packet_ == run.packet) {
      // The same packet again: its frame changed, or a frame closed in between.
      EXPECT_TRUE(last_frame_ != run.frame || closed_since_) << "packet " << run.packet << " split within frame " << run.frame;
      if (last_frame_ != run.frame) straddles.insert(run.packet);
    }
    have_last_ = true;
    last_packet_ = run.packet;
    last_frame_ = run.frame;
    closed_since_ = false;
    for (std::size_t i = 0; i < run.count; ++i)
      given.push_back({run.points[i], run.frame, run.packet,
                       run.return_types != nullptr ? run.return_types[i] : NebulaReturnType::unknown});
    per_frame[run.frame] += run.count;
  }
  void frame_closed(const FrameInfo& frame, std::uint32_t sensor) override {
    EXPECT_EQ(sensor, 0u);
    EXPECT_EQ(per_frame[frame.id], frame.points) << "frame " << frame.id;
    closed.insert(frame.id);
    closed_since_ = true;
  }

  std::vector<Given> given;
  std::map<std::uint64_t, std::uint64_t> per_frame;
  std::set<std::uint64_t> closed;
  std::set<std::uint64_t> straddles;  // packets whose points went to two frames
  std::size_t runs = 0;

 private:
  bool types_;
  bool have_last_ = false, closed_since_ = false;
  std::uint64_t last_packet_ = 0, last_frame_ = 0;
};

struct Case {
  const char* capture;
  float min_range, max_range;  // metres
  float fov_from, fov_to;      // degrees; equal: no --fov
  float cut;                   // degrees
  bool types;
};

void check_runs(const Case& c) {
  SCOPED_TRACE(c.capture);
  const auto packets = hesai_test::pcap_payloads(c.capture);
  ASSERT_FALSE(packets.empty());
  hesai::port::DecodeOptions options;
  options.detect_rotation = false;  // every packet processed as it comes, clockwise
  options.min_range = c.min_range;
  options.max_range = c.max_range;
  ASSERT_EQ(options.frames.set_cut_deg(c.cut), hesai::Error::ok);
  if (c.fov_from != c.fov_to) {
    ASSERT_EQ(options.frames.set_fov_deg(c.fov_from, c.fov_to), hesai::Error::ok);
  }
  RunRecorder sink(c.types);
  hesai::port::Pipeline pipeline(options, &sink);
  for (const auto& p : packets) ASSERT_TRUE(pipeline.feed(hesai_test::view(p), 1));
  pipeline.finish();

  // The reference: each packet decoded on its own, the range and field of view applied by hand
  // (FrameAssembler::in_fov for the field of view).
  hesai::FrameAssembler fov = options.frames;
  std::vector<Given> want;
  std::unique_ptr<hesai::Decoder> decoder;
  std::uint64_t index = 0;
  std::size_t keeping = 0;  // packets with a kept point
  for (const auto& p : packets) {
    hesai::Model model = hesai::Model::unknown;
    hesai::PacketKind kind = hesai::PacketKind::point_cloud;
    if (hesai::identify(hesai_test::view(p), model, kind) != hesai::Error::ok || kind != hesai::PacketKind::point_cloud)
      continue;
    if (!decoder) decoder = std::make_unique<hesai::Decoder>(model);
    hesai::PacketInfo info;
    static hesai::PacketPoints points;
    hesai::UnitScan scan;
    hesai::ReturnComparison compare;
    if (decoder->decode(hesai_test::view(p), info, points, scan, compare) != hesai::Error::ok) continue;
    const std::size_t before = want.size();
    for (const Point& q : points) {
      if (q.distance_m < c.min_range || q.distance_m > c.max_range || !fov.in_fov(q.azimuth_deg)) continue;
      want.push_back({q, 0, index, c.types ? hesai::port::nebula_return_type(info, compare, q) : NebulaReturnType::unknown});
    }
    if (want.size() != before) ++keeping;
    ++index;
  }
  ASSERT_GT(want.size(), 1000u);
  ASSERT_EQ(sink.given.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    const Given& g = sink.given[i];
    ASSERT_EQ(g.packet, want[i].packet) << "point " << i;
    ASSERT_TRUE(hesai_test::same_point_bits(g.point, want[i].point)) << "point " << i << " of packet " << g.packet;
    ASSERT_EQ(g.type, want[i].type) << "point " << i << " of packet " << g.packet;
  }
  EXPECT_EQ(sink.closed.size(), sink.per_frame.size());  // finish() closed every frame
  // A run a packet where it keeps to one frame; near a cut a block's points alternate between two.
  EXPECT_GE(sink.runs, keeping);
  EXPECT_FALSE(sink.straddles.empty()) << "no packet gave points to two frames: the cut is not exercised";
}

TEST(PipelineRuns, EveryPointInPlaceWithReturnTypes) { check_runs({"pandar64_dual.pcap", 0, 1e9f, 0, 0, 0, true}); }

TEST(PipelineRuns, EveryPointWithoutReturnTypesAtAnotherCut) {
  check_runs({"qt128c2x_dual.pcap", 0, 1e9f, 0, 0, 180.5f, false});
}

TEST(PipelineRuns, RangesAndFovGatherTheKeptPoints) {
  check_runs({"pandar64_dual.pcap", 1, 50, 300, 30, 350, true});
  check_runs({"pandar40p_dual.pcap", 2, 30, 0, 0, 90, true});
}

}  // namespace
