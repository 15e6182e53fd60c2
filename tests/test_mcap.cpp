// The MCAP writer and the PointCloud2 encoding (port/), read back by a small parser written here
// from the MCAP specification (tests/mcap_check.h): record structure, offsets and CRCs; the CDR
// bytes checked by hand. The program's MCAP output: test_mcap_cli.cpp; the reference reader
// (npm's @mcap/core) reads the bundled captures' files in tests/mcap/.
#include <gtest/gtest.h>
#include <gtest/gtest-spi.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "hesai_port/formats/mcap.h"
#include "hesai_port/formats/pointcloud2.h"
#include "mcap_check.h"
#include "packet_builder.h"
#include "test_support.h"

using namespace hesai;
using namespace hesai_test;
using hesai::port::crc32_ieee;

namespace {

// The failure messages check_mcap() reports for `b`, one a line; empty when it finds none.
std::string failures_of(const std::vector<std::uint8_t>& b) {
  testing::TestPartResultArray results;
  {
    testing::ScopedFakeTestPartResultReporter reporter(
        testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &results);
    check_mcap(b);
  }
  std::string all;
  for (int i = 0; i < results.size(); ++i) all += std::string(results.GetTestPartResult(i).message()) + "\n";
  return all;
}

TEST(Crc32Ieee, CatalogueCheckValue) {
  // CRC-32/ISO-HDLC ("CRC-32", zlib) of "123456789": 0xCBF43926 (the CRC catalogue).
  EXPECT_EQ(crc32_ieee("123456789", 9), 0xCBF43926u);
  EXPECT_EQ(crc32_ieee("", 0), 0u);
  // "The quick brown fox jumps over the lazy dog": 0x414FA339 (zlib's crc32 of it).
  EXPECT_EQ(crc32_ieee("The quick brown fox jumps over the lazy dog", 43), 0x414FA339u);
}

TEST(Crc32Ieee, SplitAtEveryOffsetAndCombined) {
  const char* text = "123456789";
  for (std::size_t k = 0; k <= 9; ++k) {
    EXPECT_EQ(crc32_ieee(text + k, 9 - k, crc32_ieee(text, k)), 0xCBF43926u) << k;
    EXPECT_EQ(port::crc32_ieee_combine(crc32_ieee(text, k), crc32_ieee(text + k, 9 - k), 9 - k), 0xCBF43926u) << k;
  }
  std::vector<std::uint8_t> big(3000001);
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<std::uint8_t>(i * 7 + (i >> 9));
  const std::uint32_t whole = crc32_ieee(big.data(), big.size());
  for (const std::size_t k : {std::size_t{1}, std::size_t{4096}, std::size_t{1234567}}) {
    const std::uint32_t a = crc32_ieee(big.data(), k), c = crc32_ieee(big.data() + k, big.size() - k);
    EXPECT_EQ(port::crc32_ieee_combine(a, c, big.size() - k), whole) << k;
  }
}

TEST(McapWriter, RecordsOffsetsAndCrcsOfChunkedMessages) {
  const std::string path = temp_path("hesai_test_writer.mcap");
  port::McapWriter w;
  ASSERT_TRUE(w.open(path, "ros2", "test"));
  const std::uint16_t s = w.add_schema("pkg/msg/Thing", "ros2msg", "uint8 a\n");
  const std::uint16_t c = w.add_channel(s, "/thing", "cdr", {{"k", "v"}});
  // 5 messages of 400 000 bytes: a chunk closes once its records reach 1 MiB, so after the third
  // message (1 200 000 + records) and at the end: two chunks.
  std::vector<std::vector<std::uint8_t>> sent;
  for (std::uint32_t i = 0; i < 5; ++i) {
    std::vector<std::uint8_t> m(400000);
    for (std::size_t k = 0; k < m.size(); ++k) m[k] = static_cast<std::uint8_t>(k * (i + 3));
    const std::uint64_t t = 1000 + 10 * i;
    if (i % 2 == 0) {
      ASSERT_TRUE(w.write_message(c, i, t, t, m.data(), m.size()));
    } else {  // in pieces
      ASSERT_TRUE(w.begin_message(c, i, t, t, m.size()));
      ASSERT_TRUE(w.append(m.data(), 123));
      ASSERT_TRUE(w.append(m.data() + 123, m.size() - 123));
      ASSERT_TRUE(w.end_message());
    }
    sent.push_back(m);
  }
  ASSERT_TRUE(w.close());
  const std::vector<std::uint8_t> b = hesai_test::read_file(path);
  const Parsed p = check_mcap(b);
  EXPECT_EQ(p.profile, "ros2");
  EXPECT_EQ(p.chunks, 2u);
  ASSERT_EQ(p.messages.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(p.messages[i].first, 1000 + 10 * i);
    EXPECT_TRUE(p.messages[i].second == sent[i]) << i;
  }
  // Statistics: 5 messages, 1 schema, 1 channel, 2 chunks, times 1000..1040.
  for (const Record& r : p.summary) {
    if (r.op != 0x0B) continue;
    EXPECT_EQ(le(b, r.body, 8), 5u);
    EXPECT_EQ(le(b, r.body + 8, 2), 1u);
    EXPECT_EQ(le(b, r.body + 10, 4), 1u);
    EXPECT_EQ(le(b, r.body + 22, 4), 2u);
    EXPECT_EQ(le(b, r.body + 26, 8), 1000u);
    EXPECT_EQ(le(b, r.body + 34, 8), 1040u);
  }
  std::remove(path.c_str());
}

TEST(McapWriter, TheCheckerCatchesAFlippedByte) {
  const std::string path = temp_path("hesai_test_writer_flip.mcap");
  port::McapWriter w;
  ASSERT_TRUE(w.open(path, "ros2", "test"));
  const std::uint16_t c = w.add_channel(0, "/x", "cdr", {});
  ASSERT_TRUE(w.write_message(c, 0, 5, 5, "abcdefgh", 8));
  ASSERT_TRUE(w.close());
  std::vector<std::uint8_t> b = hesai_test::read_file(path);
  EXPECT_EQ(failures_of(b), "");
  // The message's last byte: the chunk's CRC and the data section's no longer match.
  std::size_t at = 0;
  for (std::size_t i = 0; i + 8 <= b.size(); ++i)
    if (std::memcmp(b.data() + i, "abcdefgh", 8) == 0) at = i + 7;
  ASSERT_NE(at, 0u);
  b[at] ^= 1;
  std::string f = failures_of(b);
  EXPECT_NE(f.find("chunk at"), std::string::npos) << f;
  EXPECT_NE(f.find("data_section_crc"), std::string::npos) << f;
  b[at] ^= 1;
  b[b.size() - 8 - 1] ^= 1;  // the footer's summary_crc
  f = failures_of(b);
  EXPECT_NE(f.find("summary_crc"), std::string::npos) << f;
  EXPECT_EQ(f.find("chunk at"), std::string::npos) << f;
  std::remove(path.c_str());
}

TEST(McapWriter, MessageSizeMustMatchAndPipesAreRefused) {
  const std::string path = temp_path("hesai_test_writer_bad.mcap");
  port::McapWriter w;
  ASSERT_TRUE(w.open(path, "ros2", "test"));
  const std::uint16_t c = w.add_channel(0, "/x", "cdr", {});
  ASSERT_TRUE(w.begin_message(c, 0, 1, 1, 10));
  EXPECT_FALSE(w.append("0123456789ab", 12));
  EXPECT_FALSE(w.close());
  std::remove(path.c_str());
  // Chunk headers are rewritten in place: a pipe cannot hold an MCAP file.
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  port::McapWriter piped;
  const port::WriteResult r = piped.open("/dev/fd/" + std::to_string(fds[1]), "ros2", "test");
  EXPECT_FALSE(r);
  EXPECT_EQ(r.os_error(), ESPIPE);
  close(fds[0]);
  close(fds[1]);
}

TEST(PointCloud2, HeadBytesCheckedByHand) {
  // stamp 1 700 000 000.123456789 s, frame "hesai", 2 points.
  const std::vector<std::uint8_t> h = port::pointcloud2_head(1700000000123456789, "hesai", 2);
  // Offsets after the 4-byte encapsulation (CDR alignment counts from there): stamp.sec 0,
  // nanosec 4, frame_id length 8 ("hesai" + NUL = 6) and bytes 12..17, pad to 20: height 20,
  // width 24, field count 28; ten fields of 16 + (name + NUL rounded up to 4) bytes each, names
  // x y z (4 each) intensity 12 return_type 12 channel 8 azimuth 8 elevation 12 distance 12
  // time_stamp 12: 248 bytes from 32 to 280; is_bigendian 280, pad, point_step 284, row_step 288,
  // data length 292; data from 296: 300 bytes with the encapsulation.
  ASSERT_EQ(h.size(), 300u);
  const std::uint8_t enc[4] = {0, 1, 0, 0};
  EXPECT_EQ(0, std::memcmp(h.data(), enc, 4));
  EXPECT_EQ(le(h, 4 + 0, 4), 1700000000u);
  EXPECT_EQ(le(h, 4 + 4, 4), 123456789u);
  EXPECT_EQ(le(h, 4 + 8, 4), 6u);
  EXPECT_EQ(0, std::memcmp(h.data() + 4 + 12, "hesai", 6));
  EXPECT_EQ(le(h, 4 + 20, 4), 1u);
  EXPECT_EQ(le(h, 4 + 24, 4), 2u);
  EXPECT_EQ(le(h, 4 + 28, 4), 10u);
  // The first field: "x", offset 0, FLOAT32 (7), count 1.
  EXPECT_EQ(le(h, 4 + 32, 4), 2u);
  EXPECT_EQ(h[4 + 36], 'x');
  EXPECT_EQ(le(h, 4 + 40, 4), 0u);
  EXPECT_EQ(h[4 + 44], 7);
  EXPECT_EQ(le(h, 4 + 48, 4), 1u);
  // The last field, time_stamp (28 bytes, 252..280): name length 11 at 252, name at 256, offset 28
  // at 268, UINT32 (6) at 272, count 1 at 276.
  EXPECT_EQ(le(h, 4 + 252, 4), 11u);
  EXPECT_EQ(0, std::memcmp(h.data() + 4 + 256, "time_stamp", 11));
  EXPECT_EQ(le(h, 4 + 280 - 12, 4), 28u);
  EXPECT_EQ(h[4 + 280 - 8], 6);
  EXPECT_EQ(le(h, 4 + 280 - 4, 4), 1u);
  EXPECT_EQ(h[4 + 280], 0);  // is_bigendian
  EXPECT_EQ(le(h, 4 + 284, 4), 32u);
  EXPECT_EQ(le(h, 4 + 288, 4), 64u);
  EXPECT_EQ(le(h, 4 + 292, 4), 64u);
  EXPECT_EQ(port::pointcloud2_size(h.size(), 2), 300u + 64 + 1);
}

TEST(PointCloud2, PointRecordCheckedByHand) {
  Point p;
  p.x = 1.5f;            // 0x3FC00000
  p.y = -2.0f;           // 0xC0000000
  p.z = 0.25f;           // 0x3E800000
  p.intensity = 200;
  p.return_index = 1;
  p.channel = 5;         // nebula's 0-based channel 4
  p.azimuth_deg = 180;   // pi as float32: 0x40490FDB
  p.elevation_deg = 90;  // pi/2: 0x3FC90FDB
  p.distance_m = 8.0f;   // 0x41000000
  p.time_ns = 1000000000 + 70000;
  std::uint8_t r[32];
  port::encode_point(p, port::NebulaReturnType::last_strongest, 1000000000, r);
  const std::vector<std::uint8_t> v(r, r + 32);
  EXPECT_EQ(le(v, 0, 4), 0x3FC00000u);
  EXPECT_EQ(le(v, 4, 4), 0xC0000000u);
  EXPECT_EQ(le(v, 8, 4), 0x3E800000u);
  EXPECT_EQ(v[12], 200);
  EXPECT_EQ(v[13], 10);  // nebula's LAST_STRONGEST, as given (not the return_index)
  EXPECT_EQ(le(v, 14, 2), 4u);
  EXPECT_EQ(le(v, 16, 4), 0x40490FDBu);
  EXPECT_EQ(le(v, 20, 4), 0x3FC90FDBu);
  EXPECT_EQ(le(v, 24, 4), 0x41000000u);
  EXPECT_EQ(le(v, 28, 4), 70000u);
}

// PointCloud2Data encodes each point as it comes, before the message's stamp (its earliest point)
// is known; finish() gives every record's time_stamp from that stamp, clamped to 32 bits.
namespace {
Point timed(std::int64_t t, std::uint8_t channel) {
  Point p;
  p.x = 1.5f;
  p.channel = channel;
  p.azimuth_deg = 180;
  p.time_ns = t;
  return p;
}
// time_stamp of each record of `d` after finish().
std::vector<std::uint64_t> time_stamps(port::PointCloud2Data& d) {
  const std::uint8_t* b = d.finish();
  const std::vector<std::uint8_t> v(b, b + d.size() * port::kPointStep);
  std::vector<std::uint64_t> t;
  for (std::size_t i = 0; i < d.size(); ++i) t.push_back(le(v, i * port::kPointStep + 28, 4));
  return t;
}
}  // namespace

TEST(PointCloud2, DataTimesFromTheEarliestPointWhereverItComes) {
  const std::int64_t t0 = 1700000000000000000;
  port::PointCloud2Data d;
  const Point first[] = {timed(t0 + 1000, 1), timed(t0 + 1500, 2)};
  const port::NebulaReturnType types[] = {port::NebulaReturnType::last, port::NebulaReturnType::strongest};
  d.add(first, types, 2);
  const Point later[] = {timed(t0 + 900, 3)};  // earlier than every point before it: the stamp
  d.add(later, nullptr, 1);
  EXPECT_EQ(d.size(), 3u);
  EXPECT_EQ(d.stamp_ns(), t0 + 900);
  (void)d.finish(1);  // in pieces: the first record, then the rest
  EXPECT_EQ(time_stamps(d), (std::vector<std::uint64_t>{100, 600, 0}));
  // The other fields as encode_point writes them; no type given: unknown (0).
  const std::uint8_t* b = d.finish();
  EXPECT_EQ(b[13], 1);   // LAST
  EXPECT_EQ(b[32 + 13], 3);  // STRONGEST
  EXPECT_EQ(b[64 + 13], 0);
  EXPECT_EQ(b[64 + 14], 2);  // channel 3, 0-based
  std::uint8_t r[32];
  port::encode_point(later[0], port::NebulaReturnType::unknown, t0 + 900, r);
  EXPECT_EQ(std::memcmp(b + 64, r, 32), 0);
  EXPECT_EQ(time_stamps(d), (std::vector<std::uint64_t>{100, 600, 0}));  // finish() twice: the same

  d.clear();  // the storage stays; the times start over
  const Point one[] = {timed(t0 - 5, 4), timed(t0 - 7, 4)};
  d.add(one, nullptr, 2);
  EXPECT_EQ(d.stamp_ns(), t0 - 7);
  EXPECT_EQ(time_stamps(d), (std::vector<std::uint64_t>{2, 0}));
}

TEST(PointCloud2, DataTimesSpanningSecondsClampAt32Bits) {
  const std::int64_t t0 = 1700000000000000000;
  port::PointCloud2Data d;
  // 1.5 s apart, then 3 s after the first (a span of 2^31 ns and more: the times are kept), then
  // 2 s before it: the stamp. 5 s after the stamp does not fit 32 bits: 2^32 - 1.
  const Point a[] = {timed(t0, 1), timed(t0 + 1500000000, 1)};
  const Point b[] = {timed(t0 + 3000000000, 1)};
  const Point c[] = {timed(t0 - 2000000000, 1), timed(t0 + 250, 1)};
  d.add(a, nullptr, 2);
  d.add(b, nullptr, 1);
  d.add(c, nullptr, 2);
  EXPECT_EQ(d.stamp_ns(), t0 - 2000000000);
  (void)d.finish(2);
  EXPECT_EQ(time_stamps(d), (std::vector<std::uint64_t>{2000000000, 3500000000, 0xFFFFFFFFu, 0, 2000000250}));
}

TEST(PointCloud2, DefinitionAsRosbag2WritesIt) {
  const std::string& d = port::pointcloud2_definition();
  const std::string rule = "\n" + std::string(80, '=') + "\nMSG: ";
  EXPECT_EQ(d.rfind("# This message holds a collection of N-dimensional points", 0), 0u);
  const std::size_t pf = d.find(rule + "sensor_msgs/PointField\n");
  const std::size_t hd = d.find(rule + "std_msgs/Header\n");
  const std::size_t tm = d.find(rule + "builtin_interfaces/Time\n");
  ASSERT_NE(pf, std::string::npos);
  ASSERT_NE(hd, std::string::npos);
  ASSERT_NE(tm, std::string::npos);
  EXPECT_LT(pf, hd);
  EXPECT_LT(hd, tm);
  // The definition's fields, as the .msg files declare them.
  for (const char* line : {"\nstd_msgs/Header header\n", "\nPointField[] fields\n", "\nuint8[] data ",
                           "\nuint8 FLOAT32 = 7\n", "\nbuiltin_interfaces/Time stamp\n", "\nuint32 nanosec\n"})
    EXPECT_NE(d.find(line), std::string::npos) << line;
}


// nebula's ReturnType values (tier4/nebula nebula_core_common/nebula_common.hpp, enum ReturnType:
// UNKNOWN, LAST, FIRST, STRONGEST, FIRST_WEAK, LAST_WEAK, IDENTICAL, SECOND, SECONDSTRONGEST,
// FIRST_STRONGEST, LAST_STRONGEST from 0), written out here as numbers.
constexpr unsigned kUnknown = 0, kLast = 1, kFirst = 2, kStrongest = 3, kIdentical = 6, kSecond = 7,
                   kSecondStrongest = 8, kFirstStrongest = 9, kLastStrongest = 10;

unsigned nebula(Model m, std::uint8_t mode, std::uint8_t index, bool identical = false, bool weaker = false) {
  return static_cast<unsigned>(port::nebula_return_type(m, mode, index, identical, weaker));
}

// The table of docs/CLI.md (MCAP), row by row: the mode bytes of the manuals (Pandar64 3.1.2.2
// and 3.1.2.3; QT128C2X 3.1.2.2 "Return Mode field / Block 1 / Block 2", 3.1.2 Tail) and the
// labels of nebula's hesai_sensor.hpp get_return_type, pandar_xt16.hpp, pandar_xt32.hpp.
TEST(NebulaReturnType, TableByHand) {
  // Single return: one label per mode, whatever the reflectivity.
  EXPECT_EQ(nebula(Model::qt128c2x, 0x33, 0), kFirst);
  EXPECT_EQ(nebula(Model::qt128c2x, 0x34, 0), kSecond);
  EXPECT_EQ(nebula(Model::pandar64, 0x37, 0), kStrongest);
  EXPECT_EQ(nebula(Model::pandar64, 0x38, 0), kLast);
  EXPECT_EQ(nebula(Model::pandar40, 0x37, 0), kStrongest);
  EXPECT_EQ(nebula(Model::pandar40p, 0x38, 0), kLast);
  // 0x39 last (block 1), strongest (block 2): "If the last return is also the strongest, then the
  // even-numbered block stores the second strongest return".
  EXPECT_EQ(nebula(Model::pandar64, 0x39, 0, false, false), kLastStrongest);
  EXPECT_EQ(nebula(Model::pandar64, 0x39, 0, false, true), kLast);
  EXPECT_EQ(nebula(Model::pandar64, 0x39, 1, false, false), kStrongest);
  EXPECT_EQ(nebula(Model::pandar64, 0x39, 1, false, true), kSecondStrongest);
  EXPECT_EQ(nebula(Model::pandar64, 0x39, 0, true, false), kIdentical);
  EXPECT_EQ(nebula(Model::pandar64, 0x39, 1, true, false), kIdentical);
  // 0x3A first, second; 0x3E strongest, second strongest.
  EXPECT_EQ(nebula(Model::qt128c2x, 0x3A, 0), kFirst);
  EXPECT_EQ(nebula(Model::qt128c2x, 0x3A, 1), kSecond);
  EXPECT_EQ(nebula(Model::qt128c2x, 0x3E, 0), kStrongest);
  EXPECT_EQ(nebula(Model::qt128c2x, 0x3E, 1), kSecondStrongest);
  EXPECT_EQ(nebula(Model::qt128c2x, 0x3E, 1, true), kIdentical);
  // 0x3B first, last; the XT16 and XT32 send last in block 1 (nebula swaps the two for them).
  EXPECT_EQ(nebula(Model::qt128c2x, 0x3B, 0), kFirst);
  EXPECT_EQ(nebula(Model::qt128c2x, 0x3B, 1), kLast);
  EXPECT_EQ(nebula(Model::pandar_qt64, 0x3B, 0), kFirst);
  EXPECT_EQ(nebula(Model::pandar_xt32m2x, 0x3B, 1), kLast);
  EXPECT_EQ(nebula(Model::pandar_xt16, 0x3B, 0), kLast);
  EXPECT_EQ(nebula(Model::pandar_xt16, 0x3B, 1), kFirst);
  EXPECT_EQ(nebula(Model::pandar_xt32, 0x3B, 0), kLast);
  EXPECT_EQ(nebula(Model::pandar_xt32, 0x3B, 1), kFirst);
  EXPECT_EQ(nebula(Model::pandar_xt32, 0x3B, 1, true), kIdentical);
  // 0x3C first, strongest.
  EXPECT_EQ(nebula(Model::pandar_xt32m2x, 0x3C, 0, false, false), kFirstStrongest);
  EXPECT_EQ(nebula(Model::pandar_xt32m2x, 0x3C, 0, false, true), kFirst);
  EXPECT_EQ(nebula(Model::pandar_xt32m2x, 0x3C, 1, false, false), kStrongest);
  EXPECT_EQ(nebula(Model::pandar_xt32m2x, 0x3C, 1, false, true), kSecondStrongest);
  // 0x3D triple: first, last, strongest.
  EXPECT_EQ(nebula(Model::pandar_xt32m2x, 0x3D, 0), kFirst);
  EXPECT_EQ(nebula(Model::pandar_xt32m2x, 0x3D, 1), kLast);
  EXPECT_EQ(nebula(Model::pandar_xt32m2x, 0x3D, 2, false, true), kStrongest);
  EXPECT_EQ(nebula(Model::pandar_xt32m2x, 0x3D, 2, true), kIdentical);
  // A byte no manual names.
  EXPECT_EQ(nebula(Model::pandar64, 0x00, 0), kUnknown);
  EXPECT_EQ(nebula(Model::pandar64, 0x3F, 1, true), kUnknown);
}

// The points of one packet with their nebula ReturnType, as the hesai program labels them.
struct Labelled {
  std::vector<Point> points;
  std::vector<unsigned> types;
  unsigned of(std::size_t block, std::size_t channel) const {
    for (std::size_t i = 0; i < points.size(); ++i)
      if (points[i].block == block && points[i].channel == channel) return types[i];
    ADD_FAILURE() << "no point at block " << block << " channel " << channel;
    return 99;
  }
  bool has(std::size_t block, std::size_t channel) const {
    for (const Point& p : points)
      if (p.block == block && p.channel == channel) return true;
    return false;
  }
};
Labelled label(const std::vector<std::uint8_t>& payload, Model model = Model::pandar64,
               ReturnComparison* compared = nullptr) {
  Decoder dec(model);
  PacketInfo info;
  PacketPoints pts;
  UnitScan scan;
  ReturnComparison compare;
  Labelled out;
  EXPECT_EQ(dec.decode(view(payload), info, pts, scan, compare), Error::ok);
  if (compared != nullptr) *compared = compare;
  for (const Point& p : pts) {
    out.points.push_back(p);
    out.types.push_back(static_cast<unsigned>(port::nebula_return_type(info, compare, p)));
  }
  return out;
}

// pandar64_dual.pcap, return mode 0x39 (the tail byte at 1186: Pandar64 manual 3.1.2.3). Units
// read from the capture's bytes (block, 1-based channel: distance, reflectivity), labels by the
// table: blocks 1 and 2 of a firing are the returns of one firing (3.1.2.2).
TEST(NebulaReturnType, Pandar64DualCaptureByHand) {
  const auto packets = pcap_payloads("pandar64_dual.pcap");
  ASSERT_GT(packets.size(), 84u);
  ASSERT_EQ(packets[0][1186], 0x39);
  const Labelled p0 = label(packets[0]);
  // Packet 0, blocks 0/1, channel 1: (173, 0) and (173, 0): one echo sent twice, both IDENTICAL.
  EXPECT_EQ(p0.of(0, 1), kIdentical);
  EXPECT_EQ(p0.of(1, 1), kIdentical);
  // Channel 20: last (539, 2), strongest block (112, 0): the last reflects more, so it is the
  // strongest too and block 2 holds the second strongest.
  EXPECT_EQ(p0.of(0, 20), kLastStrongest);
  EXPECT_EQ(p0.of(1, 20), kSecondStrongest);
  // Blocks 4/5, channel 25: (529, 0) and (133, 0): equal reflectivity, both count as strongest.
  EXPECT_EQ(p0.of(4, 25), kLastStrongest);
  EXPECT_EQ(p0.of(5, 25), kStrongest);
  // Packet 1, blocks 0/1, channel 26: (535, 0) and (0, 0): block 2 has no return and no point;
  // the last is not weaker (0 vs 0), and not identical (the distances differ).
  const Labelled p1 = label(packets[1]);
  EXPECT_EQ(p1.of(0, 26), kLastStrongest);
  EXPECT_FALSE(p1.has(1, 26));
  // Packet 84, blocks 0/1, channel 11: (673, 0) and (423, 4): block 2 reflects more.
  const Labelled p84 = label(packets[84]);
  EXPECT_EQ(p84.of(0, 11), kLast);
  EXPECT_EQ(p84.of(1, 11), kStrongest);
}

// The same packet sent in a single-return mode (the tail byte set to 0x37, then 0x38): every
// block is a firing of its own, every point STRONGEST, then LAST (Pandar64 manual 3.1.2.3).
// The per-packet table (PacketReturnTypes) gives what nebula_return_type gives, for every model,
// every return-mode byte, return index and comparison.
TEST(NebulaReturnType, PacketTableIsTheFunction) {
  ReturnComparison compare;
  compare.identical[1][0] = 0x05;  // block 1: channels 1 and 3 identical
  compare.weaker[1][0] = 0x06;     // channels 2 and 3 weaker
  compare.weaker[3][1] = 0x01;     // block 3: channel 9 weaker
  int checked = 0;
  for (std::size_t m = 0; m < kModelCount; ++m) {
    for (int mode = 0; mode < 256; ++mode) {
      PacketInfo info;
      info.model = static_cast<Model>(m);
      info.return_mode = static_cast<std::uint8_t>(mode);
      const port::PacketReturnTypes table(info);
      for (std::uint8_t block = 0; block < 4; ++block) {
        for (std::uint8_t index = 0; index < 6; ++index) {
          // A block's points (channel 0: none, as channel 1; 200: beyond every model), and one of
          // another block among them: of_block() gives each what the function gives.
          std::vector<Point> points;
          for (const int channel : {0, 1, 2, 3, 4, 9, 10, 200}) {
            Point p;
            p.block = block;
            p.channel = static_cast<std::uint8_t>(channel);
            p.return_index = index;
            points.push_back(p);
          }
          points[5].block = static_cast<std::uint8_t>(block ^ 1);
          std::vector<port::NebulaReturnType> types(points.size());
          table.of_block(compare, points.data(), points.size(), types.data());
          for (std::size_t i = 0; i < points.size(); ++i) {
            const port::NebulaReturnType want = port::nebula_return_type(info, compare, points[i]);
            ASSERT_EQ(table(compare, points[i]), want) << "model " << m << " mode " << mode << " block " << int(block)
                                                       << " channel " << int(points[i].channel) << " index " << int(index);
            ASSERT_EQ(types[i], want) << "of_block: model " << m << " mode " << mode << " block " << int(block)
                                      << " point " << i << " index " << int(index);
            ++checked;
          }
        }
      }
    }
  }
  EXPECT_EQ(checked, static_cast<int>(kModelCount) * 256 * 4 * 6 * 8);
}

TEST(NebulaReturnType, Pandar64SingleReturnByHand) {
  const auto packets = pcap_payloads("pandar64_dual.pcap");
  ASSERT_FALSE(packets.empty());
  for (const auto& [mode, want] : {std::pair<std::uint8_t, unsigned>{0x37, kStrongest}, {0x38, kLast}}) {
    std::vector<std::uint8_t> p = packets[0];
    p[1186] = mode;
    const Labelled l = label(p);
    ASSERT_FALSE(l.points.empty());
    for (std::size_t i = 0; i < l.points.size(); ++i) {
      EXPECT_EQ(l.points[i].return_index, 0);
      EXPECT_EQ(l.types[i], want) << "block " << int{l.points[i].block} << " channel " << int{l.points[i].channel};
    }
    EXPECT_EQ(l.of(0, 1), want);  // identical to block 1's unit, but single return: no IDENTICAL
  }
}

// Equal distance is not enough: nebula's hesai_sensor.hpp (is_duplicate) calls a return a
// duplicate, IDENTICAL, only when both its distance and its reflectivity equal another return's
// of the firing; otherwise the mode's label (0x39: is_strongest, "no other reflects more"). Packet
// 0 of qt128c2x_dual.pcap (return mode 0x39 at tail + 12, QT128C2X manual 3.1.2 Tail; 4-byte
// units, flags 0x1D) with block 2's units rewritten to the distance of block 1's and another
// reflectivity, re-sealed (CRC1 over the body; the signature is not checked without a key).
TEST(NebulaReturnType, Qt128EqualDistanceOtherReflectivityIsNotIdentical) {
  const auto packets = pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_FALSE(packets.empty());
  std::vector<std::uint8_t> p = packets[0];
  const QtOffsets o = qt128_offsets(p);
  ASSERT_EQ(o.unit, 4u);
  ASSERT_EQ(p[o.tail + 12], 0x39);
  // The capture's units (block, 1-based channel: distance, reflectivity), read from its bytes:
  // channel 1 (31, 2) and (31, 2); channel 6 (40, 41) and (40, 41); channel 7 (49, 44) and (49, 44).
  auto unit = [&](int block, int channel) {
    const std::size_t at = 12 + o.block * static_cast<std::size_t>(block - 1) + 2 + o.unit * static_cast<std::size_t>(channel - 1);
    return std::make_pair(unsigned{load_le16(&p[at])}, unsigned{p[at + 2]});
  };
  for (int b = 1; b <= 2; ++b) {
    EXPECT_EQ(unit(b, 1), std::make_pair(31u, 2u));
    EXPECT_EQ(unit(b, 6), std::make_pair(40u, 41u));
    EXPECT_EQ(unit(b, 7), std::make_pair(49u, 44u));
  }
  // Channel 6: block 2 reflects 20, block 1 (41) more. Channel 7: block 2 reflects 90, more than
  // block 1 (44). Same distances, so neither pair is IDENTICAL. Channel 1 left as sent: IDENTICAL.
  qt128_point(p, 2, 6, 40, 20);
  qt128_point(p, 2, 7, 49, 90);
  qt128_seal(p);
  ReturnComparison compare;
  const Labelled l = label(p, Model::qt128c2x, &compare);
  // The rewritten units are those of the points (intensity the raw reflectivity).
  for (const auto& [block, channel, refl] : {std::tuple<std::size_t, std::size_t, unsigned>{0, 6, 41}, {1, 6, 20}, {0, 7, 44}, {1, 7, 90}})
    for (std::size_t i = 0; i < l.points.size(); ++i) {
      if (l.points[i].block == block && l.points[i].channel == channel) {
        EXPECT_EQ(l.points[i].intensity, refl);
      }
    }
  // ReturnComparison (0-based channels): identical only for channel 1.
  EXPECT_TRUE(compare.is_identical(0, 0));
  EXPECT_TRUE(compare.is_identical(1, 0));
  EXPECT_FALSE(compare.is_identical(0, 5)) << "equal distance, reflectivity 41 vs 20";
  EXPECT_FALSE(compare.is_identical(1, 5)) << "equal distance, reflectivity 20 vs 41";
  EXPECT_FALSE(compare.is_identical(0, 6)) << "equal distance, reflectivity 44 vs 90";
  EXPECT_FALSE(compare.is_identical(1, 6)) << "equal distance, reflectivity 90 vs 44";
  EXPECT_FALSE(compare.is_weaker(0, 5));
  EXPECT_TRUE(compare.is_weaker(1, 5));
  EXPECT_TRUE(compare.is_weaker(0, 6));
  EXPECT_FALSE(compare.is_weaker(1, 6));
  // nebula's labels, by hand (0x39: block 1 last, block 2 strongest).
  EXPECT_EQ(l.of(0, 1), kIdentical);
  EXPECT_EQ(l.of(1, 1), kIdentical);
  EXPECT_EQ(l.of(0, 6), kLastStrongest) << "the last return reflects more: it is the strongest too";
  EXPECT_EQ(l.of(1, 6), kSecondStrongest);
  EXPECT_EQ(l.of(0, 7), kLast);
  EXPECT_EQ(l.of(1, 7), kStrongest);
}

}  // namespace
