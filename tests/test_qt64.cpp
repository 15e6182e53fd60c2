// PandarQT64 (point cloud protocol 3.1) on its bundled real capture, data/pandar_qt64.pcap, and on
// packets derived from it. No manual for this model is among the seeds: the layout is the vendor
// SDK's (udp_protocol_v3_1.h) and nebula's (pandar_qt64.hpp). Expected header values were read by
// hand from the hex bytes quoted beside them; counts come from this file's own loops over the raw
// bytes; every point is checked against a plain double-precision evaluation written here.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "hesai/calibration.h"
#include "hesai/decoder.h"
#include "hesai/frame.h"
#include "hesai/sequence.h"
#include "packet_builder.h"
#include "test_support.h"

using hesai::Decoder;
using hesai::Error;
using hesai::Model;
using hesai::PacketInfo;
using hesai::PacketPoints;
using namespace hesai_test;

namespace {

// The layout, typed from the SDK's udp_protocol_v3_1.h: 12-byte header, 4 blocks of azimuth u16
// + 64 x {distance u16, reflectivity u8, confidence u8}, 28-byte tail ending in the UDP sequence.
constexpr std::size_t kPayload = 1072, kBody = 12, kBlockBytes = 258, kTail = 1044;
// The capture's packets and points (non-zero distances), counted by RawCounts below and again by
// tests/golden/count_points.py (ctest golden_counts), which reads them from this initializer.
struct Totals {
  const char* capture;
  std::size_t packets, points;
};
constexpr Totals kTotals{"pandar_qt64.pcap", 1200, 299376};
constexpr std::size_t kPackets = kTotals.packets;
constexpr std::size_t kPoints = kTotals.points;

const char* const kCapture = kTotals.capture;
const char* const kAngles = "calibration/pandar_qt64_angles.csv";
const char* const kFiretimes = "calibration/pandar_qt64_firetimes.csv";

std::vector<std::uint8_t> first_packet() {
  const auto packets = pcap_payloads(kCapture);
  EXPECT_FALSE(packets.empty());
  return packets.empty() ? std::vector<std::uint8_t>(kPayload) : packets[0];
}

// t0: date-time (year byte + 1900, the SDK's tm_year) + timestamp (us), from the tail's bytes.
std::int64_t packet_time_ns(const std::vector<std::uint8_t>& p) {
  const std::uint8_t* dt = &p[kTail + 18];
  const std::int64_t s = timegm_utc(1900 + dt[0], dt[1], dt[2], dt[3], dt[4], dt[5]);
  return s * 1000000000LL + static_cast<std::int64_t>(hesai::load_le32(&p[kTail + 12])) * 1000;
}

// Packets, points, return mode and spin rate, counted from the raw bytes by this test's loops.
TEST(Qt64Golden, RawCounts) {
  const auto packets = pcap_payloads(kCapture);
  ASSERT_EQ(packets.size(), kPackets);
  Decoder dec(Model::pandar_qt64);
  PacketPoints pts;
  PacketInfo info;
  std::size_t raw = 0, decoded = 0;
  for (const auto& p : packets) {
    ASSERT_EQ(p.size(), kPayload);
    for (std::size_t b = 0; b < 4; ++b)
      for (std::size_t c = 0; c < 64; ++c) raw += hesai::load_le16(&p[kBody + b * kBlockBytes + 2 + c * 4]) != 0;
    ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
    decoded += pts.count;
    EXPECT_EQ(info.model, Model::pandar_qt64);
    EXPECT_EQ(info.return_mode, 0x3B);  // first + last, dual
    EXPECT_EQ(info.returns, 2);
    EXPECT_EQ(info.motor_rpm, 600);
    EXPECT_TRUE(info.has_sequence);
  }
  EXPECT_EQ(raw, kPoints);
  EXPECT_EQ(decoded, raw);
}

// Header and tail of the first packet, with the bytes they were read from.
TEST(Qt64Golden, FirstPacketFields) {
  const auto p = first_packet();
  // Pre-header + header: ee ff 03 01 00 00 | 40 04 01 04 02 01 -> protocol 3.1, 64 lasers,
  // 4 blocks, first block return 1, dis unit 4 mm, return num 2, flags 0x01 (UDP sequence).
  const std::uint8_t header[12] = {0xEE, 0xFF, 0x03, 0x01, 0x00, 0x00, 0x40, 0x04, 0x01, 0x04, 0x02, 0x01};
  for (std::size_t i = 0; i < 12; ++i) EXPECT_EQ(p[i], header[i]) << i;
  Model m = Model::unknown;
  hesai::PacketKind kind{};
  ASSERT_EQ(hesai::identify(view(p), m, kind), Error::ok);
  EXPECT_EQ(m, Model::pandar_qt64);
  Decoder dec(Model::pandar_qt64);
  PacketInfo info;
  ASSERT_EQ(dec.validate(view(p), info), Error::ok);
  EXPECT_EQ(info.blocks, 4);
  EXPECT_EQ(info.dis_unit_mm, 4);
  EXPECT_EQ(info.flags, 0x01);
  // Block azimuths: 78 00, 78 00, b4 00, b4 00 -> 1.20, 1.20, 1.80, 1.80 degrees.
  EXPECT_EQ(info.block_azimuth[0], 0x78);
  EXPECT_EQ(info.block_azimuth[1], 0x78);
  EXPECT_EQ(info.block_azimuth[2], 0xB4);
  EXPECT_EQ(info.block_azimuth[3], 0xB4);
  // Tail at 1044: 13 05 03 00 00 00 | 00 | 00 00 00 | 58 02 | aa 7b 0c 00 | 3b | 42 |
  //               75 09 06 0e 1f 16 | 39 86 02 00
  EXPECT_EQ(p[kTail + 10], 0x58); EXPECT_EQ(p[kTail + 16], 0x3B); EXPECT_EQ(p[kTail + 18], 0x75);
  EXPECT_EQ(info.high_temperature, 0);        // shutdown flag
  EXPECT_EQ(info.motor_rpm, 0x0258);          // 600 rpm
  EXPECT_EQ(info.timestamp_us, 0x000C7BAAu);  // 818090 us
  EXPECT_EQ(info.return_mode, 0x3B);
  EXPECT_EQ(info.returns, 2);
  EXPECT_EQ(info.factory_info, 0x42);
  EXPECT_TRUE(info.has_sequence);
  EXPECT_EQ(info.sequence, 0x00028639u);      // 165433
  // Year 0x75 = 117 -> 1900 + 117 = 2017-09-06 14:31:22; calendar.timegm = 1504708282.
  const hesai::DateTime& d = info.date_time;
  EXPECT_EQ(std::make_tuple(d.year, +d.month, +d.day, +d.hour, +d.minute, +d.second),
            std::make_tuple(2017, 9, 6, 14, 31, 22));
  EXPECT_EQ(info.time_ns, 1504708282LL * 1000000000 + 818090000LL);
}

// The UDP sequence counts up by one over the whole capture: no loss.
TEST(Qt64Golden, SequenceHasNoGap) {
  const auto packets = pcap_payloads(kCapture);
  ASSERT_EQ(packets.size(), kPackets);
  for (std::size_t i = 1; i < packets.size(); ++i)
    ASSERT_EQ(hesai::load_le32(&packets[i][kTail + 24]), hesai::load_le32(&packets[i - 1][kTail + 24]) + 1) << i;
}

// Loss accounting from the tail's UDP sequence (flags bit 0): the capture with packets 10, 11 and
// 500 left out loses 3, in two gaps.
TEST(Qt64Golden, SequenceLossFromTheTail) {
  const auto packets = pcap_payloads(kCapture);
  ASSERT_EQ(packets.size(), kPackets);
  Decoder dec(Model::pandar_qt64);
  hesai::SequenceTracker tracker;
  PacketInfo info;
  std::uint64_t lost = 0;
  for (std::size_t i = 0; i < packets.size(); ++i) {
    if (i == 10 || i == 11 || i == 500) continue;
    ASSERT_EQ(dec.validate(view(packets[i]), info), Error::ok);
    ASSERT_TRUE(info.has_sequence);
    lost += tracker.observe(info.sequence);
  }
  EXPECT_EQ(lost, 3u);
  EXPECT_EQ(tracker.counts().lost, 3u);
}

// Every point against the reference, with the unit's angle file and the vendor's firing times
// (`files`), or with the built-in tables, which hold the same numbers (tables/qt64_tables.h).
// Reference: distance x 4 mm; azimuth = block azimuth + channel offset + firing time x rpm x 360
// / 60e6 (the SDK's GetFiretimesCorrection, rpm x 6e-6 degree per us); time = t0 + 25.71 us +
// 166.67 us x firing (block / 2 in dual return) + firing time (SDK udp3_1_parser.cc).
// Counter-clockwise: the capture's block azimuths mirrored (a -> 36000 - a) and the firing-time
// term subtracted, as for every sensor (README, "Geometry and time").
void expect_every_point_matches(bool files, hesai::Rotation rotation = hesai::Rotation::clockwise) {
  const bool ccw = rotation == hesai::Rotation::counterclockwise;
  auto packets = pcap_payloads(kCapture);
  ASSERT_EQ(packets.size(), kPackets);
  if (ccw)
    for (auto& p : packets) p = counterclockwise_copy(p, Model::pandar_qt64);
  const ReferenceCalibration ref = read_reference_calibration(kAngles, kFiretimes, 64);
  Decoder dec(Model::pandar_qt64);
  dec.set_rotation(rotation);
  if (files) {
    hesai::AngleCorrection a;
    hesai::FiretimeCorrection f;
    const auto at = read_file(data_path(kAngles));
    const auto ft = read_file(data_path(kFiretimes));
    ASSERT_EQ(hesai::parse_angle_csv(view(at), 64, a).error, Error::ok);
    ASSERT_EQ(hesai::parse_firetime_csv(view(ft), 64, f).error, Error::ok);
    ASSERT_EQ(dec.set_angles(a), Error::ok);
    ASSERT_EQ(dec.set_firetimes(f), Error::ok);
  }
  const double kDeg = M_PI / 180;
  const std::int64_t firing_start_ns[4] = {0, 166670, 333330, 500000};
  PacketPoints pts;
  PacketInfo info;
  std::size_t checked = 0;
  double worst = 0;
  for (const auto& p : packets) {
    ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
    const std::int64_t t0 = packet_time_ns(p);
    ASSERT_EQ(info.time_ns, t0);
    const double rpm = hesai::load_le16(&p[kTail + 10]);
    std::size_t k = 0;
    for (std::size_t b = 0; b < 4; ++b) {
      const std::uint8_t* blk = &p[kBody + b * kBlockBytes];
      const double block_az = hesai::load_le16(blk) / 100.0;
      for (std::size_t c = 0; c < 64; ++c) {
        const std::uint8_t* q = blk + 2 + c * 4;
        const std::uint16_t raw = hesai::load_le16(q);
        if (raw == 0) continue;
        const double r = raw * 0.004;
        const double az = block_az + ref.azimuth[c] + (ccw ? -1 : 1) * ref.fire1[c] * rpm * 360.0 / 60e6;
        const double e = ref.elevation[c] * kDeg;
        const double x = r * std::cos(e) * std::sin(az * kDeg);
        const double y = r * std::cos(e) * std::cos(az * kDeg);
        const double z = r * std::sin(e);
        const std::int64_t t = t0 + 25710 + firing_start_ns[b / 2] + std::llround(ref.fire1[c] * 1000);
        ASSERT_LT(k, pts.count);
        const hesai::Point& o = pts.points[k++];
        ASSERT_EQ(o.channel, c + 1);
        ASSERT_EQ(o.block, b);
        ASSERT_EQ(o.return_index, b % 2);
        ASSERT_EQ(o.intensity, q[2]);
        ASSERT_EQ(o.confidence, q[3]);
        ASSERT_EQ(o.time_ns, t);
        ASSERT_NEAR(o.distance_m, r, 1e-6);
        ASSERT_NEAR(o.elevation_deg, ref.elevation[c], 1e-4);
        const double err = std::max({std::fabs(o.x - x), std::fabs(o.y - y), std::fabs(o.z - z)});
        worst = std::max(worst, err);
        ASSERT_LT(err, 1e-4) << "point " << k;
        double daz = std::fabs(o.azimuth_deg - std::fmod(az + 720.0, 360.0));
        if (daz > 180) daz = 360 - daz;
        ASSERT_LT(daz, 1e-3);
        ++checked;
      }
    }
    ASSERT_EQ(k, pts.count);
  }
  EXPECT_EQ(checked, kPoints);
  ::testing::Test::RecordProperty("worst_error_m", std::to_string(worst));
}

TEST(Qt64Golden, EveryPointMatchesDoubleReferenceWithUnitFiles) { expect_every_point_matches(true); }
TEST(Qt64Golden, EveryPointMatchesDoubleReferenceWithBuiltInTables) { expect_every_point_matches(false); }
TEST(Qt64Golden, CounterClockwiseEveryPointMatchesDoubleReference) {
  expect_every_point_matches(true, hesai::Rotation::counterclockwise);
}

// Worked by hand. Packet 1, block 3 (the second firing of the dual-return packet), channel 10:
// unit bytes 19 00 c1 00 -> 25 x 4 mm = 0.100 m, reflectivity 193; block azimuth b4 00 = 1.80 deg.
// Channel 10: elevation -34.320, azimuth offset 6.554 (angle file); firing time 21.22 us.
// Time: t0 + 25.71 + 166.67 + 21.22 us = 818090 + 213.60 us -> 1504708282 s + 818303600 ns.
// Azimuth: 1.80 + 6.554 + 21.22 us x 600 rpm x 360 / 60e6 (= 0.076392) = 8.430392 degrees.
TEST(Qt64Golden, HandWorkedPoint) {
  const auto p = first_packet();
  Decoder dec(Model::pandar_qt64);
  PacketPoints pts;
  PacketInfo info;
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  const hesai::Point* found = nullptr;
  for (const hesai::Point& o : pts)
    if (o.block == 2 && o.channel == 10) found = &o;
  ASSERT_NE(found, nullptr);
  EXPECT_EQ(found->time_ns, 1504708282LL * 1000000000 + 818303600LL);
  EXPECT_NEAR(found->azimuth_deg, 8.430392, 1e-4);
  EXPECT_NEAR(found->elevation_deg, -34.320, 1e-4);
  EXPECT_NEAR(found->distance_m, 0.100, 1e-6);
  EXPECT_EQ(found->intensity, 193);
  EXPECT_EQ(found->return_index, 0);  // first return (block 3 of 4: the first of its pair)
}

// ---- Packets derived from the capture's first packet ----

std::vector<std::uint8_t> changed(std::size_t at, std::uint8_t value) {
  auto p = first_packet();
  p[at] = value;
  return p;
}

Error validate(const std::vector<std::uint8_t>& p, PacketInfo& info) {
  Decoder dec(Model::pandar_qt64);
  return dec.validate(view(p), info);
}
Error validate(const std::vector<std::uint8_t>& p) {
  PacketInfo info;
  return validate(p, info);
}

TEST(Qt64Packet, Identification) {
  Model m = Model::unknown;
  hesai::PacketKind kind{};
  auto p = first_packet();
  // Without the UDP sequence flag the packet is 4 bytes shorter (SDK GetPacketSize).
  auto no_seq = changed(11, 0x00);
  EXPECT_EQ(hesai::identify(view(no_seq), m, kind), Error::flags_length_mismatch);
  no_seq.resize(kPayload - 4);
  ASSERT_EQ(hesai::identify(view(no_seq), m, kind), Error::ok);
  EXPECT_EQ(m, Model::pandar_qt64);
  PacketInfo info;
  ASSERT_EQ(validate(no_seq, info), Error::ok);
  EXPECT_FALSE(info.has_sequence);
  p.resize(kPayload - 1);
  EXPECT_EQ(hesai::identify(view(p), m, kind), Error::flags_length_mismatch);
  p.resize(8);
  EXPECT_EQ(hesai::identify(view(p), m, kind), Error::bad_length);
  EXPECT_EQ(hesai::identify(view(changed(6, 0x20)), m, kind), Error::unsupported_model);  // 32 lasers
  EXPECT_EQ(hesai::identify(view(changed(7, 0x02)), m, kind), Error::unsupported_model);  // 2 blocks
  EXPECT_EQ(hesai::identify(view(changed(3, 0x03)), m, kind), Error::unsupported_version);  // 3.3
  // Another model's decoder refuses it.
  Decoder qt128(Model::qt128c2x);
  EXPECT_EQ(qt128.validate(view(first_packet()), info), Error::model_mismatch);
}

TEST(Qt64Packet, FieldRules) {
  EXPECT_EQ(validate(changed(11, 0x03)), Error::unsupported_section);           // IMU flag, no layout
  EXPECT_EQ(validate(changed(9, 0x00)), Error::bad_header);                     // distance unit 0
  EXPECT_EQ(validate(changed(kTail + 16, 0x3D)), Error::bad_return_mode);       // triple: not 4 blocks
  EXPECT_EQ(validate(changed(kTail + 16, 0x00)), Error::bad_return_mode);
  EXPECT_EQ(validate(changed(kTail + 11, 0x06)), Error::bad_motor_speed);       // 0x0658 = 1624 rpm
  EXPECT_EQ(validate(changed(kBody + 1, 0x01)), Error::dual_block_mismatch);    // block 1 at 0x0178
  auto az = first_packet();
  hesai::store_le16(&az[kBody], 36000);
  hesai::store_le16(&az[kBody + kBlockBytes], 36000);
  EXPECT_EQ(validate(az), Error::bad_azimuth);
  auto ts = first_packet();
  hesai::store_le32(&ts[kTail + 12], 1000000);
  EXPECT_EQ(validate(ts), Error::bad_timestamp);
  EXPECT_EQ(validate(changed(kTail + 19, 13)), Error::bad_date_time);           // month 13
  EXPECT_EQ(validate(changed(kTail + 23, 60)), Error::bad_date_time);           // second 60
}

// The SDK's year rule (GetMicroLidarTimeU64): tm_year = byte, + 100 below 70; 0 = Unix seconds.
TEST(Qt64Packet, YearByte) {
  PacketInfo info;
  ASSERT_EQ(validate(changed(kTail + 18, 20), info), Error::ok);
  EXPECT_EQ(info.date_time.year, 2020);
  ASSERT_EQ(validate(changed(kTail + 18, 124), info), Error::ok);
  EXPECT_EQ(info.date_time.year, 2024);
  // Year byte 0: bytes 2..5 hold Unix seconds, big-endian: 65 ee 5a 40 = 1710119488
  // = 2024-03-11 01:11:28 UTC (date -u -d @1710119488).
  auto p = changed(kTail + 18, 0);
  const std::uint8_t secs[4] = {0x65, 0xEE, 0x5A, 0x40};
  for (std::size_t i = 0; i < 4; ++i) p[kTail + 20 + i] = secs[i];
  ASSERT_EQ(validate(p, info), Error::ok);
  EXPECT_EQ(info.time_ns, 1710119488LL * 1000000000 + 818090000LL);
  EXPECT_EQ(info.date_time.year, 2024);
  EXPECT_EQ(info.date_time.month, 3);
}

// Single return: each block is its own firing, 166.67 us apart (SDK PandarQT_BLOCK_NS_OFFSET2),
// and every point has return index 0. Blocks of a single-return packet need not share azimuths.
TEST(Qt64Packet, SingleReturnBlockTimes) {
  for (const std::uint8_t mode : {std::uint8_t{0x37}, std::uint8_t{0x38}, std::uint8_t{0x33}, std::uint8_t{0x34}}) {
    auto p = changed(kTail + 16, mode);
    hesai::store_le16(&p[kBody + kBlockBytes], 0x7E);  // block 2 at 1.26 degrees
    Decoder dec(Model::pandar_qt64);
    PacketPoints pts;
    PacketInfo info;
    ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok) << int(mode);
    EXPECT_EQ(info.returns, 1);
    ASSERT_GT(pts.count, 0u);
    const std::int64_t firing_start_ns[4] = {0, 166670, 333330, 500000};
    const ReferenceCalibration ref = read_reference_calibration(kAngles, kFiretimes, 64);
    for (const hesai::Point& o : pts) {
      EXPECT_EQ(o.return_index, 0);
      EXPECT_EQ(o.time_ns, info.time_ns + 25710 + firing_start_ns[o.block] + std::llround(ref.fire1[o.channel - 1u] * 1000));
    }
  }
}

// The firing-time azimuth term can be switched off: then azimuth = block + channel offset.
TEST(Qt64Packet, FiretimeCorrectionOff) {
  const auto p = first_packet();
  const ReferenceCalibration ref = read_reference_calibration(kAngles, kFiretimes, 64);
  Decoder dec(Model::pandar_qt64);
  dec.set_firetime_correction(false);
  PacketPoints pts;
  PacketInfo info;
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  ASSERT_GT(pts.count, 0u);
  for (const hesai::Point& o : pts)
    EXPECT_NEAR(o.azimuth_deg, std::fmod(info.block_azimuth[o.block] / 100.0 + ref.azimuth[o.channel - 1u] + 360.0, 360.0),
                1e-4);
}

// Frames: by point azimuth through the shared FrameAssembler, one per rotation. The capture's
// block azimuths wrap 4 times (packets 300, 600, 900 and the last, 1199): 4 full rotations
// between 5 wraps of the point azimuths, plus the points of the first packets that lie before
// 0 degrees and those of the last packet past it.
TEST(Qt64Golden, FramesOnePerRotation) {
  const auto packets = pcap_payloads(kCapture);
  ASSERT_EQ(packets.size(), kPackets);
  std::size_t wraps = 0;
  for (std::size_t i = 1; i < packets.size(); ++i)
    wraps += hesai::load_le16(&packets[i][kBody]) < hesai::load_le16(&packets[i - 1][kBody]);
  EXPECT_EQ(wraps, 4u);
  Decoder dec(Model::pandar_qt64);
  hesai::FrameAssembler frames;
  PacketPoints pts;
  PacketInfo info;
  std::map<std::uint64_t, std::size_t> per_frame;
  std::uint64_t index = 0;
  for (const auto& p : packets) {
    ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
    ASSERT_EQ(frames.set_beam_spread(dec.beam_spread()), Error::ok);
    frames.begin_packet(index++, 0);
    for (std::size_t b = 0; b < info.blocks; ++b) {
      frames.block(info.block_azimuth[b]);
      for (hesai::FrameInfo f; frames.pop_closed(f);) {
      }
      for (const hesai::Point& q : pts) {
        if (q.block != b) continue;
        ++per_frame[frames.point(q.azimuth_deg)];
      }
    }
  }
  // Frames 2..5 hold one rotation each: 300 packets x 2 firings x 64 channels, less the
  // no-returns; more than 90% of a full rotation's 76 800 units returned in the capture.
  std::size_t full = 0;
  for (const auto& [id, n] : per_frame) full += n > 70000;
  EXPECT_EQ(full, 4u);
}

}  // namespace
