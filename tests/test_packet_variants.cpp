// Sensor settings the bundled captures do not show (README, "Sensor settings we read"). Each
// variant is built from the real packets of a bundled capture byte for byte
// (tests/packet_builder.h: units cut or dropped, header fields and the tail rewritten, then the
// CRCs recomputed), and must decode to exactly what the original packet gives: the original
// points are the reference (test_golden.cpp checks them against the manuals' formulas).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <iterator>
#include <string>
#include <vector>

#include "hesai/calibration.h"
#include "hesai/decoder.h"
#include "hesai/detail/tables/pandar64_tables.h"
#include "packet_builder.h"
#include "test_support.h"

using namespace hesai;
using namespace hesai_test;

namespace {

struct Decoded {
  Error error = Error::ok;
  PacketInfo info;
  std::vector<Point> points;
};

Decoded decode(Decoder& d, const std::vector<std::uint8_t>& p) {
  static PacketPoints pts;
  Decoded r;
  r.error = d.decode(view(p), r.info, pts);
  r.points.assign(pts.begin(), pts.end());
  return r;
}

// Every field of two points, exactly (the same channel, geometry and time give the same floats).
::testing::AssertionResult same_point(const Point& a, const Point& b, std::uint8_t want_confidence) {
  if (a.x == b.x && a.y == b.y && a.z == b.z && a.distance_m == b.distance_m && a.azimuth_deg == b.azimuth_deg &&
      a.elevation_deg == b.elevation_deg && a.time_ns == b.time_ns && a.intensity == b.intensity &&
      a.channel == b.channel && a.return_index == b.return_index && a.block == b.block &&
      b.confidence == want_confidence)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "channel " << int(a.channel) << "/" << int(b.channel) << " block "
                                       << int(a.block) << "/" << int(b.block) << " time " << a.time_ns << "/"
                                       << b.time_ns << " confidence " << int(b.confidence);
}

// The packet-level fields a variant must keep.
void expect_same_info(const PacketInfo& a, const PacketInfo& b) {
  EXPECT_EQ(a.time_ns, b.time_ns);
  EXPECT_EQ(a.block_azimuth, b.block_azimuth);
  EXPECT_EQ(a.motor_rpm, b.motor_rpm);
  EXPECT_EQ(a.return_mode, b.return_mode);
  EXPECT_EQ(a.mode_flag, b.mode_flag);
  EXPECT_EQ(a.sequence, b.sequence);
  EXPECT_EQ(a.safety.rolling_counter, b.safety.rolling_counter);
  EXPECT_EQ(a.date_time.year, b.date_time.year);
  EXPECT_EQ(a.date_time.month, b.date_time.month);
  EXPECT_EQ(a.date_time.day, b.date_time.day);
  EXPECT_EQ(a.date_time.hour, b.date_time.hour);
  EXPECT_EQ(a.date_time.minute, b.date_time.minute);
  EXPECT_EQ(a.date_time.second, b.date_time.second);
}

const std::vector<std::vector<std::uint8_t>>& qt128_packets() {
  static const auto packets = pcap_payloads("qt128c2x_dual.pcap");
  return packets;
}

// QT128 App. II and the mode flag (tail byte 5, at 1066 in the captures' 0x1D layout): block 1
// fires sequence 1 (Loop1, index 0) when bit 0 is set, else sequence 2; in single return block 2
// fires the other one, in dual return both blocks share block 1's.
std::size_t block_loop(const std::vector<std::uint8_t>& original, std::size_t block) {
  const std::size_t loop1 = (original[1066] & 1) ? 0 : 1;
  const bool dual = original[10] == 2;
  return (dual || block == 0) ? loop1 : 1 - loop1;
}

// ---- 1. QT128 units of 3 bytes (flags bit 4 clear) ----

// Vendor SDK udp_protocol_v3_2.h unitSize(): 3 bytes, plus the confidence byte with flags bit 4.
// Every packet of the capture with each unit's 4th byte dropped and bit 4 cleared (0x1D -> 0x0D):
// 871 bytes, and exactly the original points with confidence 0.
TEST(Qt128ThreeByteUnits, EveryCapturePacketDecodesToTheOriginalPoints) {
  Decoder dec(Model::qt128c2x);
  std::size_t points = 0;
  for (const auto& p : qt128_packets()) {
    ASSERT_EQ(p[11], 0x1D);
    const auto q = qt128_rebuild(p, 128, 0x0D, {first_units(128), first_units(128)});
    ASSERT_EQ(q.size(), 871u);  // 1127 - 2 blocks x 128 confidence bytes
    const Decoded want = decode(dec, p);
    const Decoded got = decode(dec, q);
    ASSERT_EQ(want.error, Error::ok);
    ASSERT_EQ(got.error, Error::ok);
    EXPECT_EQ(got.info.flags, 0x0D);
    expect_same_info(want.info, got.info);
    ASSERT_EQ(got.points.size(), want.points.size());
    for (std::size_t i = 0; i < want.points.size(); ++i) ASSERT_TRUE(same_point(want.points[i], got.points[i], 0));
    points += got.points.size();
  }
  EXPECT_EQ(points, 337108u);  // test_golden.cpp's count of the capture's non-zero distances
}

// The capture's confidence bytes are all zero: give them values, so that the 4-byte decode shows
// them and the 3-byte one (the same units without that byte) cannot. Units the sensor left all
// zero stay so: they include the resting channels', whose four bytes the manual fixes at 0 (3.1.2).
TEST(Qt128ThreeByteUnits, ConfidenceByteOnlyWithBit4) {
  auto p = qt128_packets().at(0);
  for (std::size_t b = 0; b < 2; ++b)
    for (std::size_t c = 0; c < 128; ++c) {
      std::uint8_t* u = &p[12 + b * 514 + 2 + c * 4];
      if ((u[0] | u[1] | u[2]) != 0) u[3] = static_cast<std::uint8_t>(c + 1);
    }
  qt128_seal(p);
  Decoder dec(Model::qt128c2x);
  const Decoded four = decode(dec, p);
  ASSERT_EQ(four.error, Error::ok);
  ASSERT_FALSE(four.points.empty());
  for (const Point& q : four.points) EXPECT_EQ(q.confidence, q.channel);  // unit c carries c + 1
  const Decoded three = decode(dec, qt128_rebuild(p, 128, 0x0D, {first_units(128), first_units(128)}));
  ASSERT_EQ(three.error, Error::ok);
  ASSERT_EQ(three.points.size(), four.points.size());
  for (std::size_t i = 0; i < four.points.size(); ++i) EXPECT_TRUE(same_point(four.points[i], three.points[i], 0));
}

// The length follows the unit size: a 3-byte packet that claims bit 4, or a 4-byte one that does not.
TEST(Qt128ThreeByteUnits, LengthMismatchEitherWay) {
  const auto& p = qt128_packets().at(0);
  auto q = qt128_rebuild(p, 128, 0x0D, {first_units(128), first_units(128)});
  Model m;
  PacketKind k;
  ASSERT_EQ(identify(view(q), m, k), Error::ok);
  q[11] = 0x1D;  // 871 bytes with 4-byte units announced (1127 expected)
  EXPECT_EQ(identify(view(q), m, k), Error::flags_length_mismatch);
  auto r = p;
  r[11] = 0x0D;  // 1127 bytes with 3-byte units announced (871 expected)
  EXPECT_EQ(identify(view(r), m, k), Error::flags_length_mismatch);
  Decoder dec(Model::qt128c2x);
  PacketInfo info;
  PacketPoints pts;
  EXPECT_EQ(dec.decode(view(r), info, pts), Error::flags_length_mismatch);
  EXPECT_EQ(pts.count, 0u);
}

// ---- 2. QT128 channel customisation (flags bit 6) ----

// The bundled configuration, read by this test with strtod (not the library's parser): rows
// "Loop1 channel, Loop2 channel" after the three header rows; the hash line has one field.
const std::vector<std::size_t>& listed_channels(std::size_t loop) {
  static const auto columns = [] {
    std::array<std::vector<std::size_t>, 2> c;
    for (const auto& row : read_numeric_csv("calibration/qt128c2x_channel_config.csv").rows)
      if (row.size() == 2)
        for (std::size_t k = 0; k < 2; ++k) c[k].push_back(static_cast<std::size_t>(row[k]));
    return c;
  }();
  return columns.at(loop);
}

ChannelConfig bundled_config() {
  ChannelConfig c;
  const auto text = read_file(data_path("calibration/qt128c2x_channel_config.csv"));
  EXPECT_EQ(parse_channel_config_csv(view(text), c).error, Error::ok);
  return c;
}

// The customised packet of a real one: in each block only the units of the channels listed for
// its loop, in the file's order; laser num = their count, flags bit 6 set (and bit 4 as given).
std::vector<std::uint8_t> customised(const std::vector<std::uint8_t>& p, std::uint8_t flags, std::size_t keep_count = 80) {
  std::vector<std::size_t> keep[2];
  for (std::size_t b = 0; b < 2; ++b) {
    for (std::size_t ch : listed_channels(block_loop(p, b))) keep[b].push_back(ch - 1);  // unit position = channel - 1
    keep[b].resize(keep_count);
  }
  return qt128_rebuild(p, static_cast<std::uint8_t>(keep_count), flags, keep);
}

// SDK udp3_2_parser.cc: unit j of a block is channel channel[loop][j] of the configuration. The
// bundled file lists 80 channels per loop (Loop1 49..128, Loop2 17..32 and 65..128). Every
// capture packet reduced to those units decodes to exactly the original points of the listed
// channels, in both unit sizes.
TEST(Qt128ChannelCustomisation, EightyChannelsDecodeToTheOriginalPointsOfTheListedChannels) {
  const std::vector<std::size_t> loop_channels[2] = {listed_channels(0), listed_channels(1)};
  ASSERT_EQ(loop_channels[0].size(), 80u);
  ASSERT_EQ(loop_channels[1].size(), 80u);
  EXPECT_EQ(loop_channels[0][0], 49u);  // file line 4: "49,17"
  EXPECT_EQ(loop_channels[1][0], 17u);
  Decoder plain(Model::qt128c2x), custom(Model::qt128c2x);
  ASSERT_EQ(custom.set_channel_config(bundled_config()), Error::ok);
  for (const std::uint8_t flags : {std::uint8_t{0x5D}, std::uint8_t{0x4D}}) {  // 4-byte and 3-byte units
    const std::uint8_t confidence_mask = (flags & 0x10) ? 0xFF : 0;
    std::size_t points = 0;
    for (const auto& p : qt128_packets()) {
      const auto q = customised(p, flags);
      ASSERT_EQ(q.size(), flags == 0x5D ? 743u : 583u);  // 12 + 2 x (2 + 80 x 4 or 3) + 4 + 17 + 30 + 4 + 32
      const Decoded all = decode(plain, p);
      const Decoded got = decode(custom, q);
      ASSERT_EQ(got.error, Error::ok);
      expect_same_info(all.info, got.info);
      std::vector<Point> want;
      for (const Point& o : all.points) {
        const auto& listed = loop_channels[block_loop(p, o.block)];
        if (std::find(listed.begin(), listed.end(), o.channel) != listed.end()) want.push_back(o);
      }
      // The file lists each loop's channels in ascending order, as the original points come.
      ASSERT_EQ(got.points.size(), want.size());
      for (std::size_t i = 0; i < want.size(); ++i)
        ASSERT_TRUE(same_point(want[i], got.points[i], static_cast<std::uint8_t>(want[i].confidence & confidence_mask)));
      points += got.points.size();
    }
    EXPECT_GT(points, 200000u) << int(flags);
  }
}

// A one-loop configuration maps the blocks of both sequences with its one column.
TEST(Qt128ChannelCustomisation, OneLoopConfigurationMapsBothSequences) {
  ChannelConfig c = bundled_config();
  c.loops = 1;  // Loop1 only: 49..128
  Decoder plain(Model::qt128c2x), custom(Model::qt128c2x);
  ASSERT_EQ(custom.set_channel_config(c), Error::ok);
  const auto& p = qt128_packets().at(0);  // mode flag 0: both blocks fire sequence 2
  ASSERT_EQ(block_loop(p, 0), 1u);
  std::vector<std::size_t> keep = listed_channels(0);
  for (std::size_t& k : keep) --k;
  const Decoded got = decode(custom, qt128_rebuild(p, 80, 0x5D, {keep, keep}));
  ASSERT_EQ(got.error, Error::ok);
  const Decoded all = decode(plain, p);
  std::vector<Point> want;
  for (const Point& o : all.points)
    if (o.channel >= 49) want.push_back(o);
  ASSERT_EQ(got.points.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_TRUE(same_point(want[i], got.points[i], 0));
}

// Customised units are checked as the channel the configuration names: with the one-loop
// configuration (49..128) a sequence-2 block's units 0..15 are channels 49..64, which rest in
// sequence 2 (bank B, manual App. II); data there rejects the packet, in unit 38 (channel 87,
// bank C, no return in this packet) it is a point.
TEST(Qt128ChannelCustomisation, DataInAUnitOfARestingChannel) {
  ChannelConfig c = bundled_config();
  c.loops = 1;
  Decoder custom(Model::qt128c2x);
  ASSERT_EQ(custom.set_channel_config(c), Error::ok);
  const auto& p = qt128_packets().at(0);
  ASSERT_EQ(block_loop(p, 0), 1u);
  ASSERT_EQ(block_loop(p, 1), 1u);
  std::vector<std::size_t> keep = listed_channels(0);
  ASSERT_EQ(keep.at(0), 49u);
  ASSERT_EQ(keep.at(38), 87u);
  for (std::size_t& k : keep) --k;
  const auto q = qt128_rebuild(p, 80, 0x5D, {keep, keep});
  const Decoded base = decode(custom, q);
  ASSERT_EQ(base.error, Error::ok);
  for (const std::size_t unit : {std::size_t{0}, std::size_t{15}}) {
    auto r = q;
    r[12 + 2 + 4 * unit] = 0x40;  // block 1, distance 64 (0.256 m)
    qt128_seal(r);
    EXPECT_EQ(decode(custom, r).error, Error::resting_channel_data) << unit;
  }
  auto r = q;
  ASSERT_EQ(r[12 + 2 + 4 * 38] | r[12 + 2 + 4 * 38 + 1], 0);  // channel 87: no return in this packet
  r[12 + 2 + 4 * 38] = 0x40;
  qt128_seal(r);
  const Decoded one_more = decode(custom, r);
  ASSERT_EQ(one_more.error, Error::ok);
  EXPECT_EQ(one_more.points.size(), base.points.size() + 1);
}

TEST(Qt128ChannelCustomisation, Rejections) {
  const auto& p = qt128_packets().at(0);
  const auto q = customised(p, 0x5D);
  Model m;
  PacketKind k;
  ASSERT_EQ(identify(view(q), m, k), Error::ok);
  PacketInfo info;
  PacketPoints pts;

  // Bit 6 without a configuration.
  Decoder none(Model::qt128c2x);
  EXPECT_EQ(none.validate(view(q), info), Error::channel_config_required);
  EXPECT_EQ(none.decode(view(q), info, pts), Error::channel_config_required);
  EXPECT_EQ(pts.count, 0u);

  // A configuration of 80 channels for packets of 79 and of 128 units.
  Decoder dec(Model::qt128c2x);
  ASSERT_EQ(dec.set_channel_config(bundled_config()), Error::ok);
  EXPECT_EQ(dec.decode(view(customised(p, 0x5D, 79)), info, pts), Error::channel_config_mismatch);
  auto all_units = p;
  all_units[11] |= 0x40;  // bit 6 with laser num 128
  EXPECT_EQ(dec.decode(view(all_units), info, pts), Error::channel_config_mismatch);
  EXPECT_EQ(none.decode(view(all_units), info, pts), Error::channel_config_required);
  // The configuration applies only to customised packets: the capture's own decode as before.
  EXPECT_EQ(dec.decode(view(p), info, pts), Error::ok);

  // The header: laser num 0 or above 128 with bit 6; not 128 without it.
  auto h = q;
  for (const std::uint8_t lasers : {std::uint8_t{0}, std::uint8_t{129}, std::uint8_t{255}}) {
    h[6] = lasers;
    EXPECT_EQ(identify(view(h), m, k), Error::bad_header) << int(lasers);
    EXPECT_EQ(dec.decode(view(h), info, pts), Error::bad_header) << int(lasers);
  }
  h = q;
  h[11] &= static_cast<std::uint8_t>(~0x40);  // 80 units, no customisation: another model
  EXPECT_EQ(identify(view(h), m, k), Error::unsupported_model);
  h = q;
  h[6] = 81;  // the length no longer follows
  EXPECT_EQ(identify(view(h), m, k), Error::flags_length_mismatch);
}

// set_channel_config() checks a configuration against the model; a refused one changes nothing.
TEST(Qt128ChannelCustomisation, SetterRefusesBadConfigurations) {
  const ChannelConfig good = bundled_config();
  const auto q = customised(qt128_packets().at(0), 0x5D);
  Decoder dec(Model::qt128c2x);
  ASSERT_EQ(dec.set_channel_config(good), Error::ok);
  PacketInfo info;
  PacketPoints pts;
  ASSERT_EQ(dec.decode(view(q), info, pts), Error::ok);
  const std::size_t count = pts.count;

  struct Case {
    const char* what;
    ChannelConfig config;
    Error error;
  };
  std::vector<Case> cases;
  auto with = [&](const char* what, Error e, auto change) {
    ChannelConfig c = good;
    change(c);
    cases.push_back({what, c, e});
  };
  with("LaserNum 0", Error::invalid_argument, [](ChannelConfig& c) { c.laser_num = 0; });
  with("LaserNum 129", Error::invalid_argument, [](ChannelConfig& c) { c.laser_num = 129; });
  with("no loop", Error::invalid_argument, [](ChannelConfig& c) { c.loops = 0; });
  with("three loops", Error::invalid_argument, [](ChannelConfig& c) { c.loops = 3; });
  with("channel 0", Error::invalid_argument, [](ChannelConfig& c) { c.channel[1][5] = 0; });
  with("channel 129", Error::invalid_argument, [](ChannelConfig& c) { c.channel[0][79] = 129; });
  with("a repeated channel", Error::invalid_argument, [](ChannelConfig& c) { c.channel[1][1] = c.channel[1][0]; });
  with("BlockNum 3", Error::channel_config_mismatch, [](ChannelConfig& c) { c.block_num = 3; });
  for (const Case& c : cases) {
    EXPECT_EQ(dec.set_channel_config(c.config), c.error) << c.what;
    ASSERT_EQ(dec.decode(view(q), info, pts), Error::ok) << c.what;
    EXPECT_EQ(pts.count, count) << c.what;  // the earlier configuration still applies
  }
  // A configuration is the QT128's only.
  Decoder p64(Model::pandar64);
  EXPECT_EQ(p64.set_channel_config(good), Error::invalid_argument);
  // And it can be forgotten.
  dec.clear_channel_config();
  EXPECT_EQ(dec.decode(view(q), info, pts), Error::channel_config_required);
}

// ---- 3. QT128 time without a calendar (year byte 0: Unix seconds, big-endian) ----

bool leap(int y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

// Seconds since 1970-01-01 UTC, counting the days year by year and month by month.
std::uint32_t unix_seconds_by_count(int year, int month, int day, int hour, int minute, int second) {
  static const int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  std::int64_t days = 0;
  for (int y = 1970; y < year; ++y) days += leap(y) ? 366 : 365;
  for (int m = 1; m < month; ++m) days += kDays[m - 1] + (m == 2 && leap(year) ? 1 : 0);
  days += day - 1;
  return static_cast<std::uint32_t>(days * 86400 + hour * 3600 + minute * 60 + second);
}

std::uint32_t capture_seconds(const std::vector<std::uint8_t>& p) {
  const std::uint8_t* dt = &p[1076];  // tail 1061 + 15, year - 1900
  return unix_seconds_by_count(1900 + dt[0], dt[1], dt[2], dt[3], dt[4], dt[5]);
}

// Vendor SDK GetMicroLidarTimeU64: a year byte of 0 means bytes 2..5 of the date-time are Unix
// seconds, big-endian. Every capture packet rewritten so gives the original points and times to
// the ns, and its date-time in calendar form.
TEST(Qt128UnixTime, EveryCapturePacketGivesTheOriginalTimes) {
  // Hand-checked: the first packet is 2020-10-09 12:03:29 UTC = 1602245009 (test_golden.cpp).
  EXPECT_EQ(capture_seconds(qt128_packets().at(0)), 1602245009u);
  Decoder dec(Model::qt128c2x);
  for (const auto& p : qt128_packets()) {
    auto q = p;
    qt128_set_unix_time(q, capture_seconds(p));
    ASSERT_EQ(q[1076], 0);
    const Decoded want = decode(dec, p);
    const Decoded got = decode(dec, q);
    ASSERT_EQ(got.error, Error::ok);
    expect_same_info(want.info, got.info);  // time_ns and date_time included
    ASSERT_EQ(got.points.size(), want.points.size());
    for (std::size_t i = 0; i < want.points.size(); ++i) ASSERT_TRUE(same_point(want.points[i], got.points[i], 0));
  }
}

// Hand-checked values of the Unix form: 0x5F805191 = 1602245009 (2020-10-09 12:03:29), the
// largest value 0xFFFFFFFF = 2106-02-07 06:28:15 (python: datetime.utcfromtimestamp(2**32-1)).
TEST(Qt128UnixTime, HandCheckedSeconds) {
  Decoder dec(Model::qt128c2x);
  auto q = qt128_packets().at(0);
  const std::size_t dt = 1076;
  qt128_set_unix_time(q, 0x5F805191u);
  EXPECT_EQ(q[dt + 2], 0x5F);  // big-endian
  EXPECT_EQ(q[dt + 5], 0x91);
  PacketInfo info;
  ASSERT_EQ(dec.validate(view(q), info), Error::ok);
  EXPECT_EQ(info.time_ns, 1602245009LL * 1000000000 + 403019000);  // + the timestamp, 403019 us
  qt128_set_unix_time(q, 0xFFFFFFFFu);
  ASSERT_EQ(dec.validate(view(q), info), Error::ok);
  EXPECT_EQ(info.date_time.year, 2106);
  EXPECT_EQ(info.date_time.month, 2);
  EXPECT_EQ(info.date_time.day, 7);
  EXPECT_EQ(info.date_time.hour, 6);
  EXPECT_EQ(info.date_time.minute, 28);
  EXPECT_EQ(info.date_time.second, 15);
  EXPECT_EQ(info.time_ns, 4294967295LL * 1000000000 + 403019000);
  // Byte 1 (the calendar's month) is not read in this form, as the SDK does not.
  q[dt + 1] = 7;
  qt128_seal(q);
  EXPECT_EQ(dec.validate(view(q), info), Error::ok);
  EXPECT_EQ(info.date_time.year, 2106);
}

// All three QT128 settings at once: 3-byte units, 80 customised channels, Unix seconds.
TEST(Qt128Variants, AllAtOnce) {
  Decoder plain(Model::qt128c2x), custom(Model::qt128c2x);
  ASSERT_EQ(custom.set_channel_config(bundled_config()), Error::ok);
  std::size_t points = 0;
  for (std::size_t i = 0; i < qt128_packets().size(); i += 7) {
    const auto& p = qt128_packets()[i];
    auto q = customised(p, 0x4D);
    qt128_set_unix_time(q, capture_seconds(p));
    const Decoded all = decode(plain, p);
    const Decoded got = decode(custom, q);
    ASSERT_EQ(got.error, Error::ok);
    expect_same_info(all.info, got.info);
    std::size_t k = 0;
    for (const Point& o : all.points) {
      const auto& listed = listed_channels(block_loop(p, o.block));
      if (std::find(listed.begin(), listed.end(), o.channel) == listed.end()) continue;
      ASSERT_LT(k, got.points.size());
      ASSERT_TRUE(same_point(o, got.points[k++], 0));
    }
    EXPECT_EQ(k, got.points.size());
    points += k;
  }
  EXPECT_GT(points, 0u);
}

// ---- 6. Pandar64 nonlinear reflectivity (manual Appendix D) ----

// Entries of the manual's Appendix D table, read by hand: field value -> actual reflectivity %,
// and the integer percentage Point::intensity holds (nearest, halves up; 255 has no value: "-").
struct ReflectivityEntry {
  std::uint8_t field;
  double percent;
  std::uint8_t intensity;
};
const ReflectivityEntry kAppendixD[] = {
    {0, 0.0, 0},     {16, 0.44, 0},    {17, 0.5, 1},     {25, 1.05, 1},    {100, 15.87, 16},
    {113, 20.25, 20}, {177, 49.5, 50}, {200, 63.25, 63}, {251, 99.5, 100}, {252, 132, 132},
    {253, 196, 196}, {254, 242, 242},
};

TEST(Pandar64Reflectivity, ManualTableEntries) {
  for (const ReflectivityEntry& e : kAppendixD)
    EXPECT_DOUBLE_EQ(tables::pandar64_nonlinear_reflectivity_pct[e.field], e.percent) << int(e.field);
}

TEST(Pandar64Reflectivity, NonlinearMappingAppliesToIntensity) {
  const Stamp s;
  auto p = pandar64_packet(0x37, s);
  int channel = 1;
  for (const ReflectivityEntry& e : kAppendixD) pandar64_point(p, 1, channel++, 1000, e.field);
  pandar64_point(p, 1, channel, 1000, 255);
  Decoder dec(Model::pandar64);
  PacketInfo info;
  PacketPoints pts;
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);  // raw by default: the byte as sent
  ASSERT_EQ(pts.count, std::size(kAppendixD) + 1);
  for (std::size_t i = 0; i < std::size(kAppendixD); ++i) EXPECT_EQ(pts.points[i].intensity, kAppendixD[i].field);

  ASSERT_EQ(dec.set_reflectivity(Reflectivity::nonlinear), Error::ok);
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  for (std::size_t i = 0; i < std::size(kAppendixD); ++i)
    EXPECT_EQ(pts.points[i].intensity, kAppendixD[i].intensity) << int(kAppendixD[i].field);
  EXPECT_EQ(pts.points[std::size(kAppendixD)].intensity, 255);  // the manual's "-": left as sent

  ASSERT_EQ(dec.set_reflectivity(Reflectivity::raw), Error::ok);
  ASSERT_EQ(dec.decode(view(p), info, pts), Error::ok);
  EXPECT_EQ(pts.points[4].intensity, 100);
}

// The other manuals give no mapping: nonlinear is refused there, raw accepted.
TEST(Pandar64Reflectivity, OtherModelsRefuseNonlinear) {
  for (const Model m : {Model::pandar40, Model::pandar40p, Model::qt128c2x}) {
    Decoder dec(m);
    EXPECT_EQ(dec.set_reflectivity(Reflectivity::nonlinear), Error::invalid_argument) << model_name(m);
    EXPECT_EQ(dec.set_reflectivity(Reflectivity::raw), Error::ok) << model_name(m);
  }
}

// ---- 7. The Pandar40P/64 year byte ----

// Vendor SDK udp_protocol_p40.h / udp_protocol_p64.h: tm_year = byte, + 100 when byte < 70. The
// manual's year - 2000 for 0..69; years since 1900 from 70 (the Pandar64 capture sends 120 in 2020).
TEST(PandarYearByte, VendorRule) {
  struct Case {
    std::uint8_t byte;
    int year;
  };
  const Case cases[] = {{0, 2000}, {24, 2024}, {69, 2069}, {70, 1970}, {99, 1999}, {120, 2020}, {124, 2024}, {255, 2155}};
  const Stamp s;  // 2024-05-17 08:30:15.25
  for (const bool p64 : {true, false}) {
    auto p = p64 ? pandar64_packet(0x37, s) : pandar40_packet(true, 0x37, s, s.us);
    const std::size_t year_at = p64 ? 1188 : 1256;
    Decoder dec(p64 ? Model::pandar64 : Model::pandar40p);
    for (const Case& c : cases) {
      p[year_at] = c.byte;
      PacketInfo info;
      ASSERT_EQ(dec.validate(view(p), info), Error::ok) << int(c.byte);
      EXPECT_EQ(info.date_time.year, c.year) << int(c.byte);
      EXPECT_EQ(info.time_ns, timegm_utc(c.year, 5, 17, 8, 30, 15) * 1000000000LL + 250000000LL) << int(c.byte);
    }
  }
}

}  // namespace
