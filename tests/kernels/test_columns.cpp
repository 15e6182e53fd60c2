// The columnar output (PointColumns, PacketColumns<N>) against the Point output, and the vector
// paths (AVX-512 and AVX2 on x86-64, NEON on AArch64) against the portable scalar path: every
// point of every bundled capture. Each test counts the packets it expects each vector kernel to
// decode and requires the counters of the core's test build to say the same (kernel_calls.h):
// the kernel a test names ran, on every packet, and not the scalar loops in its place.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "hesai/calibration.h"
#include "hesai/decoder.h"
#include "hesai/detail/pandar40_packet.h"
#include "hesai/detail/pandar64_packet.h"
#include "hesai/detail/qt128_packet.h"
#include "hesai/detail/qt64_packet.h"
#include "hesai/detail/xt_packet.h"
#include "kernel_calls.h"
#include "packet_builder.h"
#include "test_support.h"
#include "vector_paths.h"

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
// into columns; calls check(points, info, columns) per packet. The Points by DecodePath::best's
// kernel and the columns by `path`'s, each on every packet.
template <typename Setup, typename Check>
void each_packet(const Capture& cap, Setup setup, DecodePath path, Check check) {
  const auto packets = pcap_payloads(cap.file);
  ASSERT_FALSE(packets.empty()) << cap.file;
  KernelTally tally;
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
    tally.decoded(DecodePath::best, Output::points);
    tally.decoded(path, Output::columns);
  }
  EXPECT_GT(points, 0u) << cap.file;
  tally.check(cap.file);
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
  if (const std::string why = columns_scalar_reason(DecodePath::best); !why.empty()) GTEST_SKIP() << why;
  for (const Capture& cap : kCaptures) expect_same_points(cap, defaults, DecodePath::best);
}

// On an AVX-512 CPU `best` runs the AVX-512 code; this keeps the AVX2 code proved there too
// (elsewhere it is `best` again).
TEST(Columns, SameValuesAsPointsOnEveryCaptureAvx2Path) {
  if (const std::string why = columns_scalar_reason(DecodePath::avx2); !why.empty()) GTEST_SKIP() << why;
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
  if (const std::string why = columns_scalar_reason(DecodePath::best); !why.empty()) GTEST_SKIP() << why;
  for (const Capture& cap : kCaptures) {
    const auto packets = pcap_payloads(cap.file);
    Decoder scalar(cap.model), vector(cap.model);
    static Columns a, b;
    std::size_t points = 0;
    KernelTally tally;
    const auto near = [](float u, float v) { return std::fabs(u - v) <= 1e-6f * std::max(std::fabs(u), std::fabs(v)); };
    for (const auto& p : packets) {
      PacketInfo info;
      ASSERT_EQ(scalar.decode(view(p), info, a.c, DecodePath::portable), Error::ok);
      ASSERT_EQ(vector.decode(view(p), info, b.c), Error::ok);
      tally.decoded(DecodePath::best, Output::columns);
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
    tally.check(cap.file);
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
  // The 3-byte units go to the vector kernels; the customised channels (a channel map) to the
  // scalar loops on every path.
  KernelTally tally;
  for (std::size_t i = 0; i < 64; ++i) {
    const auto& p = qt[i];
    std::vector<std::size_t> keep;
    for (std::size_t j = 0; j < config.laser_num; ++j) keep.push_back(config.channel[(p[1066] & 1) ? 0 : 1][j] - 1u);
    for (const bool customised : {false, true}) {
      const auto v = customised ? qt128_rebuild(p, static_cast<std::uint8_t>(config.laser_num), 0x4D, {keep, keep})
                                : qt128_rebuild(p, 128, 0x0D, {first_units(128), first_units(128)});
      for (const DecodePath path : {DecodePath::best, DecodePath::avx2, DecodePath::portable}) {
        PacketInfo info;
        ASSERT_EQ(by_point.decode(view(v), info, pts), Error::ok);
        ASSERT_EQ(by_column.decode(view(v), info, cols.c, path), Error::ok);
        if (!customised) {
          tally.decoded(DecodePath::best, Output::points);
          tally.decoded(path, Output::columns);
        }
        expect_equal(pts, info, cols.c, "packet " + std::to_string(i));
        points += pts.count;
      }
    }
  }
  EXPECT_GT(points, 0u);
  tally.check("QT128 3-byte units and customised channels");
}

// The same bits (== would take -0 for +0).
bool same_bits(float a, float b) {
  std::uint32_t u, v;
  std::memcpy(&u, &a, sizeof u);
  std::memcpy(&v, &b, sizeof v);
  return u == v;
}

// Points by the vector path (AVX-512 or AVX2 on x86-64, NEON on AArch64) and by the portable one:
// every field of every point, the floats bit for bit.
void expect_same_point_fields(const PacketPoints& a, const PacketPoints& b, const std::string& what) {
  ASSERT_EQ(a.count, b.count) << what;
  for (std::size_t i = 0; i < a.count; ++i) {
    const Point& p = a.points[i];
    const Point& q = b.points[i];
    ASSERT_TRUE(same_bits(p.x, q.x) && same_bits(p.y, q.y) && same_bits(p.z, q.z) &&
                same_bits(p.distance_m, q.distance_m))
        << what << " point " << i;
    ASSERT_TRUE(same_bits(p.azimuth_deg, q.azimuth_deg) && same_bits(p.elevation_deg, q.elevation_deg))
        << what << " point " << i;
    ASSERT_EQ(p.time_ns, q.time_ns) << what << " point " << i;
    ASSERT_TRUE(p.intensity == q.intensity && p.channel == q.channel && p.return_index == q.return_index &&
                p.confidence == q.confidence && p.block == q.block)
        << what << " point " << i;
  }
}

TEST(Columns, PointsVectorPathEqualsScalarOnEveryCapture) {
  if (const std::string why = points_scalar_reason(DecodePath::best); !why.empty()) GTEST_SKIP() << why;
  static PacketPoints a, b;
  for (const Capture& cap : kCaptures) {
    Decoder dec(cap.model);
    std::size_t points = 0;
    KernelTally tally;
    for (const auto& p : pcap_payloads(cap.file)) {
      PacketInfo info;
      ASSERT_EQ(dec.decode(view(p), info, a, DecodePath::portable), Error::ok);
      for (const DecodePath path : {DecodePath::best, DecodePath::avx2}) {
        ASSERT_EQ(dec.decode(view(p), info, b, path), Error::ok);
        tally.decoded(path, Output::points);
        expect_same_point_fields(a, b, cap.file);
      }
      points += a.count;
    }
    EXPECT_GT(points, 0u) << cap.file;
    tally.check(cap.file);
  }
  // QT128 3-byte units (no confidence byte) and customised channels.
  const auto qt = pcap_payloads("qt128c2x_dual.pcap");
  Decoder dec(Model::qt128c2x);
  KernelTally tally;
  for (std::size_t i = 0; i < 64; ++i) {
    const auto v = qt128_rebuild(qt[i], 128, 0x0D, {first_units(128), first_units(128)});
    PacketInfo info;
    ASSERT_EQ(dec.decode(view(v), info, a, DecodePath::portable), Error::ok);
    ASSERT_EQ(dec.decode(view(v), info, b, DecodePath::best), Error::ok);
    tally.decoded(DecodePath::best, Output::points);
    expect_same_point_fields(a, b, "3-byte units, packet " + std::to_string(i));
  }
  tally.check("QT128 3-byte units");
  // QT128 confidence bytes, all 0 in the capture: a different one in each unit of a block (not
  // in the resting channels' units, which must stay 0).
  std::size_t confident = 0;
  KernelTally confidence_tally;
  for (std::size_t i = 0; i < 64; ++i) {
    auto v = qt[i];
    const auto l = qt128::Layout::from_header(v[qt128::kLaserNum], v[qt128::kFlags]);
    ASSERT_EQ(l.unit, 4u);
    for (std::size_t blk = 0; blk < qt128::kBlocks; ++blk) {
      for (std::size_t j = 0; j < l.lasers; ++j) {
        std::uint8_t* u = &v[qt128::kBody + blk * l.block + qt128::kBlockPoints + j * l.unit];
        if ((u[0] | u[1] | u[2]) != 0) u[3] = static_cast<std::uint8_t>(1 + j + 128 * blk + i);
      }
    }
    qt128_seal(v);
    PacketInfo info;
    ASSERT_EQ(dec.decode(view(v), info, a, DecodePath::portable), Error::ok);
    ASSERT_EQ(dec.decode(view(v), info, b, DecodePath::best), Error::ok);
    confidence_tally.decoded(DecodePath::best, Output::points);
    expect_same_point_fields(a, b, "confidence bytes, packet " + std::to_string(i));
    for (std::size_t n = 0; n < a.count; ++n) confident += a.points[n].confidence != 0;
  }
  EXPECT_GT(confident, 0u);
  confidence_tally.check("QT128 confidence bytes");
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

namespace {

// Where the motor speed field of each layout lies (the manuals' tail tables; the SDK's for QT64 and XT).
std::size_t speed_at(Model m, const std::vector<std::uint8_t>& p) {
  switch (m) {
    case Model::pandar40:
    case Model::pandar40p: return pandar40::kMotorSpeed;
    case Model::pandar64: return pandar64::kMotorSpeed;
    case Model::qt128c2x: return qt128::Layout::from_header(p[qt128::kLaserNum], p[qt128::kFlags]).tail + qt128::kTailMotorSpeed;
    case Model::pandar_qt64: return qt64::kTail + qt64::kTailMotorSpeed;
    default: return p.size() - xt::kTailBytes + xt::kTailMotorSpeed;
  }
}

}  // namespace

// The beam-direction cache rebuilt at a new spin rate (Decoder::update_spin) by each path's loop
// (AVX-512, AVX2, scalar on x86-64; the scalar loop on every path on AArch64, where the Points of
// DecodePath::best are then written by NEON) gives the same bits: three decoders, one per path, each
// rebuilding on every packet (the motor speed rewritten to (97 i) mod 1501 rpm, every accepted
// rate from 0 to 1500 in turn), both rotations, the design angles and random angle offsets
// over the accepted range (-360..360 degrees, so that every azimuth wrap is taken): every field
// of every point and the beam spread equal.
TEST(Columns, SpinRebuildSameBitsOnEveryPath) {
  if (const std::string why = points_scalar_reason(DecodePath::best); !why.empty()) GTEST_SKIP() << why;
  static PacketPoints a, b, c;
  std::uint32_t seed = 12345;
  const auto random = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<double>(seed >> 8) / static_cast<double>(1u << 24);
  };
  for (const Capture& cap : kCaptures) {
    auto packets = pcap_payloads(cap.file);
    for (std::size_t i = 0; i < packets.size(); ++i) {
      store_le16(&packets[i][speed_at(cap.model, packets[i])], static_cast<std::uint16_t>((97 * i) % 1501));
      if (cap.model == Model::qt128c2x) qt128_seal(packets[i]);
    }
    for (const bool offsets : {false, true}) {
      for (const Rotation rotation : {Rotation::clockwise, Rotation::counterclockwise}) {
        Decoder scalar(cap.model), avx2(cap.model), best(cap.model);
        if (offsets) {
          static AngleCorrection angles;
          angles.channels = static_cast<std::uint16_t>(channel_count(cap.model));
          for (std::size_t ch = 0; ch < angles.channels; ++ch) {
            angles.elevation_deg[ch] = -30 + 60 * random();
            angles.azimuth_deg[ch] = -360 + 720 * random();
          }
          for (Decoder* d : {&scalar, &avx2, &best}) ASSERT_EQ(d->set_angles(angles), Error::ok);
        }
        for (Decoder* d : {&scalar, &avx2, &best}) d->set_rotation(rotation);
        KernelTally tally;
        const std::string what = std::string(cap.file) + (offsets ? " offsets " : " design ") +
                                 (rotation == Rotation::clockwise ? "cw" : "ccw");
        for (const auto& p : packets) {
          PacketInfo info;
          ASSERT_EQ(scalar.decode(view(p), info, a, DecodePath::portable), Error::ok);
          ASSERT_EQ(avx2.decode(view(p), info, b, DecodePath::avx2), Error::ok);
          ASSERT_EQ(best.decode(view(p), info, c, DecodePath::best), Error::ok);
          tally.decoded(DecodePath::avx2, Output::points);
          tally.decoded(DecodePath::best, Output::points);
          expect_same_point_fields(a, b, std::string(cap.file) + " avx2");
          expect_same_point_fields(a, c, std::string(cap.file) + " best");
          const AzimuthSpread sa = scalar.beam_spread(), sb = avx2.beam_spread(), sc = best.beam_spread();
          ASSERT_TRUE(sa.min_deg == sb.min_deg && sa.max_deg == sb.max_deg && sa.min_deg == sc.min_deg &&
                      sa.max_deg == sc.max_deg)
              << cap.file << " rpm " << info.motor_rpm;
        }
        tally.check(what);
        expect_beams_rebuilt(DecodePath::avx2, what);
        expect_beams_rebuilt(DecodePath::best, what);
      }
    }
  }
}

// A firing loop's cache arrays are rebuilt when a packet first uses them at a rate (a dual-return
// QT128 packet uses one of the two; the others' spread alone is computed at the change): a
// decoder that switches path on every packet (best, AVX2, portable in turn), with the rate
// changed every third packet (598, 600, 602 rpm) and on every packet, equals a decoder on the
// scalar path in every field of every point and in the beam spread, and in Points and columns alike.
TEST(Columns, SpinRebuildLazyLoopsSameBits) {
  if (const std::string why = points_scalar_reason(DecodePath::best); !why.empty()) GTEST_SKIP() << why;
  static PacketPoints a, b;
  static Columns ca, cb;
  const DecodePath paths[] = {DecodePath::best, DecodePath::avx2, DecodePath::portable};
  for (const Capture& cap : kCaptures) {
    for (const std::size_t every : {std::size_t{3}, std::size_t{1}}) {
      auto packets = pcap_payloads(cap.file);
      for (std::size_t i = 0; i < packets.size(); ++i) {
        store_le16(&packets[i][speed_at(cap.model, packets[i])], static_cast<std::uint16_t>(598 + 2 * (i / every % 3)));
        if (cap.model == Model::qt128c2x) qt128_seal(packets[i]);
      }
      Decoder scalar(cap.model), mixed(cap.model), scalar_columns(cap.model), mixed_columns(cap.model);
      KernelTally tally;
      for (std::size_t i = 0; i < packets.size(); ++i) {
        // The path turns every packet, and one step further at each third: a rate that changes every
        // third packet then meets each path in turn (with paths[i % 3], every such change met `best`,
        // and where that is AVX-512 the AVX2 rebuild never ran).
        const DecodePath path = paths[(i + i / 3) % 3];
        PacketInfo info;
        ASSERT_EQ(scalar.decode(view(packets[i]), info, a, DecodePath::portable), Error::ok);
        ASSERT_EQ(mixed.decode(view(packets[i]), info, b, path), Error::ok);
        expect_same_point_fields(a, b, std::string(cap.file) + " packet " + std::to_string(i));
        ASSERT_EQ(scalar_columns.decode(view(packets[i]), info, ca.c, DecodePath::portable), Error::ok);
        ASSERT_EQ(mixed_columns.decode(view(packets[i]), info, cb.c, path), Error::ok);
        tally.decoded(path, Output::points);
        tally.decoded(path, Output::columns);
        ASSERT_EQ(ca.c.count, a.count);
        ASSERT_EQ(cb.c.count, a.count);
        for (std::size_t j = 0; j < a.count; ++j) {
          ASSERT_TRUE(ca.c.x[j] == cb.c.x[j] && ca.c.y[j] == cb.c.y[j] && ca.c.z[j] == cb.c.z[j] &&
                      ca.c.time_ns[j] == cb.c.time_ns[j])
              << cap.file << " packet " << i << " column " << j;
        }
        for (const Decoder* d : {&mixed, &scalar_columns, &mixed_columns}) {
          ASSERT_TRUE(d->beam_spread().min_deg == scalar.beam_spread().min_deg &&
                      d->beam_spread().max_deg == scalar.beam_spread().max_deg)
              << cap.file << " packet " << i;
        }
      }
      const std::string what = std::string(cap.file) + " rate changed every " + std::to_string(every) + " packets";
      tally.check(what);
      expect_beams_rebuilt(DecodePath::avx2, what);
      expect_beams_rebuilt(DecodePath::best, what);
    }
  }
}
