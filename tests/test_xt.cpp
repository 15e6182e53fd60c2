// Golden tests on the PandarXT16, XT32 and XT32M2X captures (point cloud protocol 6.1), and the
// protocol's rules on packets changed from them. The layout and rules come from the vendor SDK
// (HesaiLidar_SDK_2.0: udp_protocol_v6_1.h, udp6_1_parser.cc) and tier4/nebula (pandar_xt*.hpp),
// as cited in core/src/sensors/xt.cpp. Counts are taken from the raw bytes by this file's loops
// (and were counted again by a plain Python reading of the pcap bytes: the initializers below);
// header values were read by hand from the hex bytes quoted beside them; every point is checked
// against a plain double-precision evaluation.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "hesai/calibration.h"
#include "hesai/decoder.h"
#include "hesai/frame.h"
#include "hesai/sequence.h"
#include "test_support.h"

using hesai::Decoder;
using hesai::Error;
using hesai::Model;
using hesai::PacketInfo;
using hesai::PacketPoints;
using namespace hesai_test;

namespace {

struct XtCapture {
  const char* capture;
  std::size_t packets;
  std::size_t points;  // units of non-zero distance
  Model model;
  const char* angles;
  const char* firetimes;
  std::size_t payload;
  std::size_t blocks;
  std::size_t channels;
  double unit_m;             // the header's dis unit (byte 9): 4 or 5 mm
  std::uint8_t return_mode;  // the tail's (byte 10 of the tail)
  // Design tables the model's sources publish (xt_tables.h cites them): elevation of channel c
  // (1-based) = top - step x (c - 1), azimuth 0; firing time = 6 + fire_step x ((c - 1) mod
  // fire_group) us.
  double top_deg, step_deg, fire_step_us;
  std::size_t fire_group;
};

const XtCapture kXt16{"pandar_xt16.pcap", 1626, 165138, Model::pandar_xt16,
                      "calibration/pandar_xt16_angles.csv", "calibration/pandar_xt16_firetimes.csv",
                      568, 8, 16, 0.004, 0x39, 15.0, 2.0, 3.024, 16};
const XtCapture kXt32{"pandar_xt32.pcap", 2000, 486606, Model::pandar_xt32,
                      "calibration/pandar_xt32_angles.csv", "calibration/pandar_xt32_firetimes.csv",
                      1080, 8, 32, 0.004, 0x39, 15.0, 1.0, 1.512, 32};
const XtCapture kXt32m2x{"pandar_xt32m2x.pcap", 1815, 223372, Model::pandar_xt32m2x,
                         "calibration/pandar_xt32m2x_angles.csv", "calibration/pandar_xt32m2x_firetimes.csv",
                         820, 6, 32, 0.005, 0x3C, 19.5, 1.3, 2.888, 16};

void PrintTo(const XtCapture& c, std::ostream* os) { *os << hesai::model_name(c.model); }

std::size_t block_bytes(const XtCapture& c) { return 2 + 4 * c.channels; }
std::size_t tail_at(const XtCapture& c) { return 12 + c.blocks * block_bytes(c); }

std::vector<std::uint8_t> file_bytes(const std::string& name) { return read_file(data_path(name)); }

// t0 from the tail: date-time at +13 (year - 1900), timestamp (us) at +19.
std::int64_t packet_time_ns(const XtCapture& c, const std::vector<std::uint8_t>& p) {
  const std::uint8_t* d = &p[tail_at(c) + 13];
  const std::int64_t s = timegm_utc(1900 + d[0], d[1], d[2], d[3], d[4], d[5]);
  return s * 1000000000LL + static_cast<std::int64_t>(hesai::load_le32(&p[tail_at(c) + 19])) * 1000;
}

ReferenceCalibration design_reference(const XtCapture& c) {
  ReferenceCalibration ref;
  for (std::size_t i = 0; i < c.channels; ++i) {
    ref.elevation.push_back(c.top_deg - c.step_deg * static_cast<double>(i));
    ref.azimuth.push_back(0);
    ref.fire1.push_back(6 + c.fire_step_us * static_cast<double>(i % c.fire_group));
  }
  ref.fire2 = ref.fire1;
  return ref;
}

class Xt : public ::testing::TestWithParam<XtCapture> {};

TEST_P(Xt, CountsFromRawBytes) {
  const XtCapture& c = GetParam();
  const auto packets = pcap_payloads(c.capture);
  ASSERT_EQ(packets.size(), c.packets);
  Decoder dec(c.model);
  PacketPoints pts;
  PacketInfo info;
  std::size_t raw = 0, decoded = 0;
  for (const auto& p : packets) {
    ASSERT_EQ(p.size(), c.payload);
    for (std::size_t b = 0; b < c.blocks; ++b)
      for (std::size_t ch = 0; ch < c.channels; ++ch)
        raw += hesai::load_le16(&p[12 + b * block_bytes(c) + 2 + ch * 4]) != 0;
    ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
    decoded += pts.count;
    EXPECT_EQ(info.model, c.model);
    EXPECT_EQ(info.return_mode, c.return_mode);
    EXPECT_EQ(info.returns, 2);  // both modes are dual
    EXPECT_EQ(info.dis_unit_mm, std::lround(c.unit_m * 1000));
    EXPECT_GE(info.motor_rpm, 590);
    EXPECT_LE(info.motor_rpm, 610);
  }
  EXPECT_EQ(decoded, raw);
  EXPECT_EQ(raw, c.points);
}

// Every point against the double-precision reference: r = distance x dis unit, azimuth = block
// azimuth + offset + firing time x spin rate, elevation from the file; time = t0 - 50 us x the
// firings after the block + the channel's firing time.
// Counter-clockwise: every block azimuth mirrored (a -> 36000 - a), and the firing-time
// correction subtracted (the coordinate system stays clockwise, see hesai::Rotation).
void expect_every_point_matches(const XtCapture& c, const ReferenceCalibration& ref, Decoder& dec,
                                hesai::Rotation rotation = hesai::Rotation::clockwise) {
  const bool ccw = rotation == hesai::Rotation::counterclockwise;
  auto packets = pcap_payloads(c.capture);
  ASSERT_EQ(packets.size(), c.packets);
  if (ccw)
    for (auto& p : packets)
      for (std::size_t b = 0; b < c.blocks; ++b) {
        std::uint8_t* a = &p[12 + b * block_bytes(c)];
        hesai::store_le16(a, static_cast<std::uint16_t>((36000 - hesai::load_le16(a)) % 36000));
      }
  dec.set_rotation(rotation);
  const double turn = ccw ? -1.0 : 1.0;
  PacketPoints pts;
  PacketInfo info;
  const double kDeg = M_PI / 180;
  std::size_t checked = 0;
  for (const auto& p : packets) {
    ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
    const std::int64_t t0 = packet_time_ns(c, p);
    ASSERT_EQ(info.time_ns, t0);
    const double rpm = hesai::load_le16(&p[tail_at(c) + 11]);
    std::size_t k = 0;
    for (std::size_t b = 0; b < c.blocks; ++b) {
      const std::uint8_t* blk = &p[12 + b * block_bytes(c)];
      const double block_az = hesai::load_le16(blk) / 100.0;
      for (std::size_t ch = 0; ch < c.channels; ++ch) {
        const std::uint8_t* q = blk + 2 + ch * 4;
        const std::uint16_t raw = hesai::load_le16(q);
        if (raw == 0) continue;
        const double r = raw * c.unit_m;
        const double az = block_az + ref.azimuth[ch] + turn * ref.fire1[ch] * rpm * 360.0 / 60e6;
        const double e = ref.elevation[ch] * kDeg;
        const double x = r * std::cos(e) * std::sin(az * kDeg);
        const double y = r * std::cos(e) * std::cos(az * kDeg);
        const double z = r * std::sin(e);
        const auto firings_after = static_cast<std::int64_t>((c.blocks - 1 - b) / 2);
        const std::int64_t t = t0 - 50000 * firings_after + std::llround(ref.fire1[ch] * 1000);
        ASSERT_LT(k, pts.count);
        const hesai::Point& o = pts.points[k++];
        ASSERT_EQ(o.channel, ch + 1);
        ASSERT_EQ(o.block, b);
        ASSERT_EQ(o.return_index, b % 2);
        ASSERT_EQ(o.intensity, q[2]);
        ASSERT_EQ(o.confidence, q[3]);
        ASSERT_EQ(o.time_ns, t);
        ASSERT_NEAR(o.distance_m, r, 1e-4);
        ASSERT_LT(std::max({std::fabs(o.x - x), std::fabs(o.y - y), std::fabs(o.z - z)}), 1e-3) << "point " << k;
        double daz = std::fabs(o.azimuth_deg - std::fmod(az + 720.0, 360.0));
        if (daz > 180) daz = 360 - daz;
        ASSERT_LT(daz, 1e-3);
        ASSERT_NEAR(o.elevation_deg, ref.elevation[ch], 1e-5);
        ++checked;
      }
    }
    ASSERT_EQ(k, pts.count);
  }
  EXPECT_EQ(checked, c.points);
}

TEST_P(Xt, EveryPointMatchesDoubleReferenceWithUnitFiles) {
  const XtCapture& c = GetParam();
  Decoder dec(c.model);
  hesai::AngleCorrection a;
  hesai::FiretimeCorrection f;
  const auto angles = file_bytes(c.angles);
  const auto firetimes = file_bytes(c.firetimes);
  ASSERT_EQ(hesai::parse_angle_csv(view(angles), c.channels, a).error, Error::ok);
  ASSERT_EQ(hesai::parse_firetime_csv(view(firetimes), c.channels, f).error, Error::ok);
  ASSERT_EQ(dec.set_angles(a), Error::ok);
  ASSERT_EQ(dec.set_firetimes(f), Error::ok);
  expect_every_point_matches(c, read_reference_calibration(c.angles, c.firetimes, c.channels), dec);
}

// Without files the decoder uses the design tables; the vendor's firing-time file equals them.
TEST_P(Xt, EveryPointMatchesDoubleReferenceWithDesignTables) {
  const XtCapture& c = GetParam();
  const ReferenceCalibration design = design_reference(c);
  const ReferenceCalibration vendor = read_reference_calibration(c.angles, c.firetimes, c.channels);
  for (std::size_t i = 0; i < c.channels; ++i) EXPECT_NEAR(vendor.fire1[i], design.fire1[i], 1e-9) << i + 1;
  Decoder dec(c.model);
  expect_every_point_matches(c, design, dec);
}

TEST_P(Xt, CounterClockwiseEveryPointMatchesDoubleReference) {
  const XtCapture& c = GetParam();
  Decoder dec(c.model);
  expect_every_point_matches(c, design_reference(c), dec, hesai::Rotation::counterclockwise);
}

// One frame per rotation: the block azimuths wrap 4 times in each capture (counted here), so the
// stream is a partial turn, 3 whole turns and a partial turn: 5 frames, 3 of them cut at both ends.
TEST_P(Xt, OneFramePerRotation) {
  const XtCapture& c = GetParam();
  const auto packets = pcap_payloads(c.capture);
  std::size_t wraps = 0;
  std::uint16_t last = 0;
  bool any = false;
  for (const auto& p : packets)
    for (std::size_t b = 0; b < c.blocks; ++b) {
      const std::uint16_t a = hesai::load_le16(&p[12 + b * block_bytes(c)]);
      wraps += any && a < last;
      last = a;
      any = true;
    }
  ASSERT_EQ(wraps, 4u);
  Decoder dec(c.model);
  hesai::FrameAssembler frames;
  PacketPoints pts;
  PacketInfo info;
  hesai::SequenceTracker sequence;  // the XT32M2X gaps: up to 413 packets, 223 degrees, lost at once
  std::vector<hesai::FrameInfo> closed;
  std::uint64_t index = 0;
  for (const auto& p : packets) {
    ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
    ASSERT_EQ(frames.set_beam_spread(dec.beam_spread()), Error::ok);
    frames.begin_packet(index++, sequence.observe(info.sequence));
    for (std::size_t b = 0; b < info.blocks; ++b) {
      frames.block(info.block_azimuth[b]);
      for (const hesai::Point& q : pts)
        if (q.block == b) (void)frames.point(q.azimuth_deg);
    }
    for (hesai::FrameInfo f; frames.pop_closed(f);) closed.push_back(f);
  }
  frames.finish();
  for (hesai::FrameInfo f; frames.pop_closed(f);) closed.push_back(f);
  ASSERT_EQ(closed.size(), wraps + 1);
  std::size_t whole = 0;
  for (const auto& f : closed) whole += f.starts_at_cut && f.ends_at_cut;
  EXPECT_EQ(whole, wraps - 1);
}

INSTANTIATE_TEST_SUITE_P(Captures, Xt, ::testing::Values(kXt16, kXt32, kXt32m2x),
                         [](const auto& i) { return std::string(hesai::model_name(i.param.model)); });

// ---- Header fields of the first packets, with the bytes they were read from ----

TEST(XtHeader, Xt16FirstPacket) {
  const auto p = pcap_payloads("pandar_xt16.pcap").at(0);
  // ee ff 06 01 00 00 | 10 08 01 04 02 01: protocol 6.1, 16 lasers, 8 blocks, echo count 1,
  // dis unit 4 mm, echo num 2, flags 0x01 (UDP sequence).
  EXPECT_EQ(p[2], 0x06); EXPECT_EQ(p[3], 0x01); EXPECT_EQ(p[6], 0x10); EXPECT_EQ(p[7], 0x08);
  EXPECT_EQ(p[9], 0x04); EXPECT_EQ(p[10], 0x02); EXPECT_EQ(p[11], 0x01);
  Decoder dec(Model::pandar_xt16);
  PacketInfo info;
  ASSERT_EQ(dec.validate(view(p), info), Error::ok);
  EXPECT_EQ(info.blocks, 8);
  EXPECT_EQ(info.dis_unit_mm, 4);
  EXPECT_EQ(info.flags, 0x01);
  // Block 1 azimuth: 54 69 -> 0x6954 = 26964 = 269.64 degrees; block 2 the same (dual).
  EXPECT_EQ(info.block_azimuth[0], 26964);
  EXPECT_EQ(info.block_azimuth[1], 26964);
  // Tail at 540: 00 00 86 ec 07 83 83 00 01 | 00 | 39 | 58 02 | 77 07 19 04 0c 1d | 65 31 04 00 |
  //              42 | ce 56 f7 00
  EXPECT_EQ(info.high_temperature, 0);  // shutdown flag
  EXPECT_EQ(info.return_mode, 0x39);    // last + strongest
  EXPECT_EQ(info.motor_rpm, 0x0258);    // 600 rpm
  EXPECT_EQ(info.timestamp_us, 0x00043165u);  // 274789 us
  EXPECT_EQ(info.factory_info, 0x42);
  EXPECT_TRUE(info.has_sequence);
  EXPECT_EQ(info.sequence, 0x00F756CEu);  // 16209614
  // 0x77 = 119 -> 2019-07-25 04:12:29; calendar.timegm((2019,7,25,4,12,29)) = 1564027949.
  EXPECT_EQ(info.date_time.year, 2019);
  EXPECT_EQ(info.date_time.month, 7);
  EXPECT_EQ(info.date_time.day, 25);
  EXPECT_EQ(info.date_time.hour, 4);
  EXPECT_EQ(info.date_time.minute, 12);
  EXPECT_EQ(info.date_time.second, 29);
  EXPECT_EQ(info.time_ns, 1564027949LL * 1000000000 + 274789000LL);
}

TEST(XtHeader, Xt32FirstPacket) {
  const auto p = pcap_payloads("pandar_xt32.pcap").at(0);
  // ee ff 06 01 00 00 | 20 08 01 04 02 01: 32 lasers, 8 blocks, dis unit 4 mm.
  EXPECT_EQ(p[6], 0x20); EXPECT_EQ(p[7], 0x08); EXPECT_EQ(p[9], 0x04);
  Decoder dec(Model::pandar_xt32);
  PacketInfo info;
  ASSERT_EQ(dec.validate(view(p), info), Error::ok);
  EXPECT_EQ(info.block_azimuth[0], 0x006C);  // 6c 00 = 1.08 degrees
  // Tail at 1052: 00 00 86 f1 07 83 01 00 01 | 00 | 39 | 57 02 | 77 07 19 03 13 1d | 9d 72 09 00 |
  //               42 | 6c 9a 04 00
  EXPECT_EQ(info.return_mode, 0x39);
  EXPECT_EQ(info.motor_rpm, 0x0257);           // 599 rpm
  EXPECT_EQ(info.timestamp_us, 0x0009729Du);   // 619165 us
  EXPECT_EQ(info.sequence, 0x00049A6Cu);       // 301676
  // 2019-07-25 03:19:29; calendar.timegm = 1564024769.
  EXPECT_EQ(info.time_ns, 1564024769LL * 1000000000 + 619165000LL);
}

TEST(XtHeader, Xt32m2xFirstPacket) {
  const auto p = pcap_payloads("pandar_xt32m2x.pcap").at(0);
  // ee ff 06 01 00 00 | 20 06 01 05 03 01: 32 lasers, 6 blocks, dis unit 5 mm, echo num 3.
  EXPECT_EQ(p[6], 0x20); EXPECT_EQ(p[7], 0x06); EXPECT_EQ(p[9], 0x05); EXPECT_EQ(p[10], 0x03);
  Decoder dec(Model::pandar_xt32m2x);
  PacketInfo info;
  ASSERT_EQ(dec.validate(view(p), info), Error::ok);
  EXPECT_EQ(info.dis_unit_mm, 5);
  // Tail at 792: 00 00 86 e7 07 83 02 00 01 | 00 | 3c | 57 02 | 77 07 19 06 2e 10 | b6 f8 0c 00 |
  //              42 | a5 e2 d2 04
  // Return mode 0x3C (first + strongest, dual) although the header's echo num says 3: two
  // returns per firing, and the block azimuths pair up (48 00, 48 00, 5a 00, ...).
  EXPECT_EQ(info.return_mode, 0x3C);
  EXPECT_EQ(info.returns, 2);
  EXPECT_EQ(info.block_azimuth[0], 72);
  EXPECT_EQ(info.block_azimuth[1], 72);
  EXPECT_EQ(info.block_azimuth[2], 90);
  EXPECT_EQ(info.motor_rpm, 599);
  EXPECT_EQ(info.timestamp_us, 0x000CF8B6u);  // 850102 us
  EXPECT_EQ(info.sequence, 0x04D2E2A5u);      // 80929445
  // 2019-07-25 06:46:16; calendar.timegm = 1564037176.
  EXPECT_EQ(info.time_ns, 1564037176LL * 1000000000 + 850102000LL);
}

// ---- Point times, worked by hand for the first packet of each capture ----

// The point of (block, channel), both 1-based; fails when absent.
const hesai::Point& point_at(const PacketPoints& pts, std::size_t block, std::size_t channel) {
  for (const hesai::Point& q : pts)
    if (q.block == block - 1 && q.channel == channel) return q;
  ADD_FAILURE() << "no point for block " << block << " channel " << channel;
  static const hesai::Point none{};
  return none;
}

PacketPoints decode_first(const char* capture, Model model) {
  const auto p = pcap_payloads(capture).at(0);
  Decoder dec(model);
  PacketInfo info;
  PacketPoints pts;
  EXPECT_EQ(dec.decode(view(p), info, pts), Error::ok);
  return pts;
}

TEST(XtTimes, Xt16HandWorked) {
  // t0 = 1564027949 s + 274789 us. Dual return, 8 blocks = 4 firings 50 us apart, the last at t0:
  // blocks 1-2 start at t0 - 150 us. Channel 1 fires 6 us into the firing, channel 2 9.024 us:
  // block 1 ch 1 = t0 - 144 us; block 2 ch 2 = t0 - 140.976 us; block 8 ch 16 = t0 + 51.36 us.
  const PacketPoints pts = decode_first("pandar_xt16.pcap", Model::pandar_xt16);
  const std::int64_t t0 = 1564027949274789000LL;
  EXPECT_EQ(point_at(pts, 1, 1).time_ns, t0 - 144000);
  EXPECT_EQ(point_at(pts, 2, 2).time_ns, t0 - 140976);
  EXPECT_EQ(point_at(pts, 8, 16).time_ns, t0 + 51360);
}

TEST(XtTimes, Xt32HandWorked) {
  // t0 = 1564024769 s + 619165 us; blocks 1-2 at t0 - 150 us, 7-8 at t0. Channel 32 fires
  // 6 + 31 x 1.512 = 52.872 us in: block 1 ch 1 = t0 - 144 us, block 8 ch 32 = t0 + 52.872 us,
  // block 8 ch 1 = t0 + 6 us.
  const PacketPoints pts = decode_first("pandar_xt32.pcap", Model::pandar_xt32);
  const std::int64_t t0 = 1564024769619165000LL;
  EXPECT_EQ(point_at(pts, 1, 1).time_ns, t0 - 144000);
  EXPECT_EQ(point_at(pts, 8, 32).time_ns, t0 + 52872);
  EXPECT_EQ(point_at(pts, 8, 1).time_ns, t0 + 6000);
}

TEST(XtTimes, Xt32m2xHandWorked) {
  // t0 = 1564037176 s + 850102 us. Dual return, 6 blocks = 3 firings: blocks 1-2 at t0 - 100 us.
  // Channels 1 and 17 fire together, 6 us in: block 1 ch 1 and ch 17 = t0 - 94 us; channel 16
  // fires 6 + 15 x 2.888 = 49.32 us in: block 6 ch 16 = t0 + 49.32 us.
  const PacketPoints pts = decode_first("pandar_xt32m2x.pcap", Model::pandar_xt32m2x);
  const std::int64_t t0 = 1564037176850102000LL;
  EXPECT_EQ(point_at(pts, 1, 1).time_ns, t0 - 94000);
  EXPECT_EQ(point_at(pts, 1, 17).time_ns, t0 - 94000);
  EXPECT_EQ(point_at(pts, 6, 16).time_ns, t0 + 49320);
  // Distance unit 5 mm: block 1 channel 1's bytes 2c 02 = 556 -> 2.780 m.
  EXPECT_NEAR(point_at(pts, 1, 1).distance_m, 2.780, 1e-5);
}

// ---- Sequence: the XT32M2X capture skips three runs of numbers ----

TEST(XtSequence, Xt32m2xCaptureLoses852Packets) {
  const auto packets = pcap_payloads("pandar_xt32m2x.pcap");
  // From the raw tails (UDP sequence at tail + 24): the gaps 80930204 -> 80930618,
  // 80930870 -> 80930915 and 80931537 -> 80931933 skip 413 + 44 + 395 = 852 numbers;
  // first 80929445, last 80932111: 2667 numbers, 1815 packets, 852 missing.
  std::size_t gaps = 0;
  std::uint64_t skipped = 0;
  for (std::size_t i = 1; i < packets.size(); ++i) {
    const std::uint32_t a = hesai::load_le32(&packets[i - 1][792 + 24]);
    const std::uint32_t b = hesai::load_le32(&packets[i][792 + 24]);
    if (b != a + 1) {
      ++gaps;
      skipped += b - a - 1;
    }
  }
  EXPECT_EQ(gaps, 3u);
  EXPECT_EQ(skipped, 852u);
  Decoder dec(Model::pandar_xt32m2x);
  hesai::SequenceTracker seq;
  PacketInfo info;
  for (const auto& p : packets) {
    ASSERT_EQ(dec.validate(view(p), info), Error::ok);
    ASSERT_TRUE(info.has_sequence);
    (void)seq.observe(info.sequence);
  }
  EXPECT_EQ(seq.counts().lost, 852u);
  EXPECT_EQ(seq.counts().packets, 1815u);
}

// ---- Rules of the layout, on packets changed from the captures ----

std::vector<std::uint8_t> xt32_packet() { return pcap_payloads("pandar_xt32.pcap").at(0); }
constexpr std::size_t kXt32Tail = 1052;

Error validate(Model m, const std::vector<std::uint8_t>& p, PacketInfo& info) {
  Decoder dec(m);
  return dec.validate(view(p), info);
}

TEST(XtRules, IdentifyByLaserAndBlockNumbersAndLength) {
  Model m = Model::unknown;
  hesai::PacketKind kind{};
  for (const auto& [file, model] : {std::pair{"pandar_xt16.pcap", Model::pandar_xt16},
                                    std::pair{"pandar_xt32.pcap", Model::pandar_xt32},
                                    std::pair{"pandar_xt32m2x.pcap", Model::pandar_xt32m2x}}) {
    auto p = pcap_payloads(file).at(0);
    ASSERT_EQ(hesai::identify(view(p), m, kind), Error::ok);
    EXPECT_EQ(m, model);
    // One length per model: the tail always holds the UDP sequence (no shorter variant).
    p.pop_back();
    EXPECT_EQ(hesai::identify(view(p), m, kind), Error::bad_length) << file;
    p.push_back(0);
    p.push_back(0);
    EXPECT_EQ(hesai::identify(view(p), m, kind), Error::bad_length) << file;
  }
  auto p = xt32_packet();
  p[7] = 6;  // 32 lasers x 6 blocks is the XT32M2X, 820 bytes: this 1080-byte packet is not
  EXPECT_EQ(hesai::identify(view(p), m, kind), Error::bad_length);
  p[7] = 4;  // no 6.1 model sends 4 blocks
  EXPECT_EQ(hesai::identify(view(p), m, kind), Error::unsupported_model);
  p[7] = 8;
  p[6] = 64;
  EXPECT_EQ(hesai::identify(view(p), m, kind), Error::unsupported_model);
  p[6] = 32;
  p[3] = 0x02;  // protocol 6.2: not the XT's
  EXPECT_EQ(hesai::identify(view(p), m, kind), Error::unsupported_version);
  // The wrong decoder for the model.
  PacketInfo info;
  EXPECT_EQ(validate(Model::pandar_xt16, xt32_packet(), info), Error::model_mismatch);
}

TEST(XtRules, ReturnModesOfTheFamily) {
  PacketInfo info;
  // Single: 0x33 first, 0x37 strongest, 0x38 last; dual: 0x39, 0x3B, 0x3C (nebula, XT models).
  for (const int mode : {0x33, 0x37, 0x38, 0x39, 0x3B, 0x3C}) {
    auto p = xt32_packet();
    p[kXt32Tail + 10] = static_cast<std::uint8_t>(mode);
    ASSERT_EQ(validate(Model::pandar_xt32, p, info), Error::ok) << mode;
    EXPECT_EQ(info.returns, mode >= 0x39 ? 2 : 1);
  }
  // QT128-only modes, unknown bytes, and triple return in 8 blocks (not whole firings).
  for (const int mode : {0x00, 0x34, 0x3A, 0x3E, 0x3F, 0x3D}) {
    auto p = xt32_packet();
    p[kXt32Tail + 10] = static_cast<std::uint8_t>(mode);
    EXPECT_EQ(validate(Model::pandar_xt32, p, info), Error::bad_return_mode) << mode;
  }
}

TEST(XtRules, SingleReturnBlocksAreConsecutiveFirings) {
  // Strongest return: 8 firings, block b (1-based) at t0 - 50 x (8 - b) us; return index 0.
  auto p = xt32_packet();
  p[kXt32Tail + 10] = 0x37;
  Decoder dec(Model::pandar_xt32);
  PacketInfo info;
  PacketPoints pts;
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  const std::int64_t t0 = 1564024769619165000LL;
  EXPECT_EQ(point_at(pts, 1, 1).time_ns, t0 - 350000 + 6000);
  EXPECT_EQ(point_at(pts, 2, 2).time_ns, t0 - 300000 + 7512);
  for (const hesai::Point& q : pts) EXPECT_EQ(q.return_index, 0);
}

TEST(XtRules, TripleReturnOnTheXt32m2x) {
  // 0x3D first + last + strongest: 6 blocks = 2 firings of 3 blocks at one azimuth each; blocks
  // 1-3 at t0 - 50 us, 4-6 at t0; return index 0, 1, 2 within a firing.
  auto p = pcap_payloads("pandar_xt32m2x.pcap").at(0);
  const std::size_t tail = 792;
  p[tail + 10] = 0x3D;
  for (std::size_t b = 0; b < 6; ++b) hesai::store_le16(&p[12 + b * 130], b < 3 ? 1000 : 1018);
  Decoder dec(Model::pandar_xt32m2x);
  PacketInfo info;
  PacketPoints pts;
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  EXPECT_EQ(info.returns, 3);
  const std::int64_t t0 = 1564037176850102000LL;
  EXPECT_EQ(point_at(pts, 1, 1).time_ns, t0 - 50000 + 6000);
  EXPECT_EQ(point_at(pts, 3, 1).time_ns, t0 - 50000 + 6000);
  EXPECT_EQ(point_at(pts, 4, 1).time_ns, t0 + 6000);
  EXPECT_EQ(point_at(pts, 1, 1).return_index, 0);
  EXPECT_EQ(point_at(pts, 2, 1).return_index, 1);
  EXPECT_EQ(point_at(pts, 3, 1).return_index, 2);
  EXPECT_EQ(point_at(pts, 4, 1).return_index, 0);
  EXPECT_STREQ(hesai::return_mode_name(0x3D), "first_last_strongest");
  // The three blocks of a firing share one azimuth.
  hesai::store_le16(&p[12 + 2 * 130], 1001);
  EXPECT_EQ(dec.decode(view(p), info, pts), Error::dual_block_mismatch);
}

TEST(XtRules, FieldChecks) {
  PacketInfo info;
  auto p = xt32_packet();
  p[9] = 0;  // dis unit
  EXPECT_EQ(validate(Model::pandar_xt32, p, info), Error::bad_header);
  p = xt32_packet();
  hesai::store_le16(&p[kXt32Tail + 11], 1501);  // motor speed beyond any setting
  EXPECT_EQ(validate(Model::pandar_xt32, p, info), Error::bad_motor_speed);
  p = xt32_packet();
  hesai::store_le16(&p[12 + 130 * 3], 36000);  // block 4 azimuth
  EXPECT_EQ(validate(Model::pandar_xt32, p, info), Error::bad_azimuth);
  p = xt32_packet();
  hesai::store_le16(&p[12 + 130 * 3], 127);  // block 4 differs from block 3 (dual pair)
  EXPECT_EQ(validate(Model::pandar_xt32, p, info), Error::dual_block_mismatch);
  p = xt32_packet();
  p[kXt32Tail + 14] = 13;  // month
  EXPECT_EQ(validate(Model::pandar_xt32, p, info), Error::bad_date_time);
  p = xt32_packet();
  hesai::store_le32(&p[kXt32Tail + 19], 1000000);  // us within the second
  EXPECT_EQ(validate(Model::pandar_xt32, p, info), Error::bad_timestamp);
  // Flags bit 0 clear: the sequence field is not in use.
  p = xt32_packet();
  p[11] = 0;
  ASSERT_EQ(validate(Model::pandar_xt32, p, info), Error::ok);
  EXPECT_FALSE(info.has_sequence);
  // Shutdown flag (tail + 9) reported.
  p = xt32_packet();
  p[kXt32Tail + 9] = 1;
  ASSERT_EQ(validate(Model::pandar_xt32, p, info), Error::ok);
  EXPECT_EQ(info.high_temperature, 1);
  // Only bit 0 is the flag (SDK udp_protocol_v6_1.h, HsLidarXTV1Tail::kShutdown = 0x01).
  p[kXt32Tail + 9] = 0xFE;
  ASSERT_EQ(validate(Model::pandar_xt32, p, info), Error::ok);
  EXPECT_EQ(info.high_temperature, 0);
}

TEST(XtRules, YearZeroMeansUnixSecondsBigEndian) {
  // SDK GetMicroLidarTimeU64: year byte 0 -> bytes 2..5 are Unix seconds, big-endian.
  auto p = xt32_packet();
  const std::size_t dt = kXt32Tail + 13;
  p[dt] = 0;
  p[dt + 1] = 0;
  // 1700000000 = 0x6553F100.
  p[dt + 2] = 0x65; p[dt + 3] = 0x53; p[dt + 4] = 0xF1; p[dt + 5] = 0x00;
  PacketInfo info;
  ASSERT_EQ(validate(Model::pandar_xt32, p, info), Error::ok);
  EXPECT_EQ(info.time_ns, 1700000000LL * 1000000000 + 619165000LL);
}

TEST(XtRules, DesignTablesOfTheDecoder) {
  // A decoder without files reports the design elevations (xt_tables.h) in its points.
  const PacketPoints pts = decode_first("pandar_xt32m2x.pcap", Model::pandar_xt32m2x);
  EXPECT_NEAR(point_at(pts, 1, 1).elevation_deg, 19.5, 1e-6);
  EXPECT_NEAR(point_at(pts, 1, 17).elevation_deg, 19.5 - 1.3 * 16, 1e-5);
  EXPECT_EQ(hesai::max_points(Model::pandar_xt16), 128u);
  EXPECT_EQ(hesai::max_points(Model::pandar_xt32), 256u);
  EXPECT_EQ(hesai::max_points(Model::pandar_xt32m2x), 192u);
}

}  // namespace
