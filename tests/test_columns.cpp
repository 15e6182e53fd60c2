// The columnar output (PointColumns, PacketColumns<N>) against the Point output, and the vector
// paths (AVX2 on x86-64, NEON on AArch64) against the portable scalar path: every point of every
// bundled capture.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "hesai/decoder.h"
#include "hesai/calibration.h"
#include "packet_builder.h"
#include "test_support.h"

using namespace hesai;
using namespace hesai_test;

namespace {

struct Capture {
  const char* file;
  Model model;
};
const Capture kCaptures[] = {{"pandar40p_dual.pcap", Model::pandar40p},
                             {"pandar64_dual.pcap", Model::pandar64},
                             {"qt128c2x_dual.pcap", Model::qt128c2x},
                             {"pandar_qt64.pcap", Model::pandar_qt64},
                             {"pandar_xt16.pcap", Model::pandar_xt16},
                             {"pandar_xt32.pcap", Model::pandar_xt32},
                             {"pandar_xt32m2x.pcap", Model::pandar_xt32m2x}};

// Columns sized for the largest packet, with their count.
struct Columns {
  PacketColumns<kMaxPointsPerPacket> c;
};

// Decodes every packet of a capture into Points and, with a second decoder of the same settings,
// into columns; calls check(points, info, columns) per packet.
template <typename Setup, typename Check>
void each_packet(const Capture& cap, Setup setup, DecodePath path, Check check) {
  const auto packets = pcap_payloads(cap.file);
  ASSERT_FALSE(packets.empty()) << cap.file;
  Decoder by_point(cap.model), by_column(cap.model);
  setup(by_point);
  setup(by_column);
  static PacketPoints pts;
  static Columns cols;
  std::size_t points = 0;
  for (const auto& p : packets) {
    PacketInfo info, info_c;
    ASSERT_EQ(by_point.decode(view(p), info, pts), Error::ok) << cap.file;
    ASSERT_EQ(by_column.decode(view(p), info_c, cols.c, path), Error::ok) << cap.file;
    ASSERT_EQ(info_c.time_ns, info.time_ns);
    ASSERT_EQ(cols.c.count, pts.count) << cap.file;
    check(pts, info, cols.c);
    points += pts.count;
  }
  EXPECT_GT(points, 0u) << cap.file;
}

// Every column of every point equals the Point's field (time: from the packet time).
void expect_equal(const PacketPoints& pts, const PacketInfo& info, const PacketColumns<kMaxPointsPerPacket>& c,
                  const std::string& what) {
  ASSERT_EQ(c.count, pts.count) << what;
  for (std::size_t i = 0; i < pts.count; ++i) {
    const Point& q = pts.points[i];
    ASSERT_EQ(c.x[i], q.x) << what << " point " << i;
    ASSERT_EQ(c.y[i], q.y) << what << " point " << i;
    ASSERT_EQ(c.z[i], q.z) << what << " point " << i;
    ASSERT_EQ(info.time_ns + c.time_ns[i], q.time_ns) << what << " point " << i;
    ASSERT_EQ(c.intensity[i], q.intensity) << what << " point " << i;
    ASSERT_EQ(c.channel[i], q.channel) << what << " point " << i;
    ASSERT_EQ(c.return_index[i], q.return_index) << what << " point " << i;
  }
}

void expect_same_points(const Capture& cap, void (*setup)(Decoder&), DecodePath path) {
  each_packet(cap, setup, path, [&](const PacketPoints& pts, const PacketInfo& info, const auto& c) {
    expect_equal(pts, info, c, cap.file);
  });
}

void defaults(Decoder&) {}

TEST(Columns, SameValuesAsPointsOnEveryCapturePortable) {
  for (const Capture& cap : kCaptures) expect_same_points(cap, defaults, DecodePath::portable);
}

TEST(Columns, SameValuesAsPointsOnEveryCaptureBestPath) {
  for (const Capture& cap : kCaptures) expect_same_points(cap, defaults, DecodePath::best);
}

// On an AVX-512 CPU `best` runs the AVX-512 code; this keeps the AVX2 code proved there too
// (elsewhere it is `best` again).
TEST(Columns, SameValuesAsPointsOnEveryCaptureAvx2Path) {
  for (const Capture& cap : kCaptures) expect_same_points(cap, defaults, DecodePath::avx2);
}

TEST(Columns, SameValuesWithoutFiretimeCorrectionAndWithNonlinearReflectivity) {
  for (const Capture& cap : kCaptures)
    expect_same_points(cap, [](Decoder& d) { d.set_firetime_correction(false); }, DecodePath::best);
  expect_same_points(kCaptures[1], [](Decoder& d) { ASSERT_EQ(d.set_reflectivity(Reflectivity::nonlinear), Error::ok); },
                     DecodePath::best);
}

// The bound for a vector path: within 1e-6 relative of the scalar path, every point of
// every capture (with the same operations in the same order they are in fact equal).
TEST(Columns, VectorPathWithinOneMillionthOfScalar) {
  for (const Capture& cap : kCaptures) {
    const auto packets = pcap_payloads(cap.file);
    Decoder scalar(cap.model), vector(cap.model);
    static Columns a, b;
    std::size_t points = 0;
    const auto near = [](float u, float v) { return std::fabs(u - v) <= 1e-6f * std::max(std::fabs(u), std::fabs(v)); };
    for (const auto& p : packets) {
      PacketInfo info;
      ASSERT_EQ(scalar.decode(view(p), info, a.c, DecodePath::portable), Error::ok);
      ASSERT_EQ(vector.decode(view(p), info, b.c), Error::ok);
      ASSERT_EQ(a.c.count, b.c.count);
      for (std::size_t i = 0; i < a.c.count; ++i) {
        ASSERT_TRUE(near(a.c.x[i], b.c.x[i]) && near(a.c.y[i], b.c.y[i]) && near(a.c.z[i], b.c.z[i]))
            << cap.file << " point " << i;
        ASSERT_EQ(a.c.time_ns[i], b.c.time_ns[i]);
        ASSERT_EQ(a.c.intensity[i], b.c.intensity[i]);
        ASSERT_EQ(a.c.channel[i], b.c.channel[i]);
        ASSERT_EQ(a.c.return_index[i], b.c.return_index[i]);
      }
      points += a.c.count;
    }
    EXPECT_GT(points, 0u) << cap.file;
  }
}

// The QT128 settings the captures do not show: 3-byte units (no confidence) and customised
// channels (the channel map: the scalar loop on every path), rebuilt from the capture's packets.
TEST(Columns, Qt128ThreeByteUnitsAndCustomisedChannels) {
  const auto qt = pcap_payloads("qt128c2x_dual.pcap");
  const auto config_text = read_file(data_path("calibration/qt128c2x_channel_config.csv"));
  static ChannelConfig config;
  ASSERT_EQ(parse_channel_config_csv(view(config_text), config).error, Error::ok);
  Decoder by_point(Model::qt128c2x), by_column(Model::qt128c2x);
  ASSERT_EQ(by_point.set_channel_config(config), Error::ok);
  ASSERT_EQ(by_column.set_channel_config(config), Error::ok);
  static PacketPoints pts;
  static Columns cols;
  std::size_t points = 0;
  for (std::size_t i = 0; i < 64; ++i) {
    const auto& p = qt[i];
    std::vector<std::size_t> keep;
    for (std::size_t j = 0; j < config.laser_num; ++j) keep.push_back(config.channel[(p[1066] & 1) ? 0 : 1][j] - 1u);
    for (const auto& v : {qt128_rebuild(p, 128, 0x0D, {first_units(128), first_units(128)}),
                          qt128_rebuild(p, static_cast<std::uint8_t>(config.laser_num), 0x4D, {keep, keep})}) {
      for (const DecodePath path : {DecodePath::best, DecodePath::avx2, DecodePath::portable}) {
        PacketInfo info;
        ASSERT_EQ(by_point.decode(view(v), info, pts), Error::ok);
        ASSERT_EQ(by_column.decode(view(v), info, cols.c, path), Error::ok);
        expect_equal(pts, info, cols.c, "packet " + std::to_string(i));
        points += pts.count;
      }
    }
  }
  EXPECT_GT(points, 0u);
}

// Points by the vector path (AVX2 on x86-64) and by the portable one: every field of every point.
void expect_same_point_fields(const PacketPoints& a, const PacketPoints& b, const std::string& what) {
  ASSERT_EQ(a.count, b.count) << what;
  for (std::size_t i = 0; i < a.count; ++i) {
    const Point& p = a.points[i];
    const Point& q = b.points[i];
    ASSERT_TRUE(p.x == q.x && p.y == q.y && p.z == q.z && p.distance_m == q.distance_m) << what << " point " << i;
    ASSERT_TRUE(p.azimuth_deg == q.azimuth_deg && p.elevation_deg == q.elevation_deg) << what << " point " << i;
    ASSERT_EQ(p.time_ns, q.time_ns) << what << " point " << i;
    ASSERT_TRUE(p.intensity == q.intensity && p.channel == q.channel && p.return_index == q.return_index &&
                p.confidence == q.confidence && p.block == q.block)
        << what << " point " << i;
  }
}

TEST(Columns, PointsVectorPathEqualsScalarOnEveryCapture) {
  static PacketPoints a, b;
  for (const Capture& cap : kCaptures) {
    Decoder dec(cap.model);
    std::size_t points = 0;
    for (const auto& p : pcap_payloads(cap.file)) {
      PacketInfo info;
      ASSERT_EQ(dec.decode(view(p), info, a, DecodePath::portable), Error::ok);
      for (const DecodePath path : {DecodePath::best, DecodePath::avx2}) {
        ASSERT_EQ(dec.decode(view(p), info, b, path), Error::ok);
        expect_same_point_fields(a, b, cap.file);
      }
      points += a.count;
    }
    EXPECT_GT(points, 0u) << cap.file;
  }
  // QT128 3-byte units (no confidence byte) and customised channels.
  const auto qt = pcap_payloads("qt128c2x_dual.pcap");
  Decoder dec(Model::qt128c2x);
  for (std::size_t i = 0; i < 64; ++i) {
    const auto v = qt128_rebuild(qt[i], 128, 0x0D, {first_units(128), first_units(128)});
    PacketInfo info;
    ASSERT_EQ(dec.decode(view(v), info, a, DecodePath::portable), Error::ok);
    ASSERT_EQ(dec.decode(view(v), info, b, DecodePath::best), Error::ok);
    expect_same_point_fields(a, b, "3-byte units, packet " + std::to_string(i));
  }
}

// Storage sized per model: PacketColumns<max_points(model)> suffices; one element less is refused
// before the packet is read, and so is a missing column.
TEST(Columns, CallerStorageSizedForTheModel) {
  for (const Capture& cap : kCaptures) {
    const auto packets = pcap_payloads(cap.file);
    ASSERT_FALSE(packets.empty());
    const std::size_t most = max_points(cap.model);
    std::vector<float> x(most), y(most), z(most);
    std::vector<std::int32_t> t(most);
    std::vector<std::uint8_t> intensity(most), channel(most), ret(most);
    PointColumns c{x.data(), y.data(), z.data(), t.data(), intensity.data(), channel.data(), ret.data(), most};
    Decoder dec(cap.model);
    PacketInfo info;
    std::size_t count = 99;
    EXPECT_EQ(dec.decode(view(packets[0]), info, c, count), Error::ok);
    EXPECT_GT(count, 0u);

    c.capacity = most - 1;
    count = 99;
    info.motor_rpm = 4321;
    EXPECT_EQ(dec.decode(view(packets[0]), info, c, count), Error::buffer_too_small) << cap.file;
    EXPECT_EQ(count, 0u);
    EXPECT_EQ(info.motor_rpm, 4321) << "info untouched";

    c.capacity = most;
    c.channel = nullptr;
    count = 99;
    EXPECT_EQ(dec.decode(view(packets[0]), info, c, count), Error::invalid_argument) << cap.file;
    EXPECT_EQ(count, 0u);
  }
  static PacketColumns<max_points(Model::qt128c2x)> qt;
  static_assert(sizeof(qt.x) == 256 * 4, "a QT128 packet's columns: 256 points");
  Decoder dec(Model::qt128c2x);
  PacketInfo info;
  EXPECT_EQ(dec.decode(view(pcap_payloads("qt128c2x_dual.pcap")[0]), info, qt), Error::ok);
  EXPECT_GT(qt.count, 0u);
  PacketColumns<max_points(Model::qt128c2x)> too_small_for_pandar64;
  Decoder p64(Model::pandar64);
  EXPECT_EQ(p64.decode(view(pcap_payloads("pandar64_dual.pcap")[0]), info, too_small_for_pandar64), Error::buffer_too_small);
  EXPECT_EQ(too_small_for_pandar64.count, 0u);
}

// A decode error leaves count 0 in the columns too.
TEST(Columns, ErrorGivesNoPoints) {
  auto p = pcap_payloads("pandar64_dual.pcap")[0];
  p[8] ^= 0xFF;  // a wrong number of blocks in the header
  Decoder dec(Model::pandar64);
  static Columns cols;
  cols.c.count = 7;
  PacketInfo info;
  EXPECT_NE(dec.decode(view(p), info, cols.c), Error::ok);
  EXPECT_EQ(cols.c.count, 0u);
}

}  // namespace
