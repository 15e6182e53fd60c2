// Decoder::survey (issue #43): what a packet gives without its points, for a caller that keeps
// none of them (hesai --packets A:B on the packets outside the range). On every bundled capture:
// the points it counts against the raw bytes' count (test_golden.cpp, tests/golden/count_points.py)
// and against decode() packet by packet, the unit scan, the PacketInfo and the beam spread equal to
// decode()'s; and a decoder that surveys some packets decodes the others to the same bits as one
// that decodes them all (the per-rate cache it leaves stale is rebuilt), across rotation changes,
// spin-rate changes and both decode paths.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "hesai/decoder.h"
#include "hesai/detail/pandar64_packet.h"
#include "hesai/detail/qt128_packet.h"
#include "test_support.h"

namespace {

using hesai::Decoder;
using hesai::DecodePath;
using hesai::Error;
using hesai::Model;
using hesai::PacketInfo;
using hesai::PacketPoints;
using hesai::UnitScan;
using hesai_test::pcap_payloads;
using hesai_test::view;

struct Capture {
  const char* file;
  Model model;
  std::size_t packets;
  std::size_t points;  // non-zero distances (QT128: neither 0 nor the marker 1), from the raw bytes
};

// The totals of test_golden.cpp, test_qt64.cpp and test_xt.cpp, which their own loops and
// tests/golden/count_points.py (ctest golden_counts) count from the pcap bytes.
const Capture kCaptures[] = {
    {"pandar40p_dual.pcap", Model::pandar40p, 1439, 434934},  {"pandar64_dual.pcap", Model::pandar64, 2400, 716622},
    {"qt128c2x_dual.pcap", Model::qt128c2x, 1800, 337108},    {"pandar_qt64.pcap", Model::pandar_qt64, 1200, 299376},
    {"pandar_xt16.pcap", Model::pandar_xt16, 1626, 165138},   {"pandar_xt32.pcap", Model::pandar_xt32, 2000, 486606},
    {"pandar_xt32m2x.pcap", Model::pandar_xt32m2x, 1815, 223372},
};

class Survey : public ::testing::TestWithParam<Capture> {};

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_same_scan(const UnitScan& a, const UnitScan& b, std::size_t packet) {
  EXPECT_EQ(a.blockage_units, b.blockage_units) << "packet " << packet;
  EXPECT_EQ(a.duplicate_returns, b.duplicate_returns) << "packet " << packet;
  EXPECT_EQ(a.beyond_rated_range, b.beyond_rated_range) << "packet " << packet;
  EXPECT_EQ(a.blockage_by_channel, b.blockage_by_channel) << "packet " << packet;
  EXPECT_EQ(a.repeated, b.repeated) << "packet " << packet;
}

void expect_same_info(const PacketInfo& a, const PacketInfo& b, std::size_t packet) {
  EXPECT_EQ(a.model, b.model) << "packet " << packet;
  EXPECT_EQ(a.blocks, b.blocks) << "packet " << packet;
  EXPECT_EQ(a.returns, b.returns) << "packet " << packet;
  EXPECT_EQ(a.block_azimuth, b.block_azimuth) << "packet " << packet;
  EXPECT_EQ(a.motor_rpm, b.motor_rpm) << "packet " << packet;
  EXPECT_EQ(a.time_ns, b.time_ns) << "packet " << packet;
  EXPECT_EQ(a.has_sequence, b.has_sequence) << "packet " << packet;
  EXPECT_EQ(a.sequence, b.sequence) << "packet " << packet;
  EXPECT_EQ(a.signature, b.signature) << "packet " << packet;
}

// Every packet surveyed by one decoder and decoded by another: the same info, scan, spread, and
// as many points; the total is the raw bytes' count.
TEST_P(Survey, CountsScansAndSpreadsAsDecode) {
  const Capture& c = GetParam();
  const auto packets = pcap_payloads(c.file);
  ASSERT_EQ(packets.size(), c.packets);
  Decoder decoding(c.model), surveying(c.model);
  PacketPoints points;
  std::size_t total = 0, distinct_total = 0;
  for (std::size_t i = 0; i < packets.size(); ++i) {
    PacketInfo di, si;
    UnitScan ds, ss;
    std::size_t n = 12345;
    ASSERT_EQ(decoding.decode(view(packets[i]), di, points, ds), Error::ok) << i;
    ASSERT_EQ(surveying.survey(view(packets[i]), si, ss, n), Error::ok) << i;
    EXPECT_EQ(n, points.count) << "packet " << i;
    expect_same_info(di, si, i);
    expect_same_scan(ds, ss, i);
    EXPECT_TRUE(same_bits(decoding.beam_spread().min_deg, surveying.beam_spread().min_deg)) << "packet " << i;
    EXPECT_TRUE(same_bits(decoding.beam_spread().max_deg, surveying.beam_spread().max_deg)) << "packet " << i;
    total += n;
    // Returns::distinct leaves the repeated returns out of the points, not out of the count.
    ASSERT_EQ(decoding.decode(view(packets[i]), di, points, ds, hesai::Returns::distinct), Error::ok) << i;
    distinct_total += points.count + ds.duplicate_returns;
  }
  EXPECT_EQ(total, c.points);
  EXPECT_EQ(distinct_total, c.points);
}

// Surveying some packets (a pattern of runs of 1..7) and decoding the others gives the points
// decode() gives when it decodes every packet, bit for bit: the loops survey() leaves stale at a
// new spin rate are rebuilt before use. The direction of rotation flips every 300 packets (every
// loop stale again), and the portable path decodes a third of the packets.
TEST_P(Survey, LeavesTheDecoderAsDecodeDoes) {
  const Capture& c = GetParam();
  const auto packets = pcap_payloads(c.file);
  Decoder every(c.model), some(c.model);
  PacketPoints expected, got;
  std::uint32_t state = 12345;
  std::size_t run = 0, decoded = 0;
  bool surveying = false;
  for (std::size_t i = 0; i < packets.size(); ++i) {
    if (i % 300 == 299) {
      const auto r = every.rotation() == hesai::Rotation::clockwise ? hesai::Rotation::counterclockwise
                                                                    : hesai::Rotation::clockwise;
      every.set_rotation(r);
      some.set_rotation(r);
    }
    if (run == 0) {
      state = state * 1103515245u + 12345u;
      run = 1 + (state >> 16) % 7;
      surveying = !surveying;
    }
    --run;
    const DecodePath path = i % 3 == 0 ? DecodePath::portable : DecodePath::best;
    PacketInfo info;
    ASSERT_EQ(every.decode(view(packets[i]), info, expected, path), Error::ok) << i;
    if (surveying) {
      UnitScan scan;
      std::size_t n = 0;
      ASSERT_EQ(some.survey(view(packets[i]), info, scan, n, path), Error::ok) << i;
      continue;
    }
    ASSERT_EQ(some.decode(view(packets[i]), info, got, path), Error::ok) << i;
    ASSERT_EQ(got.count, expected.count) << "packet " << i;
    EXPECT_TRUE(hesai_test::same_point_bits(got.points.data(), expected.points.data(), got.count))
        << "packet " << i;
    ++decoded;
  }
  EXPECT_GT(decoded, packets.size() / 4);
}

INSTANTIATE_TEST_SUITE_P(Bundled, Survey, ::testing::ValuesIn(kCaptures),
                         [](const auto& i) { return std::string(hesai::model_name(i.param.model)); });

// A new spin rate on every packet (the Pandar64 capture's motor speed rewritten: no CRC covers
// it), packets surveyed and decoded in turn: the spread follows each packet's rate as decode()'s
// does, and the decoded points are decode()'s.
TEST(SurveyRate, EveryPacketAtANewRate) {
  auto packets = pcap_payloads("pandar64_dual.pcap");
  Decoder every(Model::pandar64), some(Model::pandar64);
  PacketPoints expected, got;
  for (std::size_t i = 0; i < 400; ++i) {
    std::vector<std::uint8_t>& p = packets[i];
    hesai::store_le16(p.data() + hesai::pandar64::kMotorSpeed, static_cast<std::uint16_t>(600 + 2 * i));
    PacketInfo info;
    ASSERT_EQ(every.decode(view(p), info, expected), Error::ok) << i;
    ASSERT_EQ(info.motor_rpm, 600 + 2 * i);
    if (i % 2 == 0) {
      UnitScan scan;
      std::size_t n = 0;
      ASSERT_EQ(some.survey(view(p), info, scan, n), Error::ok) << i;
      EXPECT_EQ(n, expected.count) << i;
      EXPECT_TRUE(same_bits(every.beam_spread().min_deg, some.beam_spread().min_deg)) << i;
      EXPECT_TRUE(same_bits(every.beam_spread().max_deg, some.beam_spread().max_deg)) << i;
      continue;
    }
    ASSERT_EQ(some.decode(view(p), info, got), Error::ok) << i;
    ASSERT_EQ(got.count, expected.count) << i;
    EXPECT_TRUE(hesai_test::same_point_bits(got.points.data(), expected.points.data(), got.count)) << i;
  }
}

// Units at the edges of the smallest distance a point needs (decode(): raw >= 1 on the Pandars,
// >= 2 on the QT128C2X, whose 1 marks blockage): counted as decode() makes them.
TEST(SurveyRate, DistancesAtTheSmallestKept) {
  for (const char* file : {"pandar64_dual.pcap", "qt128c2x_dual.pcap"}) {
    std::vector<std::uint8_t> p = pcap_payloads(file)[5];
    Model model = Model::unknown;
    hesai::PacketKind kind;
    ASSERT_EQ(hesai::identify(view(p), model, kind), Error::ok);
    Decoder d(model);
    PacketInfo info;
    PacketPoints points;
    ASSERT_EQ(d.decode(view(p), info, points), Error::ok);
    const std::size_t before = points.count;
    // Four units of block 1 to distances 0, 1, 2 and 3 (units of 3 bytes on the Pandar64, 4 on
    // this QT128, whose channels 65..68 fire in both sequences: none rests, by the manual's banks).
    const bool qt = model == Model::qt128c2x;
    const std::size_t unit = qt ? 4 : 3;
    const std::size_t first = qt ? hesai::qt128::kBody + hesai::qt128::kBlockPoints + 64 * unit
                                 : hesai::pandar64::kBody + hesai::pandar64::kBlockPoints;
    std::size_t zero_before = 0;
    for (std::size_t j = 0; j < 4; ++j) {
      zero_before += hesai::load_le16(p.data() + first + j * unit) < (qt ? 2u : 1u) ? 1u : 0u;
      hesai::store_le16(p.data() + first + j * unit, static_cast<std::uint16_t>(j));
    }
    if (qt) {
      ASSERT_EQ(hesai::qt128::seal(p.data(), p.size()), Error::ok);
    }
    ASSERT_EQ(d.decode(view(p), info, points), Error::ok) << file;
    // Kept: 2 and 3, and 1 on the Pandar64: the count moves by what the four units were before.
    EXPECT_EQ(points.count, before + zero_before - (qt ? 2u : 1u)) << file;
    UnitScan scan;
    std::size_t n = 0;
    ASSERT_EQ(d.survey(view(p), info, scan, n), Error::ok) << file;
    EXPECT_EQ(n, points.count) << file;
  }
}

// A packet validate() refuses: the same error as decode(), no point counted, the scan reset.
TEST(SurveyRate, RefusedPacketCountsNothing) {
  auto packets = pcap_payloads("pandar64_dual.pcap");
  std::vector<std::uint8_t> p = packets[0];
  hesai::store_le16(p.data() + hesai::pandar64::kBody, 36000);  // block 1's azimuth: not an azimuth
  Decoder d(Model::pandar64);
  PacketInfo info;
  UnitScan scan;
  scan.duplicate_returns = 7;
  std::size_t n = 99;
  EXPECT_EQ(d.survey(view(p), info, scan, n), Error::bad_azimuth);
  EXPECT_EQ(n, 0u);
  EXPECT_EQ(scan.duplicate_returns, 0u);
}

}  // namespace
