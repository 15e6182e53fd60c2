// Golden tests on the three bundled real captures. Expected header values were read by hand from
// the hex bytes quoted beside them; counts are taken from the raw bytes by this file's own loops;
// every point is checked against a plain double-precision evaluation of the manuals' formulas.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "hesai/calibration.h"
#include "hesai/decoder.h"
#include "packet_builder.h"
#include "test_support.h"

using hesai::ByteView;
using hesai::Decoder;
using hesai::Error;
using hesai::Model;
using hesai::PacketInfo;
using hesai::PacketPoints;
using namespace hesai_test;

namespace {

// The model-specific facts the reference needs, typed from the manuals, and each capture's totals:
// its packets and points (non-zero distances; for the QT128 neither 0 nor the marker 1). The
// totals are counted twice without the library: by CountsFromRawBytes's own loops below, and by
// tests/golden/count_points.py (plain Python over the pcap bytes, ctest `golden_counts`), which
// reads them from these initializers: keep each initializer's opening {"capture", packets, points.
struct Layout {
  const char* capture;
  std::size_t packets;
  std::size_t points;
  Model model;
  const char* angles_a;
  const char* angles_b;
  const char* firetimes;
  std::size_t payload;
  std::size_t blocks;
  std::size_t channels;
  std::size_t point_bytes;
  std::size_t body;        // offset of block 1
  std::size_t block_bytes;
  std::size_t azimuth_in_block;
  std::size_t points_in_block;
  // The smallest raw distance that is a measurement, below which a unit is no point. 0 is no
  // return on every model (Pandar40P packet document, "Channel Measurements", Distance Data:
  // "Invalid measurement: 0x0000 (no return detected)"); the QT128C2X reserves 1 as well
  // (QT128C2X manual, Chinese edition, Section 3.1.2 UDP data, the table of Distance values after
  // the body table: Distance = 0 no return, Distance = 1 a reserved marker). The decoder's
  // smallest is the same (the sensor descriptors' min_distance, core/src/sensors/): no model has a
  // larger one, since the manuals' ranging specifications (Pandar64 manual Section 1.5, "Ranging
  // capability 0.3 to 200 m") state performance, not a rule of the packet.
  std::uint16_t min_distance;
};

const Layout kPandar40P{"pandar40p_dual.pcap", 1439, 434934, Model::pandar40p,
                        "calibration/pandar40p_unit_a_angles.csv", "calibration/pandar40p_unit_b_angles.csv",
                        "calibration/pandar40p_firetimes.csv", 1262, 10, 40, 3, 0, 124, 2, 4, 1};
const Layout kPandar64{"pandar64_dual.pcap", 2400, 716622, Model::pandar64,
                       "calibration/pandar64_unit_a_angles.csv", "calibration/pandar64_unit_b_angles.csv",
                       "calibration/pandar64_firetimes.csv", 1198, 6, 64, 3, 8, 194, 0, 2, 1};
const Layout kQt128{"qt128c2x_dual.pcap", 1800, 337108, Model::qt128c2x,
                    "calibration/qt128c2x_unit_a_angles.csv", "calibration/qt128c2x_unit_a_angles.csv",
                    "calibration/qt128c2x_firetimes.csv", 1127, 2, 128, 4, 12, 514, 0, 2, 2};

std::vector<std::uint8_t> file_bytes(const std::string& name) { return read_file(data_path(name)); }

hesai::AngleCorrection load_angles(const std::string& name, std::size_t channels) {
  hesai::AngleCorrection a;
  const std::vector<std::uint8_t> text = file_bytes(name);
  const hesai::ParseResult r = hesai::parse_angle_csv(view(text), channels, a);
  EXPECT_EQ(r.error, Error::ok) << name << " line " << r.line;
  return a;
}

hesai::FiretimeCorrection load_firetimes(const std::string& name, std::size_t channels) {
  hesai::FiretimeCorrection f;
  const std::vector<std::uint8_t> text = file_bytes(name);
  const hesai::ParseResult r = hesai::parse_firetime_csv(view(text), channels, f);
  EXPECT_EQ(r.error, Error::ok) << name << " line " << r.line;
  return f;
}

// t0 from the tail, by the manual's formula: date-time (whole seconds, UTC) + timestamp (us).
std::int64_t packet_time_ns(const Layout& l, const std::vector<std::uint8_t>& p) {
  std::size_t date = 0, ts = 0;
  if (l.model == Model::pandar40p) { date = 1256; ts = 1250; }
  if (l.model == Model::pandar64) { date = 1188; ts = 1182; }
  if (l.model == Model::qt128c2x) { date = 1076; ts = 1082; }
  // Year byte: QT128 year - 1900; Pandar40P/64 by the vendor SDK's rule, < 70 -> 2000 + byte
  // (the manual's year - 2000), else 1900 + byte (the Pandar64 capture sends 120 for 2020).
  const int year_base = l.model == Model::qt128c2x || p[date] >= 70 ? 1900 : 2000;
  const std::int64_t s = timegm_utc(year_base + p[date], p[date + 1], p[date + 2], p[date + 3], p[date + 4], p[date + 5]);
  return s * 1000000000LL + static_cast<std::int64_t>(hesai::load_le32(&p[ts])) * 1000;
}

// Block time offset from t0 in ns, from the manuals' tables (all captures are dual return).
std::int64_t block_offset_ns(const Layout& l, std::size_t block) {
  if (l.model == Model::qt128c2x) return 9000;  // dual: both blocks start at t0 + 9 us
  const std::int64_t last = l.model == Model::pandar64 ? -42580 : -28580;
  const std::int64_t firings_after = static_cast<std::int64_t>((l.blocks - 1 - block) / 2);
  return last - 55560 * firings_after;
}

struct RefPoint {
  double x, y, z, azimuth;
  std::int64_t time_ns;
};

// Test names and failure messages show the model, not the struct's bytes.
void PrintTo(const Layout& l, std::ostream* os) { *os << hesai::model_name(l.model); }

class Golden : public ::testing::TestWithParam<Layout> {};

// Packets, points, return mode and spin rate, counted from the raw bytes by this test's loops.
TEST_P(Golden, CountsFromRawBytes) {
  const Layout& l = GetParam();
  const auto packets = pcap_payloads(l.capture);
  ASSERT_EQ(packets.size(), l.packets);
  Decoder dec(l.model);
  PacketPoints pts;
  PacketInfo info;
  std::size_t raw_points = 0, decoded = 0;
  for (const auto& p : packets) {
    ASSERT_EQ(p.size(), l.payload);
    for (std::size_t b = 0; b < l.blocks; ++b)
      for (std::size_t c = 0; c < l.channels; ++c)
        raw_points += hesai::load_le16(&p[l.body + b * l.block_bytes + l.points_in_block + c * l.point_bytes]) >=
                      l.min_distance;
    ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
    decoded += pts.count;
    EXPECT_EQ(info.return_mode, 0x39);  // every capture is dual return (last + strongest)
    EXPECT_EQ(info.returns, 2);
    EXPECT_GE(info.motor_rpm, 590);  // about 600 rpm
    EXPECT_LE(info.motor_rpm, 610);
  }
  EXPECT_EQ(decoded, raw_points);
  EXPECT_EQ(raw_points, l.points);  // also counted by tests/golden/count_points.py
}

// Every point against the reference computation, with the unit's own angle and firing-time files.
// Counter-clockwise: the capture's azimuths mirrored (counterclockwise_copy), and the firing-time
// correction subtracted: a channel fired t after its block has turned back by spin rate x t, in a
// coordinate system that stays clockwise (Pandar40 manual Section 4.2, item 6).
void expect_every_point_matches(const Layout& l, hesai::Rotation rotation) {
  const bool ccw = rotation == hesai::Rotation::counterclockwise;
  auto packets = pcap_payloads(l.capture);
  ASSERT_EQ(packets.size(), l.packets);
  if (ccw)
    for (auto& p : packets) p = counterclockwise_copy(p, l.model);
  const ReferenceCalibration ref = read_reference_calibration(l.angles_a, l.firetimes, l.channels);
  Decoder dec(l.model);
  ASSERT_EQ(dec.set_angles(load_angles(l.angles_a, l.channels)), Error::ok);
  ASSERT_EQ(dec.set_firetimes(load_firetimes(l.firetimes, l.channels)), Error::ok);
  dec.set_rotation(rotation);
  PacketPoints pts;
  PacketInfo info;
  double worst = 0;
  std::size_t checked = 0;
  const double kDeg = M_PI / 180;
  const double turn = ccw ? -1.0 : 1.0;
  for (const auto& p : packets) {
    ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
    const std::int64_t t0 = packet_time_ns(l, p);
    EXPECT_EQ(info.time_ns, t0);
    const double rpm = hesai::load_le16(&p[l.model == Model::pandar64 ? 1180 : l.model == Model::qt128c2x ? 1074 : 1248]);
    const bool seq1 = l.model == Model::qt128c2x && (p[1066] & 1);
    std::size_t k = 0;
    for (std::size_t b = 0; b < l.blocks; ++b) {
      const std::uint8_t* blk = &p[l.body + b * l.block_bytes];
      const double block_az = hesai::load_le16(blk + l.azimuth_in_block) / 100.0;
      for (std::size_t c = 0; c < l.channels; ++c) {
        const std::uint8_t* q = blk + l.points_in_block + c * l.point_bytes;
        const std::uint16_t raw = hesai::load_le16(q);
        if (raw < l.min_distance) continue;  // no return, or the QT128's marker
        const double fire = (l.model == Model::qt128c2x && !seq1) ? ref.fire2[c] : ref.fire1[c];
        const double r = raw * 0.004;
        const double az = block_az + ref.azimuth[c] + turn * fire * rpm * 360.0 / 60e6;
        const double e = ref.elevation[c] * kDeg;
        const double x = r * std::cos(e) * std::sin(az * kDeg);
        const double y = r * std::cos(e) * std::cos(az * kDeg);
        const double z = r * std::sin(e);
        const std::int64_t t = t0 + block_offset_ns(l, b) + std::llround(fire * 1000);
        ASSERT_LT(k, pts.count);
        const hesai::Point& o = pts.points[k++];
        ASSERT_EQ(o.channel, c + 1);
        ASSERT_EQ(o.block, b);
        ASSERT_EQ(o.return_index, b % 2);
        ASSERT_EQ(o.intensity, q[2]);
        ASSERT_EQ(o.time_ns, t);
        const double err = std::max({std::fabs(o.x - x), std::fabs(o.y - y), std::fabs(o.z - z)});
        worst = std::max(worst, err);
        ASSERT_LT(err, 1e-3) << "packet point " << k;
        double daz = std::fabs(o.azimuth_deg - std::fmod(az + 720.0, 360.0));
        if (daz > 180) daz = 360 - daz;
        ASSERT_LT(daz, 1e-3);
        ++checked;
      }
    }
    ASSERT_EQ(k, pts.count);
  }
  // Every point of the capture, as counted from its raw bytes by CountsFromRawBytes's loop and by
  // tests/golden/count_points.py (ctest golden_counts), was checked.
  EXPECT_EQ(checked, l.points);
  ::testing::Test::RecordProperty("worst_error_m", std::to_string(worst));
}

TEST_P(Golden, EveryPointMatchesDoubleReference) { expect_every_point_matches(GetParam(), hesai::Rotation::clockwise); }

TEST_P(Golden, CounterClockwiseEveryPointMatchesDoubleReference) {
  expect_every_point_matches(GetParam(), hesai::Rotation::counterclockwise);
}

// The same packet decoded as clockwise and as counter-clockwise: each point's azimuth differs by
// twice its firing-time correction, 2 x firing time x spin rate; its range, elevation and time not.
TEST_P(Golden, RotationMovesEachPointByTwiceItsCorrection) {
  const Layout& l = GetParam();
  const auto packets = pcap_payloads(l.capture);
  ASSERT_EQ(packets.size(), l.packets);
  const ReferenceCalibration ref = read_reference_calibration(l.angles_a, l.firetimes, l.channels);
  Decoder cw(l.model), ccw(l.model);
  ccw.set_rotation(hesai::Rotation::counterclockwise);
  for (Decoder* d : {&cw, &ccw}) {
    ASSERT_EQ(d->set_angles(load_angles(l.angles_a, l.channels)), Error::ok);
    ASSERT_EQ(d->set_firetimes(load_firetimes(l.firetimes, l.channels)), Error::ok);
  }
  EXPECT_EQ(ccw.rotation(), hesai::Rotation::counterclockwise);
  PacketPoints a, b;
  PacketInfo ia, ib;
  ASSERT_EQ(cw.decode(view(packets[0]), ia, a), Error::ok);
  ASSERT_EQ(ccw.decode(view(packets[0]), ib, b), Error::ok);
  ASSERT_EQ(a.count, b.count);
  const bool seq1 = l.model == Model::qt128c2x && (packets[0][1066] & 1);
  for (std::size_t i = 0; i < a.count; ++i) {
    const std::size_t c = a.points[i].channel - 1u;
    const double fire = (l.model == Model::qt128c2x && !seq1) ? ref.fire2[c] : ref.fire1[c];
    double gap = a.points[i].azimuth_deg - b.points[i].azimuth_deg;
    if (gap > 180) gap -= 360;
    if (gap < -180) gap += 360;
    EXPECT_NEAR(gap, 2 * fire * ia.motor_rpm * 360.0 / 60e6, 1e-3) << "channel " << c + 1;
    EXPECT_EQ(a.points[i].distance_m, b.points[i].distance_m);
    EXPECT_EQ(a.points[i].elevation_deg, b.points[i].elevation_deg);
    EXPECT_EQ(a.points[i].time_ns, b.points[i].time_ns);
  }
}

// unit_a and unit_b are different units of the same model: their files must move the points.
// (No second QT128 unit file is bundled: its unit_a file is compared with the manual's design
// angles, from which it differs by up to 0.0005 degree.)
TEST_P(Golden, CalibrationFileIsApplied) {
  const Layout& l = GetParam();
  const bool has_b = l.model != Model::qt128c2x;
  const auto packets = pcap_payloads(l.capture);
  ASSERT_EQ(packets.size(), l.packets);
  Decoder a(l.model), b(l.model);
  ASSERT_EQ(a.set_angles(load_angles(l.angles_a, l.channels)), Error::ok);
  if (has_b) {
    ASSERT_EQ(b.set_angles(load_angles(l.angles_b, l.channels)), Error::ok);
  }
  PacketPoints pa, pb;
  PacketInfo ia, ib;
  ASSERT_EQ(a.decode(view(packets[0]), ia, pa), Error::ok);
  ASSERT_EQ(b.decode(view(packets[0]), ib, pb), Error::ok);
  ASSERT_EQ(pa.count, pb.count);
  std::size_t moved = 0;
  for (std::size_t i = 0; i < pa.count; ++i) {
    const bool angle = pa.points[i].elevation_deg != pb.points[i].elevation_deg ||
                       pa.points[i].azimuth_deg != pb.points[i].azimuth_deg;
    moved += angle && (!has_b || std::fabs(pa.points[i].z - pb.points[i].z) > 1e-4);
  }
  EXPECT_GT(moved, pa.count / 2);
}

INSTANTIATE_TEST_SUITE_P(Captures, Golden, ::testing::Values(kPandar40P, kPandar64, kQt128),
                         [](const auto& i) { return std::string(hesai::model_name(i.param.model)); });

// ---- Header fields of the first packets, with the bytes they were read from ----

TEST(GoldenHeader, Pandar64FirstPacket) {
  const auto packets = pcap_payloads("pandar64_dual.pcap");
  ASSERT_FALSE(packets.empty());
  const auto& p = packets[0];
  // Header: ee ff 40 06 00 04 00 00 -> 64 lasers, 6 blocks, distance unit 4 mm.
  EXPECT_EQ(p[0], 0xEE); EXPECT_EQ(p[1], 0xFF); EXPECT_EQ(p[2], 0x40); EXPECT_EQ(p[3], 0x06); EXPECT_EQ(p[5], 0x04);
  Decoder dec(Model::pandar64);
  PacketInfo info;
  ASSERT_EQ(dec.validate(view(p), info), Error::ok);
  EXPECT_EQ(info.dis_unit_mm, 4);
  // Tail at 1172: 76 34 08 6e 6e | 00 | 00 00 | 57 02 | bd e9 0e 00 | 39 | 42 | 78 06 19 0c 02 09 | 89 b3 23 00
  EXPECT_EQ(info.high_temperature, 0);
  EXPECT_EQ(info.motor_rpm, 0x0257);          // 599 rpm
  EXPECT_EQ(info.timestamp_us, 0x000EE9BDu);  // 977341 us
  EXPECT_EQ(info.return_mode, 0x39);
  EXPECT_EQ(info.factory_info, 0x42);
  EXPECT_TRUE(info.has_sequence);
  EXPECT_EQ(info.sequence, 0x0023B389u);
  // Date & Time 0x78 = 120 -> 1900 + 120 = 2020 (the vendor SDK's rule: a byte >= 70 counts years
  // since 1900; the manual's year - 2000 would give 2120), 06-25 12:02:09.
  EXPECT_EQ(info.date_time.year, 2020);
  EXPECT_EQ(info.date_time.month, 6);
  EXPECT_EQ(info.date_time.day, 25);
  EXPECT_EQ(info.date_time.hour, 12);
  EXPECT_EQ(info.date_time.minute, 2);
  EXPECT_EQ(info.date_time.second, 9);
  // calendar.timegm((2020,6,25,12,2,9)) = 1593086529.
  EXPECT_EQ(info.time_ns, 1593086529LL * 1000000000 + 977341000LL);
}

TEST(GoldenHeader, Pandar40PFirstPacket) {
  const auto packets = pcap_payloads("pandar40p_dual.pcap");
  ASSERT_FALSE(packets.empty());
  const auto& p = packets[0];
  EXPECT_EQ(p[0], 0xFF); EXPECT_EQ(p[1], 0xEE);  // block preamble, 0xFF first
  Decoder dec(Model::pandar40p);
  PacketInfo info;
  ASSERT_EQ(dec.validate(view(p), info), Error::ok);
  // Block 1 azimuth: bytes 93 00 -> 147 = 1.47 degrees.
  EXPECT_EQ(info.block_azimuth[0], 0x0093);
  // Tail at 1240 (22 bytes): ... 58 02 | 9f 73 0d 00 | 39 | 42 | 11 09 06 10 13 2e
  EXPECT_EQ(info.motor_rpm, 0x0258);          // 600 rpm
  EXPECT_EQ(info.timestamp_us, 0x000D739Fu);  // 881567 us
  EXPECT_EQ(info.return_mode, 0x39);
  EXPECT_EQ(info.factory_info, 0x42);
  EXPECT_FALSE(info.has_sequence);
  // 0x11 = 17 -> 2017-09-06 16:19:46; calendar.timegm = 1504714786.
  EXPECT_EQ(info.date_time.year, 2017);
  EXPECT_EQ(info.time_ns, 1504714786LL * 1000000000 + 881567000LL);
}

TEST(GoldenHeader, Qt128FirstPacket) {
  const auto packets = pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_FALSE(packets.empty());
  const auto& p = packets[0];
  // Pre-header + header: ee ff 03 02 03 00 | 80 02 01 04 02 1d
  EXPECT_EQ(p[2], 0x03); EXPECT_EQ(p[3], 0x02); EXPECT_EQ(p[6], 0x80); EXPECT_EQ(p[7], 0x02);
  EXPECT_EQ(p[10], 0x02); EXPECT_EQ(p[11], 0x1D);
  Decoder dec(Model::qt128c2x);
  PacketInfo info;
  ASSERT_EQ(dec.validate(view(p), info), Error::ok);
  EXPECT_EQ(info.flags, 0x1D);  // sequence, functional safety, signature, and reserved bit 4
  EXPECT_EQ(info.dis_unit_mm, 4);
  EXPECT_EQ(info.returns, 2);
  // Functional safety at 1044: 01 05 00 00 ... -> version 1, state 0b000 (init), counter 5.
  EXPECT_TRUE(info.safety.present);
  EXPECT_EQ(info.safety.version, 1);
  EXPECT_EQ(info.safety.lidar_state, 0);
  EXPECT_EQ(info.safety.rolling_counter, 5);
  // Tail at 1061: 64 00 1c 00 00 | 00 | ff ff 06 00 00 00 | 39 | 58 02 | 78 0a 09 0c 03 1d |
  //               4b 26 06 00 | 42 | cd 92 61 00 | 1e f9 45 a7
  EXPECT_EQ(info.mode_flag, 0);  // block 1 uses firing sequence 2
  EXPECT_EQ(info.return_mode, 0x39);
  EXPECT_EQ(info.motor_rpm, 600);
  EXPECT_EQ(info.timestamp_us, 0x0006264Bu);  // 403019 us
  EXPECT_EQ(info.sequence, 0x006192CDu);
  // Year 0x78 = 120 -> 1900 + 120 = 2020-10-09 12:03:29; calendar.timegm = 1602245009.
  EXPECT_EQ(info.date_time.year, 2020);
  EXPECT_EQ(info.time_ns, 1602245009LL * 1000000000 + 403019000LL);
  // The signature bytes are all zero: signing was not started.
  EXPECT_EQ(info.signature, hesai::SignatureStatus::not_signed);
}

// QT128C2X manual, Appendix II, "Firing Sequences": Firing Sequence 1 fires Banks C, D and B
// while Bank A rests; Firing Sequence 2 fires Banks C, D and A while Bank B rests. Appendix I,
// "Division of Channels into Banks": Bank A is Channels 1 to 32, Bank B Channels 33 to 64.
bool rests_in_sequence(bool sequence1, std::size_t channel) {
  return sequence1 ? channel <= 32 : channel >= 33 && channel <= 64;
}

// The bundled firetime file agrees with the rule: a channel rests in a loop exactly when the
// loop's column lists no firing time for it (Appendix II, "Firetime Correction File").
TEST(GoldenQt128, FiretimeFileRestsTheBanksOfTheRule) {
  const ReferenceCalibration ref = read_reference_calibration(
      "calibration/qt128c2x_unit_a_angles.csv", "calibration/qt128c2x_firetimes.csv", 128);
  for (std::size_t c = 1; c <= 128; ++c) {
    EXPECT_EQ(ref.fire1[c - 1] == 0, rests_in_sequence(true, c)) << c;
    EXPECT_EQ(ref.fire2[c - 1] == 0, rests_in_sequence(false, c)) << c;
  }
}

// Section 3.1.2, Tail: the mode flag names the firing sequence of block 1 (1 = sequence 1,
// 0 = sequence 2); Body: "If a channel does not fire in the current firing sequence, its
// corresponding four bytes are filled with 0." On every packet of the real capture, every
// resting channel is zero, and the sequence alternates packet to packet (dual return).
TEST(GoldenQt128, ModeFlagNamesTheFiringSequence) {
  const auto packets = pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_EQ(packets.size(), kQt128.packets);
  std::size_t zero_outside = 0, outside = 0, flag_set = 0;
  for (const auto& p : packets) {
    ASSERT_EQ(p.size(), kQt128.payload);
    const bool seq1 = p[1066] & 1;
    flag_set += seq1;
    for (std::size_t b = 0; b < 2; ++b)
      for (std::size_t c = 1; c <= 128; ++c) {
        if (!rests_in_sequence(seq1, c)) continue;
        ++outside;
        zero_outside += hesai::load_le32(&p[12 + b * 514 + 2 + (c - 1) * 4]) == 0;
      }
  }
  EXPECT_EQ(outside, packets.size() * 2 * 32);  // 32 resting channels per block
  EXPECT_EQ(zero_outside, outside);
  EXPECT_EQ(flag_set, packets.size() / 2);
}

// The QT128C2X's raw distance 1 is a marker, not a point (min_distance above): in a real packet
// with one unit set to 1 the decoder gives one point fewer and none for that channel; set to 2
// (8 mm), the point is back at 0.008 m.
TEST(GoldenQt128, DistanceOneIsAMarkerNotAPoint) {
  const auto packets = pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_FALSE(packets.empty());
  std::vector<std::uint8_t> p = packets[0];
  // Block 0's units from offset 14 (12-byte header, 2-byte azimuth), 4 bytes each: the first
  // channel with a measured distance.
  std::size_t channel = 0;
  while (channel < 128 && hesai::load_le16(&p[14 + channel * 4]) < 2) ++channel;
  ASSERT_LT(channel, 128u);
  std::size_t raw_points = 0;
  for (std::size_t b = 0; b < 2; ++b)
    for (std::size_t c = 0; c < 128; ++c) raw_points += hesai::load_le16(&p[12 + b * 514 + 2 + c * 4]) >= 2;
  Decoder dec(Model::qt128c2x);
  PacketInfo info;
  PacketPoints pts;
  for (const std::uint16_t raw : {std::uint16_t{1}, std::uint16_t{2}}) {
    hesai::store_le16(&p[14 + channel * 4], raw);
    qt128_seal(p);
    ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
    EXPECT_EQ(pts.count, raw == 1 ? raw_points - 1 : raw_points);
    std::size_t found = 0;
    for (const hesai::Point& q : pts)
      if (q.block == 0 && q.channel == channel + 1) {
        ++found;
        EXPECT_FLOAT_EQ(q.distance_m, 0.008f);
      }
    EXPECT_EQ(found, raw == 1 ? 0u : 1u) << "raw distance " << raw;
  }
}

}  // namespace
