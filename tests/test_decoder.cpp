// Decoder behaviour on synthetic packets: the manuals' worked examples, identification, every
// rejection path, signatures, and the 1 mm accuracy bound at 200 m.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "hesai/decoder.h"
#include "hesai/hkdf.h"
#include "hesai/stats.h"
#include "packet_builder.h"
#include "pandar64_manual.h"
#include "test_support.h"

using namespace hesai;
using namespace hesai_test;

namespace {

const Point* find_point(const PacketPoints& pts, int block, int channel) {
  for (const Point& p : pts)
    if (p.block == block - 1 && p.channel == channel) return &p;
  return nullptr;
}

std::int64_t ns_of(const Stamp& s) {
  return timegm_utc(s.year, s.month, s.day, s.hour, s.minute, s.second) * 1000000000LL + s.us * 1000LL;
}

// ---- Hand-worked examples from the manuals ----

// Pandar64 manual 3.1.4 and App. B: Channel 5 in Block 3, single return. Design angles of
// Channel 5 (App. A): elevation 3.04, azimuth offset -1.042; firing offset -17.964 us (B.4).
// T(3) = t0 - 42.58 - 55.56 x (6 - 3) = t0 - 209.26 us; t(3,5) = T(3) - 17.964 = t0 - 227.224 us.
// At 600 rpm the spin is 0.0036 deg/us: firing correction -17.964 x 0.0036 = -0.0646704 deg.
TEST(ManualExample, Pandar64Channel5Block3) {
  const Stamp s;
  auto p = pandar64_packet(0x37, s, 600);
  pandar64_azimuth(p, 3, 10000);        // 100.00 degrees
  pandar64_point(p, 3, 5, 2500, 77);    // 2500 x 4 mm = 10 m
  Decoder dec(Model::pandar64);
  PacketInfo info;
  PacketPoints pts;
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  ASSERT_EQ(pts.count, 1u);
  const Point& q = pts.points[0];
  EXPECT_EQ(q.time_ns, ns_of(s) - 227224);
  EXPECT_NEAR(q.azimuth_deg, 100.0 - 1.042 - 0.0646704, 1e-4);
  EXPECT_NEAR(q.elevation_deg, 3.04, 1e-6);
  EXPECT_NEAR(q.distance_m, 10.0, 1e-6);
  EXPECT_EQ(q.intensity, 77);
  // x = r cos(e) sin(a), y = r cos(e) cos(a), z = r sin(e) with a = 98.8933296, e = 3.04:
  // cos(3.04 deg) = 0.99859275, sin(3.04 deg) = 0.05303312, sin(98.8933296 deg) = 0.98797787,
  // cos(98.8933296 deg) = -0.15459537 (evaluated separately with a calculator).
  EXPECT_NEAR(q.x, 10 * 0.99859275 * 0.98797787, 1e-4);
  EXPECT_NEAR(q.y, 10 * 0.99859275 * -0.15459537, 1e-4);
  EXPECT_NEAR(q.z, 10 * 0.05303312, 1e-4);

  // Firing-time correction off: the azimuth is block + offset only.
  dec.set_firetime_correction(false);
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  EXPECT_NEAR(pts.points[0].azimuth_deg, 100.0 - 1.042, 1e-4);
  EXPECT_EQ(pts.points[0].time_ns, ns_of(s) - 227224);  // time does not depend on the switch
}

// The decoder keeps per-channel values for the last spin rate: a new rate, new angles and new
// firing times must each take effect on the next packet. Channel 5 of the Pandar64 as above
// (offset -1.042 deg, firing -17.964 us); 1200 rpm spins 0.0072 deg/us: -0.1293408 deg.
TEST(ManualExample, Pandar64SpinRateAndCalibrationChangesApply) {
  const Stamp s;
  Decoder dec(Model::pandar64);
  PacketInfo info;
  PacketPoints pts;
  auto decode_one = [&](std::uint16_t rpm, std::uint16_t block_cdeg) {
    auto p = pandar64_packet(0x37, s, rpm);
    pandar64_azimuth(p, 3, block_cdeg);
    pandar64_point(p, 3, 5, 2500, 77);
    EXPECT_EQ(dec.decode(view(p), info, pts), Error::ok);
    EXPECT_EQ(pts.count, 1u);
    return pts.points[0];
  };
  EXPECT_NEAR(decode_one(600, 10000).azimuth_deg, 100.0 - 1.042 - 0.0646704, 1e-4);
  EXPECT_NEAR(decode_one(1200, 10000).azimuth_deg, 100.0 - 1.042 - 0.1293408, 1e-4);
  EXPECT_NEAR(decode_one(600, 10000).azimuth_deg, 100.0 - 1.042 - 0.0646704, 1e-4);
  // Across 0: block 0.50 deg -> 0.5 - 1.042 - 0.0646704 + 360.
  EXPECT_NEAR(decode_one(600, 50).azimuth_deg, 360.0 + 0.5 - 1.042 - 0.0646704, 1e-4);

  // Channel 5 moved to elevation 0 and offset +2 deg: z = 0, a = 100 + 2 - 0.0646704.
  AngleCorrection angles;
  angles.channels = 64;
  angles.azimuth_deg[4] = 2.0;
  ASSERT_EQ(dec.set_angles(angles), Error::ok);
  Point q = decode_one(600, 10000);
  EXPECT_NEAR(q.azimuth_deg, 101.9353296, 1e-4);
  EXPECT_NEAR(q.z, 0.0, 1e-6);
  EXPECT_NEAR(q.x, 10 * std::sin(101.9353296 * M_PI / 180), 1e-4);
  // Across 360: block 359.00 deg + 2 - 0.0646704 -> 0.9353296.
  EXPECT_NEAR(decode_one(600, 35900).azimuth_deg, 0.9353296, 1e-4);

  // Firing times of 0: no correction, and the point time is the block's end time t0 - 209.26 us.
  FiretimeCorrection fire;
  fire.channels = 64;
  for (std::size_t i = 0; i < 64; ++i) fire.fires[0][i] = true;
  ASSERT_EQ(dec.set_firetimes(fire), Error::ok);
  q = decode_one(600, 10000);
  EXPECT_NEAR(q.azimuth_deg, 102.0, 1e-4);
  EXPECT_EQ(q.time_ns, ns_of(s) - 209260);
}

// Counter-clockwise (QT128C2X manual Section 1.2, Pandar40 manual Section 4.2 item 6: the
// coordinate system stays clockwise): Channel 5 of Block 3 as above has turned back, not on, in its -17.964 us:
// a = 100 - 1.042 + 0.0646704. Switching the direction takes effect on the next packet, both ways.
TEST(ManualExample, Pandar64Channel5Block3CounterClockwise) {
  const Stamp s;
  auto p = pandar64_packet(0x37, s, 600);
  pandar64_azimuth(p, 3, 10000);
  pandar64_point(p, 3, 5, 2500, 77);
  Decoder dec(Model::pandar64);
  EXPECT_EQ(dec.rotation(), Rotation::clockwise);  // the manuals' default
  PacketInfo info;
  PacketPoints pts;
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  EXPECT_NEAR(pts.points[0].azimuth_deg, 100.0 - 1.042 - 0.0646704, 1e-4);
  dec.set_rotation(Rotation::counterclockwise);
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  const Point& q = pts.points[0];
  EXPECT_NEAR(q.azimuth_deg, 100.0 - 1.042 + 0.0646704, 1e-4);
  EXPECT_EQ(q.time_ns, ns_of(s) - 227224);  // the firing time is the same
  // sin(99.0226704 deg) = 0.98762637, cos(99.0226704 deg) = -0.15682525 (evaluated separately).
  EXPECT_NEAR(q.x, 10 * 0.99859275 * 0.98762637, 1e-4);
  EXPECT_NEAR(q.y, 10 * 0.99859275 * -0.15682525, 1e-4);
  dec.set_rotation(Rotation::clockwise);
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  EXPECT_NEAR(pts.points[0].azimuth_deg, 100.0 - 1.042 - 0.0646704, 1e-4);
}

// beam_spread(): the smallest and largest channel offset + firing-time correction, from the
// Pandar64 manual's Appendix A (azimuth offsets) and B.4 (firing offsets) as typed in
// tests/pandar64_manual.h, for each direction and spin rate, and without the correction.
// By hand, clockwise at 600 rpm (0.0036 deg/us): the least is Channel 40, -5.208 - 54.668 x 0.0036
// = -5.4048048; the greatest Channel 51, 5.208 - 3.62 x 0.0036 = 5.194968.
TEST(ManualExample, BeamSpreadFromTheTables) {
  const Stamp s;
  Decoder dec(Model::pandar64);
  EXPECT_EQ(dec.beam_spread().min_deg, 0.0f);  // nothing decoded yet
  PacketInfo info;
  PacketPoints pts;
  for (const Rotation r : {Rotation::clockwise, Rotation::counterclockwise}) {
    for (const int rpm : {600, 1200}) {
      dec.set_rotation(r);
      ASSERT_EQ(dec.decode(view(pandar64_packet(0x37, s, static_cast<std::uint16_t>(rpm))), info, pts), Error::ok);
      const double deg_per_us = (r == Rotation::clockwise ? 1 : -1) * rpm * 360.0 / 60e6;
      double lo = 360, hi = -360;
      for (std::size_t ch = 0; ch < 64; ++ch) {
        const double a = pandar64_manual::kAzimuthOffsetDeg[ch] + pandar64_manual::kFiringOffsetUs[ch] * deg_per_us;
        lo = std::min(lo, a);
        hi = std::max(hi, a);
      }
      EXPECT_NEAR(dec.beam_spread().min_deg, lo, 1e-4) << rpm;
      EXPECT_NEAR(dec.beam_spread().max_deg, hi, 1e-4) << rpm;
      if (r == Rotation::clockwise && rpm == 600) {
        EXPECT_NEAR(lo, -5.4048048, 1e-9);
        EXPECT_NEAR(hi, 5.194968, 1e-9);
      }
    }
  }
  dec.set_firetime_correction(false);
  ASSERT_EQ(dec.decode(view(pandar64_packet(0x37, s, 600)), info, pts), Error::ok);
  EXPECT_NEAR(dec.beam_spread().min_deg, -5.208, 1e-4);  // App. A: offsets from -5.208 to 5.208
  EXPECT_NEAR(dec.beam_spread().max_deg, 5.208, 1e-4);
  // An offset beyond half a turn is the same direction the short way round: 350 is -10.
  AngleCorrection angles;
  angles.channels = 64;
  angles.azimuth_deg[0] = 350.0;
  angles.azimuth_deg[1] = 3.0;
  ASSERT_EQ(dec.set_angles(angles), Error::ok);
  ASSERT_EQ(dec.decode(view(pandar64_packet(0x37, s, 600)), info, pts), Error::ok);
  EXPECT_NEAR(dec.beam_spread().min_deg, -10.0, 1e-4);
  EXPECT_NEAR(dec.beam_spread().max_deg, 3.0, 1e-4);
}

// Pandar64 App. B.3, dual return: blocks 5 and 6 end at t0 - 42.58 us, blocks 1 and 2 at
// t0 - 42.58 - 55.56 x 2 = t0 - 153.70 us. Channel 5 fires 17.964 us before its block ends.
TEST(ManualExample, Pandar64DualReturnBlockPairs) {
  const Stamp s;
  auto p = pandar64_packet(0x39, s);
  for (int b = 1; b <= 6; ++b) pandar64_point(p, b, 5, 1000, static_cast<std::uint8_t>(b));
  Decoder dec(Model::pandar64);
  PacketInfo info;
  PacketPoints pts;
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  ASSERT_EQ(pts.count, 6u);
  const std::int64_t t0 = ns_of(s);
  EXPECT_EQ(find_point(pts, 6, 5)->time_ns, t0 - 42580 - 17964);
  EXPECT_EQ(find_point(pts, 5, 5)->time_ns, t0 - 42580 - 17964);
  EXPECT_EQ(find_point(pts, 4, 5)->time_ns, t0 - 98140 - 17964);
  EXPECT_EQ(find_point(pts, 1, 5)->time_ns, t0 - 153700 - 17964);
  EXPECT_EQ(find_point(pts, 1, 5)->return_index, 0);  // odd block: last return
  EXPECT_EQ(find_point(pts, 2, 5)->return_index, 1);  // even block: strongest return
}

// Pandar40 manual App. II, dual return: Block 6 ends at t0 - 28.58 - 55.56 x 2 = t0 - 139.70 us,
// and "Laser ID 4's firing time: (t6 - 3.62) us", so t = t0 - 143.32 us.
TEST(ManualExample, Pandar40PBlock6Laser4Dual) {
  const Stamp s;
  auto p = pandar40_packet(true, 0x39, s, s.us);
  pandar40_point(p, 6, 4, 500, 9);
  Decoder dec(Model::pandar40p);
  PacketInfo info;
  PacketPoints pts;
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  ASSERT_EQ(pts.count, 1u);
  EXPECT_EQ(pts.points[0].time_ns, ns_of(s) - 143320);
  EXPECT_EQ(pts.points[0].return_index, 1);  // block 6 is even: strongest
}

// Pandar40 (no date in the tail): the timestamp counts us from the top of the hour; the date
// and hour come from the last GPS packet. Single return: Block 10 ends at t0 - 28.58 us.
TEST(ManualExample, Pandar40TimeFromGpsAndHourRollover) {
  const Stamp s;
  Decoder dec(Model::pandar40);
  PacketInfo info;
  PacketPoints pts;
  // 30 minutes 15.25 seconds into the hour.
  auto p = pandar40_packet(false, 0x37, s, (30 * 60 + 15) * 1000000u + 250000u);
  pandar40_point(p, 10, 4, 500, 9);
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  EXPECT_EQ(info.time_reference, TimeReference::hour_relative);  // no GPS packet yet
  EXPECT_EQ(info.time_ns, (30 * 60 + 15) * 1000000000LL + 250000000LL);

  GpsPacket gps;
  gps.time = DateTime{2024, 5, 17, 8, 30, 15};
  dec.update_gps(gps);
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  EXPECT_EQ(info.time_reference, TimeReference::utc);
  EXPECT_EQ(info.time_ns, ns_of(s));  // 2024-05-17 08:30:15.25
  EXPECT_EQ(pts.points[0].time_ns, ns_of(s) - 28580 - 3620);

  // GPS at 08:59:59; a packet 0.5 s after the top of the hour, before the next GPS packet.
  gps.time = DateTime{2024, 5, 17, 8, 59, 59};
  dec.update_gps(gps);
  auto late = pandar40_packet(false, 0x37, s, 500000u);
  ASSERT_EQ(dec.decode(view(late), info, pts), Error::ok);
  EXPECT_EQ(info.time_ns, timegm_utc(2024, 5, 17, 9, 0, 0) * 1000000000LL + 500000000LL);
}

// QT128 manual App. II: block 1 starts at t0 + 9 us, block 2 at t0 + 9 + 111.11 us (single
// return). The firetime table's first rows: "99, 0.6, 65, 0.6" and "65, 1.456, 99, 1.456":
// channel 99 fires at 0.6 us in sequence 1 and at 1.456 us in sequence 2.
TEST(ManualExample, Qt128BlockStartAndFiringSequences) {
  const Stamp s;
  auto p = qt128_packet(0x15, 0x37, /*mode_flag=*/1, s);  // sequence, functional safety, confidence bytes
  qt128_point(p, 1, 99, 1000, 10, 0x5A);
  qt128_point(p, 2, 99, 1000, 20);
  qt128_point(p, 2, 65, 1000, 30);
  qt128_seal(p);
  Decoder dec(Model::qt128c2x);
  PacketInfo info;
  PacketPoints pts;
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  ASSERT_EQ(pts.count, 3u);
  const std::int64_t t0 = ns_of(s);
  // Mode flag 1: block 1 uses sequence 1, block 2 sequence 2.
  EXPECT_EQ(find_point(pts, 1, 99)->time_ns, t0 + 9000 + 600);
  EXPECT_EQ(find_point(pts, 2, 99)->time_ns, t0 + 9000 + 111110 + 1456);
  EXPECT_EQ(find_point(pts, 2, 65)->time_ns, t0 + 9000 + 111110 + 600);
  EXPECT_EQ(find_point(pts, 1, 99)->confidence, 0x5A);

  // Mode flag 0: block 1 uses sequence 2. (Flags bit 4 clear: 3-byte units, no confidence byte.)
  auto q = qt128_packet(0x05, 0x37, 0, s);
  qt128_point(q, 1, 99, 1000, 10);
  qt128_seal(q);
  ASSERT_EQ(dec.decode(view(q), info, pts), Error::ok);
  EXPECT_EQ(pts.points[0].time_ns, t0 + 9000 + 1456);
  EXPECT_EQ(pts.points[0].confidence, 0);

  // Dual return: both blocks hold one firing at t0 + 9 us.
  auto d = qt128_packet(0x05, 0x3B, 1, s);
  qt128_point(d, 1, 99, 1000, 10);
  qt128_point(d, 2, 99, 1100, 10);
  qt128_seal(d);
  ASSERT_EQ(dec.decode(view(d), info, pts), Error::ok);
  ASSERT_EQ(pts.count, 2u);
  EXPECT_EQ(pts.points[0].time_ns, t0 + 9000 + 600);
  EXPECT_EQ(pts.points[1].time_ns, t0 + 9000 + 600);
  EXPECT_EQ(pts.points[1].return_index, 1);
}

// ---- QT128: distance 1 is a marker, not a point ----

// QT128C2X manual, Chinese edition, Section 3.1.2 (UDP data), the notes on the Distance field below
// the Body table: Distance = 0 means no return, and Distance = 1 is reserved as a marker, not a
// measurement of 1 x 4 mm. The smallest measured distance is therefore 2 x 4 mm = 8 mm. No bundled
// capture holds a 1: a real packet is edited and its CRCs sealed again.
TEST(Qt128Distance, OneIsAMarkerTwoIsAPoint) {
  const auto packets = pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_FALSE(packets.empty());
  auto p = packets[0];
  ASSERT_EQ(p[9], 4);  // dis unit: 4 mm
  const int ones[] = {65, 80, 97, 128};
  const int twos[] = {66, 81, 98, 127};
  for (int b = 1; b <= 2; ++b) {
    for (int c : ones) qt128_point(p, b, c, 1, 7);
    for (int c : twos) qt128_point(p, b, c, 2, 7);
  }
  qt128_seal(p);
  // Points by the manual's rule, from the edited bytes: distances other than 0 and 1.
  std::size_t expected = 0;
  for (std::size_t b = 0; b < 2; ++b)
    for (std::size_t c = 0; c < 128; ++c) expected += load_le16(&p[12 + 514 * b + 2 + 4 * c]) >= 2;

  Decoder dec(Model::qt128c2x);
  PacketInfo info;
  PacketPoints pts;
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  EXPECT_EQ(pts.count, expected);
  for (int b = 1; b <= 2; ++b) {
    for (int c : ones) EXPECT_EQ(find_point(pts, b, c), nullptr) << "block " << b << " channel " << c;
    for (int c : twos) {
      const Point* q = find_point(pts, b, c);
      ASSERT_NE(q, nullptr) << "block " << b << " channel " << c;
      EXPECT_NEAR(q->distance_m, 0.008, 1e-7);
      EXPECT_NEAR(std::sqrt(q->x * q->x + q->y * q->y + q->z * q->z), 0.008, 1e-6);
    }
  }
}

// ---- Accuracy: every channel at 200 m within 1 mm of a double evaluation ----

// The reference comes from the test's inputs only, never from the decoder's outputs: the unit's
// angle and firetime files as the test's own reader sees them (fed to the decoder as they are),
// the block azimuths written into the packet and the spin rate in its tail. Pandar64 manual,
// Section 3.1.4 (Point cloud data analysis method) and Appendix B.4: a = block azimuth + channel
// azimuth offset + firing time x spin rate; with the axes of Section 1.3 (Y at 0 deg, clockwise
// positive from above): x = r cos(e) sin(a), y = r cos(e) cos(a), z = r sin(e).
TEST(Accuracy, AllChannelsAt200mWithin1mm) {
  const ReferenceCalibration ref = read_reference_calibration(
      "calibration/pandar64_unit_a_angles.csv", "calibration/pandar64_firetimes.csv", 64);
  AngleCorrection angles;
  angles.channels = 64;
  FiretimeCorrection fire;
  fire.channels = 64;
  for (std::size_t c = 0; c < 64; ++c) {
    ASSERT_LT(ref.fire1[c], 0.0) << c + 1;  // read: every channel fires before its block ends (App. B)
    angles.elevation_deg[c] = ref.elevation[c];
    angles.azimuth_deg[c] = ref.azimuth[c];
    fire.firetime_us[0][c] = ref.fire1[c];
    fire.fires[0][c] = true;
  }
  Decoder dec(Model::pandar64);
  ASSERT_EQ(dec.set_angles(angles), Error::ok);
  ASSERT_EQ(dec.set_firetimes(fire), Error::ok);

  const Stamp s;
  const std::uint16_t rpm = 1200;
  const double deg_per_us = rpm * 360.0 / 60e6;
  const double r = 50000 * 0.004;  // 200 m
  const double kRad = M_PI / 180;
  for (int azimuth = 0; azimuth < 36000; azimuth += 1237) {
    auto p = pandar64_packet(0x37, s, rpm);
    int block_cdeg[7] = {};
    for (int b = 1; b <= 6; ++b) {
      block_cdeg[b] = (azimuth + 7 * b) % 36000;
      pandar64_azimuth(p, b, static_cast<std::uint16_t>(block_cdeg[b]));
      for (int c = 1; c <= 64; ++c) pandar64_point(p, b, c, 50000, 1);
    }
    PacketInfo info;
    PacketPoints pts;
    ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
    ASSERT_EQ(pts.count, 384u);
    std::size_t k = 0;
    for (int b = 1; b <= 6; ++b) {
      for (std::size_t c = 0; c < 64; ++c) {
        const Point& q = pts.points[k++];
        ASSERT_EQ(q.block, b - 1);
        ASSERT_EQ(q.channel, c + 1);
        const double a = (block_cdeg[b] / 100.0 + ref.azimuth[c] + ref.fire1[c] * deg_per_us) * kRad;
        const double e = ref.elevation[c] * kRad;
        EXPECT_NEAR(q.x, r * std::cos(e) * std::sin(a), 1e-3) << "block " << b << " channel " << c + 1;
        EXPECT_NEAR(q.y, r * std::cos(e) * std::cos(a), 1e-3) << "block " << b << " channel " << c + 1;
        EXPECT_NEAR(q.z, r * std::sin(e), 1e-3) << "block " << b << " channel " << c + 1;
      }
    }
  }
}

// ---- Caller-owned point storage sized for the model ----

// A packet of the model with every channel of every block at 10 m: the most points it can carry,
// blocks x channels by the manuals' layouts (Pandar40/40P 10 x 40, Pandar64 6 x 64, QT128 2 x 128).
std::vector<std::uint8_t> full_packet(Model m) {
  const Stamp s;
  std::vector<std::uint8_t> p;
  if (m == Model::pandar64) {
    p = pandar64_packet(0x37, s);
    for (int b = 1; b <= 6; ++b)
      for (int c = 1; c <= 64; ++c) pandar64_point(p, b, c, 2500, 9);
  } else if (m == Model::qt128c2x) {
    p = qt128_packet(0x05, 0x37, 1, s);
    for (int b = 1; b <= 2; ++b)
      for (int c = 1; c <= 128; ++c) qt128_point(p, b, c, 2500, 9);
    qt128_seal(p);
  } else {
    p = pandar40_packet(m == Model::pandar40p, 0x37, s, 0);
    for (int b = 1; b <= 10; ++b)
      for (int c = 1; c <= 40; ++c) pandar40_point(p, b, c, 2500, 9);
  }
  return p;
}

TEST(CallerStorage, WorstCaseFitsOneLessIsRefused) {
  const struct {
    Model model;
    std::size_t most;  // blocks x channels, from the manuals
  } cases[] = {{Model::pandar40, 400}, {Model::pandar40p, 400}, {Model::pandar64, 384}, {Model::qt128c2x, 256}};
  for (const auto& c : cases) {
    const auto p = full_packet(c.model);
    Decoder dec(c.model);
    if (c.model == Model::qt128c2x) {
      // The manual's banks rest 32 channels per sequence (at most 2 x 96 points); a firetime file
      // that fires every channel in both sequences lets all 128 carry data.
      FiretimeCorrection all;
      all.channels = 128;
      all.loops = 2;
      for (auto& loop : all.fires) loop.fill(true);
      ASSERT_EQ(dec.set_firetimes(all), Error::ok);
    }
    EXPECT_EQ(max_points(c.model), c.most);
    PacketInfo info;
    PacketPoints whole;
    ASSERT_EQ(dec.decode(view(p), info, whole), Error::ok) << model_name(c.model);
    ASSERT_EQ(whole.count, c.most);

    // Storage of exactly the worst case: the same points as PacketPoints.
    std::vector<Point> mine(c.most);
    std::size_t count = 99;
    ASSERT_EQ(dec.decode(view(p), info, mine.data(), mine.size(), count), Error::ok);
    ASSERT_EQ(count, c.most);
    for (std::size_t i = 0; i < count; ++i) {
      EXPECT_EQ(mine[i].x, whole.points[i].x);
      EXPECT_EQ(mine[i].time_ns, whole.points[i].time_ns);
      EXPECT_EQ(mine[i].channel, whole.points[i].channel);
      EXPECT_EQ(mine[i].block, whole.points[i].block);
    }

    // One point less: refused before anything is written, whatever the packet holds.
    std::vector<Point> small(c.most - 1);
    for (Point& q : small) q.distance_m = -1;
    count = 99;
    info.motor_rpm = 4321;
    EXPECT_EQ(dec.decode(view(p), info, small.data(), small.size(), count), Error::buffer_too_small);
    EXPECT_EQ(count, 0u);
    EXPECT_EQ(info.motor_rpm, 4321) << "info untouched";
    for (const Point& q : small) EXPECT_EQ(q.distance_m, -1);
    EXPECT_EQ(dec.decode(ByteView{}, info, small.data(), small.size(), count), Error::buffer_too_small);
  }
  EXPECT_STREQ(error_name(Error::buffer_too_small), "buffer_too_small");
}

// ---- Identification ----

TEST(Identify, ByLengthMagicAndHeader) {
  const Stamp s;
  Model m;
  PacketKind k;
  EXPECT_EQ(identify(view(pandar64_packet(0x37, s)), m, k), Error::ok);
  EXPECT_EQ(m, Model::pandar64);
  EXPECT_EQ(identify(view(pandar64_packet(0x37, s, 600, true)), m, k), Error::ok);
  EXPECT_EQ(m, Model::pandar64);
  EXPECT_EQ(identify(view(pandar40_packet(false, 0x37, s, 0)), m, k), Error::ok);
  EXPECT_EQ(m, Model::pandar40);
  EXPECT_EQ(identify(view(pandar40_packet(true, 0x37, s, 0)), m, k), Error::ok);
  EXPECT_EQ(m, Model::pandar40p);
  auto q = qt128_packet(0x1D, 0x39, 0, s);
  EXPECT_EQ(identify(view(q), m, k), Error::ok);
  EXPECT_EQ(m, Model::qt128c2x);
  std::vector<std::uint8_t> gps(512, 0);
  gps[0] = 0xFF; gps[1] = 0xEE;
  EXPECT_EQ(identify(view(gps), m, k), Error::ok);
  EXPECT_EQ(k, PacketKind::gps);

  // Another protocol version (3.3, or a 4.x sensor) is unsupported, never guessed.
  q[3] = 0x03;
  EXPECT_EQ(identify(view(q), m, k), Error::unsupported_version);
  // Protocol 3.1 is the PandarQT64's: 128 lasers and 2 blocks are not.
  q[3] = 0x01;
  EXPECT_EQ(identify(view(q), m, k), Error::unsupported_model);
  q[3] = 0x02;
  q[6] = 0x40;  // 64 lasers in a 3.2 header: another model
  EXPECT_EQ(identify(view(q), m, k), Error::unsupported_model);
  q[6] = 0x80;
  q[11] = 0x1C;  // flags without the UDP sequence: 4 bytes too many
  EXPECT_EQ(identify(view(q), m, k), Error::flags_length_mismatch);
  // A Pandar64 header on a 1200-byte payload.
  auto p = pandar64_packet(0x37, s);
  p.resize(1200);
  EXPECT_EQ(identify(view(p), m, k), Error::bad_length);
  p[0] = 0x12;
  EXPECT_EQ(identify(view(p), m, k), Error::bad_magic);
  EXPECT_EQ(identify(ByteView{}, m, k), Error::bad_length);
}

TEST(Identify, ModelMismatchAndImu) {
  const Stamp s;
  Decoder dec(Model::qt128c2x);
  PacketInfo info;
  EXPECT_EQ(dec.validate(view(pandar64_packet(0x37, s)), info), Error::model_mismatch);
  auto q = qt128_packet(0x1D | 0x02, 0x39, 0, s);  // IMU flag: its layout is not in the manual
  qt128_seal(q);
  EXPECT_EQ(dec.validate(view(q), info), Error::unsupported_section);
}

// ---- Rejections of real packets: every truncation and the field corruptions ----

TEST(Reject, EveryTruncationOfRealPackets) {
  for (const char* name : {"pandar40p_dual.pcap", "pandar64_dual.pcap", "qt128c2x_dual.pcap"}) {
    const auto packets = pcap_payloads(name);
    ASSERT_FALSE(packets.empty()) << name;
    const auto& full = packets[0];
    Model m;
    PacketKind k;
    ASSERT_EQ(identify(view(full), m, k), Error::ok);
    Decoder dec(m);
    PacketInfo info;
    PacketPoints pts;
    for (std::size_t n = 0; n < full.size(); ++n) {
      std::vector<std::uint8_t> cut(full.begin(), full.begin() + static_cast<long>(n));
      const Error e = dec.decode(view(cut), info, pts);
      if (m == Model::pandar64 && n == 1194) {
        // Without its last 4 bytes a 1198-byte packet is a valid packet without UDP sequence:
        // the manual's two layouts cannot be told apart there.
        EXPECT_EQ(e, Error::ok);
        EXPECT_FALSE(info.has_sequence);
        continue;
      }
      EXPECT_NE(e, Error::ok) << name << " length " << n;
      EXPECT_EQ(pts.count, 0u);
      // The expected code: a length no layout has, or a known length of another packet kind.
      if (m == Model::qt128c2x && n >= 12) {
        EXPECT_EQ(e, Error::flags_length_mismatch) << n;
      } else if (m == Model::pandar40p && (n == 512 || n == 1256)) {
        EXPECT_EQ(e, Error::model_mismatch) << n;  // a GPS or Pandar40 length
      } else {
        EXPECT_EQ(e, Error::bad_length) << name << " " << n;
      }
    }
  }
}

TEST(Reject, Qt128EveryByteOfCrcFieldsAndTail) {
  const auto packets = pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_FALSE(packets.empty());
  const auto& good = packets[0];
  Decoder dec(Model::qt128c2x);
  PacketInfo info;
  PacketPoints pts;
  auto flip = [&](std::size_t at) {
    auto p = good;
    p[at] ^= 0x01;
    return dec.decode(view(p), info, pts);
  };
  for (std::size_t i = 12; i < 1044; ++i) ASSERT_EQ(flip(i), Error::crc_body) << i;                // body + CRC1
  for (std::size_t i = 1045; i < 1061; ++i) ASSERT_EQ(flip(i), Error::crc_functional_safety) << i; // FS + CRC2
  for (std::size_t i = 1061; i < 1095; ++i) ASSERT_EQ(flip(i), Error::crc_tail) << i;               // tail + CRC3
  // Header: the magic, version, laser and block numbers, and the flags.
  EXPECT_EQ(flip(0), Error::bad_magic);
  EXPECT_EQ(flip(3), Error::unsupported_version);
  EXPECT_EQ(flip(6), Error::unsupported_model);
  EXPECT_EQ(flip(11), Error::flags_length_mismatch);  // 0x1C: the sequence flag cleared
  auto p = good;
  p[9] = 0;  // distance unit 0
  EXPECT_EQ(dec.decode(view(p), info, pts), Error::bad_header);
  p = good;
  p[10] = 1;  // one return announced, dual-return mode in the tail
  EXPECT_EQ(dec.decode(view(p), info, pts), Error::bad_return_mode);
}

TEST(Reject, Pandar64TailFields) {
  const auto packets = pcap_payloads("pandar64_dual.pcap");
  ASSERT_FALSE(packets.empty());
  const auto& good = packets[0];
  Decoder dec(Model::pandar64);
  PacketInfo info;
  PacketPoints pts;
  auto with = [&](std::size_t at, std::uint8_t v) {
    auto p = good;
    p[at] = v;
    return dec.decode(view(p), info, pts);
  };
  EXPECT_EQ(with(0, 0xEF), Error::bad_magic);
  EXPECT_EQ(with(2, 0x41), Error::unsupported_version); // EE FF with another laser count: another model or protocol
  EXPECT_EQ(with(5, 0), Error::bad_header);              // distance unit 0
  EXPECT_EQ(with(1186, 0x36), Error::bad_return_mode);
  EXPECT_EQ(with(1189, 13), Error::bad_date_time);       // month 13
  EXPECT_EQ(with(1190, 31), Error::bad_date_time);       // June 31st
  EXPECT_EQ(with(1191, 24), Error::bad_date_time);       // hour 24
  EXPECT_EQ(with(1193, 60), Error::bad_date_time);       // second 60
  EXPECT_EQ(with(1185, 0x01), Error::bad_timestamp);     // >= 1 000 000 us
  EXPECT_EQ(with(1181, 0x06), Error::bad_motor_speed);   // 0x0657 = 1623 rpm
  EXPECT_EQ(with(1181, 0x05), Error::ok);                // 0x0557 = 1367 rpm: a plausible speed
  EXPECT_EQ(with(9, 0x8D), Error::bad_azimuth);          // block 1 azimuth >= 36000
  EXPECT_EQ(with(8 + 194, 0x48), Error::dual_block_mismatch);  // block 2 azimuth differs from block 1
  EXPECT_EQ(pts.count, 0u);
}

TEST(Reject, Pandar40PBlockPreamble) {
  const auto packets = pcap_payloads("pandar40p_dual.pcap");
  ASSERT_FALSE(packets.empty());
  Decoder dec(Model::pandar40p);
  PacketInfo info;
  PacketPoints pts;
  for (std::size_t b = 1; b < 10; ++b) {
    auto p = packets[0];
    p[124 * b + 1] = 0xEF;
    EXPECT_EQ(dec.decode(view(p), info, pts), Error::bad_magic) << b;
  }
  auto p = packets[0];
  p[1254] = 0x33;  // QT128-only return mode
  EXPECT_EQ(dec.decode(view(p), info, pts), Error::bad_return_mode);
}

// ---- qt128::seal ----

// The CRC-32/MPEG-2 of tests/packet_builder.h, written there independently of core/.
std::uint32_t reference_crc(const std::uint8_t* p, std::size_t n) { return crc32_mpeg2_reference(p, n); }

TEST(Qt128Seal, ReproducesTheSensorsCrcsAndResealsAChangedTail) {
  ASSERT_EQ(reference_crc(kCrcCheckString, 9), 0x0376E6E7u);  // the catalogue's check value
  // Packet 0 of the bundled capture: flags 0x1D (sequence, functional safety, signature), so by
  // manual 3.1.2 header 12 + body 1028 + CRC1 4 + functional safety 17: the tail starts at 1061;
  // its UDP sequence at 1061 + 26, CRC3 over the 30 bytes before it at 1091; 1127 bytes in all.
  const std::vector<std::uint8_t> real = pcap_payloads("qt128c2x_dual.pcap").at(0);
  ASSERT_EQ(real.size(), 1127u);
  ASSERT_EQ(real[11], 0x1D);
  std::vector<std::uint8_t> p = real;
  ASSERT_EQ(qt128::seal(p.data(), p.size()), Error::ok);
  EXPECT_EQ(p, real);  // the sensor's own CRC1, CRC2 and CRC3 (0xA745F91E) reproduced

  p[1061 + 26] ^= 1;  // UDP sequence 6394573 -> 6394572
  Decoder dec(Model::qt128c2x);
  PacketInfo info;
  EXPECT_EQ(dec.validate(ByteView{p.data(), p.size()}, info), Error::crc_tail);
  ASSERT_EQ(qt128::seal(p.data(), p.size()), Error::ok);
  EXPECT_EQ(dec.validate(ByteView{p.data(), p.size()}, info), Error::ok);
  EXPECT_EQ(info.sequence, 6394572u);
  // CRC3 as the reference computes it, and as Python's hand-written CRC gave: 0x7B2863A9.
  EXPECT_EQ(load_le32(&p[1091]), reference_crc(&p[1061], 30));
  EXPECT_EQ(load_le32(&p[1091]), 0x7B2863A9u);
  // Nothing else moved: CRC1, CRC2 and the signature bytes are the sensor's.
  for (std::size_t i = 0; i < p.size(); ++i) {
    const bool changed = i == 1061 + 26 || (i >= 1091 && i < 1095);
    if (!changed) {
      ASSERT_EQ(p[i], real[i]) << "byte " << i;
    }
  }
}

// qt128::seal writes the bytes the builder's own qt128_seal writes (its offsets, its CRC) on built
// packets of every flags combination (sequence, functional safety, signature, 4-byte units) and
// with customised channels (3-byte units, fewer lasers); the decoder accepts the former (the
// latter need the channel configuration).
TEST(Qt128Seal, AgreesWithTheBuildersOwnCrcsOnEveryLayout) {
  const Stamp s;
  std::size_t checked = 0;
  for (unsigned bits = 0; bits < 16; ++bits) {
    const std::uint8_t flags = static_cast<std::uint8_t>(((bits & 1) ? 0x01 : 0) | ((bits & 2) ? 0x04 : 0) |
                                                         ((bits & 4) ? 0x08 : 0) | ((bits & 8) ? 0x10 : 0));
    auto p = qt128_packet(flags, 0x37, 0, s, 600, 1234);
    qt128_point(p, 1, 5, 1000, 77, 3);
    qt128_point(p, 2, 128, 2000, 99, 1);
    auto q = p;
    qt128_seal(p);
    ASSERT_EQ(qt128::seal(q.data(), q.size()), Error::ok);
    EXPECT_EQ(q, p) << "flags " << int(flags);
    Decoder dec(Model::qt128c2x);
    PacketInfo info;
    EXPECT_EQ(dec.validate(view(p), info), Error::ok) << "flags " << int(flags);
    // With customised channels: the first 40 units of each block, cut to 3 bytes.
    auto c = qt128_rebuild(p, 40, static_cast<std::uint8_t>((flags & ~0x10) | 0x40), {first_units(40), first_units(40)});
    auto d = c;
    ASSERT_EQ(qt128::seal(d.data(), d.size()), Error::ok);
    EXPECT_EQ(d, c) << "customised, flags " << int(flags);
    checked += 2;
  }
  EXPECT_EQ(checked, 32u);
}

TEST(Qt128Seal, RefusesWhatIsNotAQt128PacketOfItsFlagsLength) {
  std::vector<std::uint8_t> p = pcap_payloads("qt128c2x_dual.pcap").at(0);
  p[1061 + 26] ^= 1;
  const std::vector<std::uint8_t> before = p;
  EXPECT_EQ(qt128::seal(p.data(), p.size() - 1), Error::bad_length);
  EXPECT_EQ(qt128::seal(p.data(), 11), Error::bad_length);  // no flags byte
  p[11] = 0x1C;  // no sequence: 4 bytes shorter
  EXPECT_EQ(qt128::seal(p.data(), p.size()), Error::bad_length);
  p[11] = 0x1D;
  p[0] = 0xFF;
  p[1] = 0xEE;  // Pandar40/64 start bytes
  EXPECT_EQ(qt128::seal(p.data(), p.size()), Error::bad_magic);
  p[0] = 0xEE;
  p[1] = 0xFF;
  EXPECT_EQ(p, before);  // nothing written
}

// ---- QT128 resting channels ----

// Manual 3.1.2: "If a channel does not fire in the current firing sequence, its corresponding four
// bytes are filled with 0"; App. II: sequence 1 rests bank A, sequence 2 bank B; App. I: bank A is
// channels 1..32, bank B 33..64, C 65..96. Packet 0 of the capture: mode flag (tail byte 5, at
// 1066) 0, so block 1 fired sequence 2, and in dual return (header byte 10 = 2) block 2 shares
// that firing: channels 33..64 rest in both blocks. Block b's unit of channel c starts at
// 12 + 514 b + 2 + 4 (c - 1).
class Qt128Resting : public ::testing::Test {
 protected:
  static std::size_t unit_at(std::size_t block, std::size_t channel) { return 12 + 514 * block + 2 + 4 * (channel - 1); }

  // CRC1 (at 1040, over the body 12..1039) and CRC3 (at 1091, over the tail 1061..1090) by
  // reference_crc, little-endian (manual 3.1.2).
  static void reseal(std::vector<std::uint8_t>& p) {
    for (const auto& [at, from] : {std::pair<std::size_t, std::size_t>{1040, 12}, {1091, 1061}}) {
      const std::uint32_t c = reference_crc(&p[from], at - from);
      for (std::size_t i = 0; i < 4; ++i) p[at + i] = static_cast<std::uint8_t>(c >> (8 * i));
    }
  }

  // The real packet with one unit's distance (and optionally reflectivity) set, re-sealed.
  std::vector<std::uint8_t> with_unit(std::size_t block, std::size_t channel, std::uint16_t raw,
                                      std::uint8_t reflectivity = 0) const {
    auto p = real;
    const std::size_t at = unit_at(block, channel);
    p[at] = static_cast<std::uint8_t>(raw & 0xFF);
    p[at + 1] = static_cast<std::uint8_t>(raw >> 8);
    p[at + 2] = reflectivity;
    reseal(p);
    return p;
  }

  void SetUp() override {
    real = pcap_payloads("qt128c2x_dual.pcap").at(0);
    ASSERT_EQ(real.size(), 1127u);
    ASSERT_EQ(real[11], 0x1D);
    ASSERT_EQ(real[1066] & 1, 0);  // block 1: firing sequence 2
    ASSERT_EQ(real[10], 2);        // dual return: block 2 the same firing
    // The sensor's own bytes: every unit of bank B is zero in both blocks, and so is channel 87
    // (bank C, fires in both sequences: no return in this packet).
    for (std::size_t b = 0; b < 2; ++b) {
      for (std::size_t ch = 33; ch <= 64; ++ch)
        for (std::size_t k = 0; k < 4; ++k) ASSERT_EQ(real[unit_at(b, ch) + k], 0) << b << " " << ch;
      for (std::size_t k = 0; k < 4; ++k) ASSERT_EQ(real[unit_at(b, 87) + k], 0);
    }
    auto copy = real;
    reseal(copy);
    ASSERT_EQ(copy, real);  // reseal() reproduces the sensor's CRCs
    ASSERT_EQ(dec.decode(view(real), info, pts), Error::ok);
    real_points = pts.count;
  }

  bool has_channel(std::uint8_t channel, std::uint8_t block) const {
    return std::any_of(pts.begin(), pts.end(), [&](const Point& q) { return q.channel == channel && q.block == block; });
  }

  std::vector<std::uint8_t> real;
  Decoder dec{Model::qt128c2x};
  PacketInfo info;
  PacketPoints pts;
  std::size_t real_points = 0;
};

// Distance 256 (1.024 m at 4 mm) in a resting unit: without the check it became a point of that
// channel with the firing time of a sequence it did not fire in.
TEST_F(Qt128Resting, DataInARestingChannelRejectsThePacket) {
  for (const auto& [block, channel] : {std::pair<std::size_t, std::size_t>{0, 33}, {0, 40}, {0, 64}, {1, 33}, {1, 50}}) {
    const auto p = with_unit(block, channel, 256);
    EXPECT_EQ(dec.decode(view(p), info, pts), Error::resting_channel_data) << block << " " << channel;
    EXPECT_EQ(pts.count, 0u);
    EXPECT_EQ(dec.decode(view(p), info, pts, DecodePath::portable), Error::resting_channel_data);
    PacketColumns<kMaxPointsPerPacket> cols;
    EXPECT_EQ(dec.decode(view(p), info, cols), Error::resting_channel_data);
    EXPECT_EQ(cols.count, 0u);
    EXPECT_EQ(dec.validate(view(p), info), Error::resting_channel_data);
    Stats s{};
    count_error(s, Error::resting_channel_data);
    EXPECT_EQ(s.malformed, 1u);
  }
  // "four bytes are filled with 0": a reflectivity or confidence byte alone is data too.
  EXPECT_EQ(dec.decode(view(with_unit(0, 40, 0, 7)), info, pts), Error::resting_channel_data);
  auto p = real;
  p[unit_at(1, 64) + 3] = 1;
  reseal(p);
  EXPECT_EQ(dec.decode(view(p), info, pts), Error::resting_channel_data);
}

// The same edit in a channel that fires (87, bank C) is a point, in the block edited.
TEST_F(Qt128Resting, TheSameEditInAFiringChannelIsAPoint) {
  for (std::uint8_t block = 0; block < 2; ++block) {
    const auto p = with_unit(block, 87, 256);
    ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
    EXPECT_EQ(pts.count, real_points + 1);
    EXPECT_TRUE(has_channel(87, block));
  }
}

// Single return: block 2 fires the other sequence (manual 3.1.2), here sequence 1, which rests
// bank A. Turned into a single-return packet (header return num 1, tail return mode 0x38 last at
// 1073), packet 0's block 2 holds bank A data from a sequence-2 firing: rejected; with block 2's
// bank A units zeroed and bank B's (which fire in sequence 1) left as they are, accepted.
TEST_F(Qt128Resting, SingleReturnBlockTwoRestsTheOtherBank) {
  auto p = real;
  p[10] = 1;
  p[1073] = 0x38;
  reseal(p);
  EXPECT_EQ(dec.decode(view(p), info, pts), Error::resting_channel_data);
  for (std::size_t ch = 1; ch <= 32; ++ch)
    for (std::size_t k = 0; k < 4; ++k) p[unit_at(1, ch) + k] = 0;
  reseal(p);
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  EXPECT_EQ(info.returns, 1);
  for (const Point& q : pts) EXPECT_FALSE(q.block == 1 && q.channel <= 32) << int(q.channel);
}

// The firetime file decides which channels rest: the shipped file's Loop2 leaves out 33..64 as
// the manual does, so the edit is rejected; a file that fires channel 40 in sequence 2 (at 50 us)
// makes the same unit a point of channel 40 at 1.024 m.
TEST_F(Qt128Resting, TheFiretimeFileNamesTheRestingChannels) {
  const auto text = read_file(data_path("calibration/qt128c2x_firetimes.csv"));
  FiretimeCorrection f;
  ASSERT_EQ(parse_firetime_csv(view(text), 128, f).error, Error::ok);
  ASSERT_EQ(dec.set_firetimes(f), Error::ok);
  const auto p = with_unit(0, 40, 256);
  EXPECT_EQ(dec.decode(view(p), info, pts), Error::resting_channel_data);
  ASSERT_FALSE(f.fires[1][40 - 1]);
  f.fires[1][40 - 1] = true;
  f.firetime_us[1][40 - 1] = 50.0;
  ASSERT_EQ(dec.set_firetimes(f), Error::ok);
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  EXPECT_EQ(pts.count, real_points + 1);
  const auto it = std::find_if(pts.begin(), pts.end(), [](const Point& q) { return q.channel == 40; });
  ASSERT_NE(it, pts.end());
  EXPECT_FLOAT_EQ(it->distance_m, 1.024f);
  // Its neighbours still rest (sequence 2 now rests 33..39 and 41..64: two runs).
  for (const std::size_t channel : {std::size_t{39}, std::size_t{41}, std::size_t{64}})
    EXPECT_EQ(dec.decode(view(with_unit(1, channel, 256)), info, pts), Error::resting_channel_data) << channel;
}

// ---- Signatures (QT128) ----

class Signature : public ::testing::Test {
 protected:
  void SetUp() override {
    // Session key by HKDF as in the notes: secret, lidar random || client random, "finish session key".
    const char secret[] = "correct horse battery";
    std::uint8_t lidar[32], client[32];
    for (int i = 0; i < 32; ++i) {
      lidar[i] = static_cast<std::uint8_t>(i);
      client[i] = static_cast<std::uint8_t>(0xA0 + i);
    }
    ASSERT_EQ(hesai_session_key(ByteView{reinterpret_cast<const std::uint8_t*>(secret), sizeof secret - 1}, lidar,
                                client, key),
              Error::ok);
    real = pcap_payloads("qt128c2x_dual.pcap");
    ASSERT_GT(real.size(), 5u);
    packet = real[5];
    qt128_seal(packet, key);  // sign the real packet (its CRCs are unchanged)
  }
  std::uint8_t key[32];
  std::vector<std::vector<std::uint8_t>> real;  // the capture's packets
  std::vector<std::uint8_t> packet;             // real[5], signed with key
  PacketInfo info;
  PacketPoints pts;
};

TEST_F(Signature, ValidInvalidMissingUnverified) {
  Decoder dec(Model::qt128c2x);
  ASSERT_EQ(dec.decode(view(packet), info, pts), Error::ok);
  EXPECT_EQ(info.signature, SignatureStatus::unverified);  // no key: not checked, and said so

  ASSERT_EQ(dec.set_session_key(key), Error::ok);
  ASSERT_EQ(dec.decode(view(packet), info, pts), Error::ok);
  EXPECT_EQ(info.signature, SignatureStatus::valid);
  EXPECT_GT(pts.count, 0u);

  for (std::size_t i = 1095; i < 1127; ++i) {
    auto p = packet;
    p[i] ^= 0x80;
    EXPECT_EQ(dec.decode(view(p), info, pts), Error::signature_invalid) << i;
    EXPECT_EQ(pts.count, 0u);
  }
  // A signed field changed and its CRC fixed: the signature catches what the CRC cannot.
  auto p = packet;
  p[1087] ^= 1;  // UDP sequence
  qt128_seal(p);
  EXPECT_EQ(dec.decode(view(p), info, pts), Error::signature_invalid);

  // Downgrade: the all-zero signature of an unsigned packet, with a key set.
  const auto& unsigned_packet = real[5];
  EXPECT_EQ(dec.decode(view(unsigned_packet), info, pts), Error::signature_missing);
  dec.set_allow_unsigned(true);
  EXPECT_EQ(dec.decode(view(unsigned_packet), info, pts), Error::ok);
  EXPECT_EQ(info.signature, SignatureStatus::accepted_unsigned);

  // A wrong key.
  key[0] ^= 1;
  ASSERT_EQ(dec.set_session_key(key), Error::ok);
  EXPECT_EQ(dec.decode(view(packet), info, pts), Error::signature_invalid);
}

TEST_F(Signature, FlagClearedIsMissingWithKey) {
  const Stamp s;
  auto q = qt128_packet(0x05, 0x37, 1, s);  // no signature section at all
  qt128_seal(q);
  Decoder dec(Model::qt128c2x);
  ASSERT_EQ(dec.set_session_key(key), Error::ok);
  EXPECT_EQ(dec.decode(view(q), info, pts), Error::signature_missing);
}

}  // namespace
