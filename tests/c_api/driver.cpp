// The C interface against the C++ one: the C functions of test_c_api.c (compiled as C99) decode
// the bundled captures, and every packet's fields and every point must equal, member for member,
// what hesai::Decoder gives for the same bytes and calibration. Then the C checks of errors, keys,
// GPS time and calibration, and the C compiler's view of the structs' layout.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "../packet_builder.h"
#include "../test_support.h"
#include "c_api_test.h"
#include "hesai/calibration.h"
#include "hesai/decoder.h"
#include "hesai/gps.h"
#include "hesai/health.h"

using namespace hesai;
using namespace hesai_test;

namespace {

struct Capture {
  Model model;
  const char* file;
  const char* angles;
  const char* firetimes;
};
const Capture kCaptures[] = {
    {Model::pandar40p, "pandar40p_dual.pcap", "calibration/pandar40p_unit_a_angles.csv", "calibration/pandar40p_firetimes.csv"},
    {Model::pandar64, "pandar64_dual.pcap", "calibration/pandar64_unit_a_angles.csv", "calibration/pandar64_firetimes.csv"},
    {Model::qt128c2x, "qt128c2x_dual.pcap", "calibration/qt128c2x_unit_a_angles.csv", "calibration/qt128c2x_firetimes.csv"},
    {Model::pandar_qt64, "pandar_qt64.pcap", "calibration/pandar_qt64_angles.csv", "calibration/pandar_qt64_firetimes.csv"},
    {Model::pandar_xt16, "pandar_xt16.pcap", "calibration/pandar_xt16_angles.csv", "calibration/pandar_xt16_firetimes.csv"},
    {Model::pandar_xt32, "pandar_xt32.pcap", "calibration/pandar_xt32_angles.csv", "calibration/pandar_xt32_firetimes.csv"},
    {Model::pandar_xt32m2x, "pandar_xt32m2x.pcap", "calibration/pandar_xt32m2x_angles.csv",
     "calibration/pandar_xt32m2x_firetimes.csv"},
};

hesai_model c_model(Model m) { return static_cast<hesai_model>(m); }

// A C++ decoder with the capture's calibration files, parsed by the library.
Decoder cpp_decoder(const Capture& c) {
  Decoder d(c.model);
  AngleCorrection angles;
  FiretimeCorrection firetimes;
  EXPECT_EQ(parse_angle_csv(view(read_file(data_path(c.angles))), channel_count(c.model), angles).error, Error::ok);
  EXPECT_EQ(parse_firetime_csv(view(read_file(data_path(c.firetimes))), channel_count(c.model), firetimes).error,
            Error::ok);
  EXPECT_EQ(d.set_angles(angles), Error::ok);
  EXPECT_EQ(d.set_firetimes(firetimes), Error::ok);
  return d;
}

// Every member of the C structs equals the C++ member of the same name, as
// hesai/packet_info_list.h lists them (the list that declares the C structs and that the library
// copies by): a member cannot be left out of the comparison.
#define HESAI_EXPECT_FIELD(type, name) EXPECT_EQ(c.name, static_cast<type>(i.name)) << "packet " << n << ": " #name;
#define HESAI_EXPECT_ARRAY(type, name, count)                                                             \
  ASSERT_EQ(i.name.size(), std::size_t{count});                                                           \
  for (std::size_t k = 0; k < (count); ++k)                                                               \
    EXPECT_EQ(c.name[k], static_cast<type>(i.name[k])) << "packet " << n << ": " #name "[" << k << "]";
#define HESAI_EXPECT_NESTED(type, name, list) expect_same_info(c.name, i.name, n);
void expect_same_info(const hesai_date_time& c, const hesai::DateTime& i, std::size_t n) {
  HESAI_DATE_TIME_LIST(HESAI_EXPECT_FIELD)
}
void expect_same_info(const hesai_functional_safety& c, const hesai::FunctionalSafety& i, std::size_t n) {
  HESAI_FUNCTIONAL_SAFETY_LIST(HESAI_EXPECT_FIELD)
}
void expect_same_info(const hesai_packet_info& c, const PacketInfo& i, std::size_t n) {
  HESAI_PACKET_INFO_LIST(HESAI_EXPECT_FIELD, HESAI_EXPECT_ARRAY, HESAI_EXPECT_NESTED)
}
#undef HESAI_EXPECT_FIELD
#undef HESAI_EXPECT_ARRAY
#undef HESAI_EXPECT_NESTED

// Exactly the same values: the same computation, so not even a rounding apart.
::testing::AssertionResult same_point(const hesai_point& c, const Point& w) {
#define HESAI_SAME(m) \
  if (!(c.m == w.m)) return ::testing::AssertionFailure() << #m << ": C " << +c.m << ", C++ " << +w.m;
  HESAI_SAME(x) HESAI_SAME(y) HESAI_SAME(z) HESAI_SAME(distance_m) HESAI_SAME(azimuth_deg) HESAI_SAME(elevation_deg)
  HESAI_SAME(time_ns) HESAI_SAME(intensity) HESAI_SAME(channel) HESAI_SAME(return_index) HESAI_SAME(confidence)
  HESAI_SAME(block)
#undef HESAI_SAME
  return ::testing::AssertionSuccess();
}

// Every packet of `packets` through the C test's decoder (already set up) and through `cpp`:
// the same error, fields and points. Returns the points compared.
std::size_t expect_same_decoding(const std::vector<std::vector<std::uint8_t>>& packets, Decoder& cpp) {
  PacketPoints want;
  PacketInfo want_info;
  std::size_t compared = 0;
  for (std::size_t n = 0; n < packets.size(); ++n) {
    const auto& p = packets[n];
    hesai_packet_info info{};
    const hesai_point* got = nullptr;
    std::size_t count = 0;
    const hesai_error e = c_feed(p.data(), p.size(), &info, &got, &count);
    // What c_feed does, in C++: a GPS packet updates the decoder, any other is decoded.
    Model model = Model::unknown;
    PacketKind kind = PacketKind::point_cloud;
    if (identify(view(p), model, kind) == Error::ok && kind == PacketKind::gps) {
      GpsPacket gps;
      const Error want_error = parse_gps_packet(view(p), gps);
      if (want_error == Error::ok) cpp.update_gps(gps);
      EXPECT_EQ(static_cast<int>(e), static_cast<int>(want_error)) << n;
      EXPECT_EQ(count, 0u);
      continue;
    }
    const Error want_error = cpp.decode(view(p), want_info, want);
    EXPECT_EQ(static_cast<int>(e), static_cast<int>(want_error)) << n;
    if (e != HESAI_ERROR_ok) continue;
    expect_same_info(info, want_info, n);
    EXPECT_EQ(count, want.count) << n;
    for (std::size_t k = 0; k < count && k < want.count; ++k) {
      const ::testing::AssertionResult same = same_point(got[k], want.points[k]);
      if (!same) {
        ADD_FAILURE() << "packet " << n << " point " << k << ": " << same.message();
        return compared;
      }
    }
    compared += count;
  }
  return compared;
}

class CApi : public ::testing::TestWithParam<Capture> {};

void PrintTo(const Capture& c, std::ostream* os) { *os << model_name(c.model); }

// The capture with the unit's calibration files, given to C as the files' bytes.
TEST_P(CApi, CaptureDecodesToTheSamePointsAsCpp) {
  const Capture& c = GetParam();
  const auto packets = pcap_payloads(c.file);
  ASSERT_FALSE(packets.empty());
  const auto angles = read_file(data_path(c.angles));
  const auto firetimes = read_file(data_path(c.firetimes));
  ASSERT_EQ(c_open_csv(c_model(c.model), angles.data(), angles.size(), firetimes.data(), firetimes.size()),
            HESAI_ERROR_ok);
  Decoder cpp = cpp_decoder(c);
  EXPECT_GT(expect_same_decoding(packets, cpp), 100000u);
}

// A counter-clockwise unit: the C setter and Decoder::set_rotation give the same points, and the
// setting takes effect (the firing-time correction turns the other way, so points move).
TEST_P(CApi, CounterclockwiseGivesTheSamePointsAsCpp) {
  const Capture& c = GetParam();
  auto packets = pcap_payloads(c.file);
  ASSERT_GE(packets.size(), 50u);
  packets.resize(50);
  const auto angles = read_file(data_path(c.angles));
  const auto firetimes = read_file(data_path(c.firetimes));
  ASSERT_EQ(c_open_csv(c_model(c.model), angles.data(), angles.size(), firetimes.data(), firetimes.size()),
            HESAI_ERROR_ok);
  hesai_packet_info info{};
  const hesai_point* got = nullptr;
  std::size_t count = 0;
  ASSERT_EQ(c_feed(packets[0].data(), packets[0].size(), &info, &got, &count), HESAI_ERROR_ok);
  ASSERT_GT(count, 0u);
  const std::vector<hesai_point> clockwise(got, got + count);

  EXPECT_EQ(c_set_rotation(2), HESAI_ERROR_invalid_argument);
  ASSERT_EQ(c_set_rotation(HESAI_ROTATION_counterclockwise), HESAI_ERROR_ok);
  Decoder cpp = cpp_decoder(c);
  cpp.set_rotation(Rotation::counterclockwise);
  EXPECT_GT(expect_same_decoding(packets, cpp), 1000u);
  ASSERT_EQ(c_feed(packets[0].data(), packets[0].size(), &info, &got, &count), HESAI_ERROR_ok);
  ASSERT_EQ(count, clockwise.size());
  std::size_t moved = 0;
  for (std::size_t k = 0; k < count; ++k) moved += got[k].azimuth_deg != clockwise[k].azimuth_deg ? 1u : 0u;
  EXPECT_GT(moved, count / 2) << "every channel fired after its block's start moves";

  ASSERT_EQ(c_set_rotation(HESAI_ROTATION_clockwise), HESAI_ERROR_ok);
  ASSERT_EQ(c_feed(packets[0].data(), packets[0].size(), &info, &got, &count), HESAI_ERROR_ok);
  ASSERT_EQ(count, clockwise.size());
  for (std::size_t k = 0; k < count; ++k) {
    EXPECT_EQ(got[k].azimuth_deg, clockwise[k].azimuth_deg) << k;
    EXPECT_EQ(got[k].x, clockwise[k].x) << k;
    EXPECT_EQ(got[k].y, clockwise[k].y) << k;
  }
}

// The same calibration given as arrays (read with strtod by the test): the same points.
TEST_P(CApi, CalibrationArraysGiveTheSamePointsAsTheFiles) {
  const Capture& c = GetParam();
  const auto packets = pcap_payloads(c.file);
  const std::size_t channels = channel_count(c.model);
  const ReferenceCalibration t = read_reference_calibration(c.angles, c.firetimes, channels);
  const bool two_loops = c.model == Model::qt128c2x;
  ASSERT_EQ(c_open_arrays(c_model(c.model), t.elevation.data(), t.azimuth.data(), t.fire1.data(),
                          two_loops ? t.fire2.data() : nullptr, channels),
            HESAI_ERROR_ok);
  Decoder cpp = cpp_decoder(c);
  EXPECT_GT(expect_same_decoding(packets, cpp), 100000u);
}

INSTANTIATE_TEST_SUITE_P(Captures, CApi, ::testing::ValuesIn(kCaptures));

// The firing-time arrays do not say which channels rest: for the QT128 the manual's bank rule
// still does (hesai.h). Every channel given a time in both loops, packet 0 of the capture (mode
// flag 0, dual: sequence 2, bank B = channels 33..64 rests, manual App. I/II) decodes as before,
// and with data in channel 40's unit (CRC1 at 1040 over bytes 12..1039, re-sealed by a bitwise
// CRC-32/MPEG-2 written here) it is resting_channel_data.
TEST(CApiQt128, FiretimeArraysKeepTheBankRule) {
  auto p = pcap_payloads("qt128c2x_dual.pcap").at(0);
  ASSERT_EQ(p[1066] & 1, 0);
  ASSERT_EQ(p[10], 2);
  const std::vector<double> elevation(128, 0.0), azimuth(128, 0.0), us(128, 10.0);
  ASSERT_EQ(c_open_arrays(HESAI_MODEL_qt128c2x, elevation.data(), azimuth.data(), us.data(), us.data(), 128),
            HESAI_ERROR_ok);
  hesai_packet_info info;
  const hesai_point* points = nullptr;
  std::size_t count = 0;
  ASSERT_EQ(c_feed(p.data(), p.size(), &info, &points, &count), HESAI_ERROR_ok);
  EXPECT_GT(count, 0u);
  const std::size_t unit = 12 + 2 + 4 * (40 - 1);
  ASSERT_EQ(p[unit] | p[unit + 1] | p[unit + 2] | p[unit + 3], 0);
  p[unit + 1] = 1;  // distance 256
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 12; i < 1040; ++i) {
    crc ^= std::uint32_t{p[i]} << 24;
    for (int b = 0; b < 8; ++b) crc = (crc & 0x80000000u) ? (crc << 1) ^ 0x04C11DB7u : crc << 1;
  }
  for (std::size_t i = 0; i < 4; ++i) p[1040 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
  EXPECT_EQ(c_feed(p.data(), p.size(), &info, &points, &count), HESAI_ERROR_resting_channel_data);
  EXPECT_EQ(count, 0u);
}

// Design values (no calibration), a Pandar40 stream (the Pandar40P packets' first 1256 bytes,
// as tests/firmware does: no Pandar40 capture is at hand) with a GPS packet amid it.
TEST(CApiPandar40, DesignValuesAndGpsTimeLikeCpp) {
  auto packets = pcap_payloads("pandar40p_dual.pcap");
  packets.resize(200);
  for (auto& p : packets) p.resize(1256);
  // Pandar40 GPS packet 2017-09-06 16:00:00 (see test_c_api.c's pandar40_gps), amid the stream.
  std::vector<std::uint8_t> gps(512, 0);
  gps[0] = 0xFF;
  gps[1] = 0xEE;
  const char digits[] = "719060000061";
  for (std::size_t i = 0; i < 12; ++i) gps[2 + i] = static_cast<std::uint8_t>(digits[i]);
  for (std::size_t i = 95; i < 506; ++i) gps[i] = 0xDF;
  gps[506] = 'A';
  gps[507] = 1;
  packets.insert(packets.begin() + 100, gps);

  ASSERT_EQ(c_open_csv(HESAI_MODEL_pandar40, nullptr, 0, nullptr, 0), HESAI_ERROR_ok);
  Decoder cpp(Model::pandar40);
  EXPECT_GT(expect_same_decoding(packets, cpp), 10000u);
}

TEST(CApi, LayoutSeenByTheCCompiler) {
  std::size_t v[32];
  ASSERT_EQ(c_layout(v, 32), 19u);
  EXPECT_EQ(v[0], sizeof(Point));
  const std::size_t offsets[] = {offsetof(Point, x), offsetof(Point, y), offsetof(Point, z),
                                 offsetof(Point, distance_m), offsetof(Point, azimuth_deg),
                                 offsetof(Point, elevation_deg), offsetof(Point, time_ns),
                                 offsetof(Point, intensity), offsetof(Point, channel),
                                 offsetof(Point, return_index), offsetof(Point, confidence),
                                 offsetof(Point, block)};
  for (std::size_t i = 0; i < 12; ++i) EXPECT_EQ(v[1 + i], offsets[i]) << "member " << i;
  // hesai.h's storage, as the C compiler lays it out, and as the library's C++ compiler does.
  EXPECT_EQ(v[13], 8192u);
  EXPECT_EQ(v[13], sizeof(hesai_decoder));
  EXPECT_EQ(v[14], alignof(hesai_decoder));
  EXPECT_GE(v[14], alignof(Decoder));
  EXPECT_EQ(v[15], sizeof(hesai_calibration_scratch));
  EXPECT_EQ(v[16], alignof(hesai_calibration_scratch));
  EXPECT_EQ(v[17], sizeof(hesai_packet_info));
  EXPECT_EQ(v[18], alignof(hesai_packet_info));
}

// The offset of every member of hesai_packet_info, hesai_date_time and hesai_functional_safety
// as the C compiler lays them out (c_packet_info_layout) equals the C++ compiler's, member by
// member from the list (the library's static_asserts pin the same offsets by hand).
TEST(CApi, PacketInfoLayoutSeenByTheCCompiler) {
#define HESAI_OFFSET_INFO(type, name) offsetof(hesai_packet_info, name),
#define HESAI_OFFSET_INFO_ARRAY(type, name, count) offsetof(hesai_packet_info, name),
#define HESAI_OFFSET_INFO_NESTED(type, name, list) offsetof(hesai_packet_info, name),
#define HESAI_OFFSET_DATE_TIME(type, name) offsetof(hesai_date_time, name),
#define HESAI_OFFSET_SAFETY(type, name) offsetof(hesai_functional_safety, name),
  const std::size_t cpp[] = {
      HESAI_PACKET_INFO_LIST(HESAI_OFFSET_INFO, HESAI_OFFSET_INFO_ARRAY, HESAI_OFFSET_INFO_NESTED)
      HESAI_DATE_TIME_LIST(HESAI_OFFSET_DATE_TIME) HESAI_FUNCTIONAL_SAFETY_LIST(HESAI_OFFSET_SAFETY)
      sizeof(hesai_packet_info), sizeof(hesai_date_time), sizeof(hesai_functional_safety)};
#undef HESAI_OFFSET_INFO
#undef HESAI_OFFSET_INFO_ARRAY
#undef HESAI_OFFSET_INFO_NESTED
#undef HESAI_OFFSET_DATE_TIME
#undef HESAI_OFFSET_SAFETY
  std::size_t c[64];
  ASSERT_EQ(c_packet_info_layout(c, 64), std::size(cpp));
  for (std::size_t k = 0; k < std::size(cpp); ++k) EXPECT_EQ(c[k], cpp[k]) << "value " << k;
}

TEST(CApi, Errors) {
  const auto qt = pcap_payloads("qt128c2x_dual.pcap").at(5);
  EXPECT_EQ(c_check_errors(qt.data(), qt.size()), 0);
}

TEST(CApi, Columns) {
  const auto qt = pcap_payloads("qt128c2x_dual.pcap").at(5);
  EXPECT_EQ(c_check_columns(qt.data(), qt.size()), 0);
}

TEST(CApi, SessionKeys) {
  // tests/test_hkdf.cpp's fixed vector (computed with Python's hmac module and with OpenSSL):
  // secret "0123456789abcdef", lidar random 00..1f, client random 20..3f. The C side derives it.
  const std::uint8_t key[32] = {0x5c, 0xad, 0x3d, 0x54, 0xb4, 0xbb, 0xdc, 0x6a,
                                0x53, 0xdb, 0x72, 0x37, 0x7c, 0x69, 0x25, 0x96,
                                0x04, 0x8d, 0x55, 0xa3, 0x95, 0xee, 0xa3, 0x39,
                                0x96, 0xec, 0x1b, 0x2c, 0xb6, 0x3c, 0x9d, 0xc7};
  // Packet 5 has the signature section, all zero (unsigned); signed here with the key.
  const auto unsigned_packet = pcap_payloads("qt128c2x_dual.pcap").at(5);
  auto signed_packet = unsigned_packet;
  qt128_seal(signed_packet, key);
  EXPECT_EQ(c_check_keys(unsigned_packet.data(), signed_packet.data(), signed_packet.size(), key), 0);
}

TEST(CApi, Pandar40TimeFromGps) {
  auto p = pcap_payloads("pandar40p_dual.pcap").at(0);
  p.resize(1256);
  EXPECT_EQ(c_check_pandar40_gps(p.data(), p.size()), 0);
}

TEST(CApi, CalibrationErrors) { EXPECT_EQ(c_check_calibration_errors(), 0); }

// QT128 channel customisation and the Pandar64 reflectivity mapping through the C setters: a real
// QT128 packet reduced to the bundled configuration's channels (as test_packet_variants.cpp builds
// it) decodes, under that file, to the points its non-zero units give (distance 2 or more).
TEST(CApi, SensorSettings) {
  const auto qt = pcap_payloads("qt128c2x_dual.pcap").at(5);
  const auto config = read_file(data_path("calibration/qt128c2x_channel_config.csv"));
  std::vector<std::size_t> keep;
  for (const auto& row : read_numeric_csv("calibration/qt128c2x_channel_config.csv").rows)
    if (row.size() == 2) keep.push_back(static_cast<std::size_t>(row[(qt[1066] & 1) ? 0 : 1]) - 1);
  ASSERT_EQ(keep.size(), 80u);
  const auto custom = qt128_rebuild(qt, 80, 0x5D, {keep, keep});  // dual return: one loop for both blocks
  std::size_t points = 0;
  for (std::size_t b = 0; b < 2; ++b)
    for (std::size_t j = 0; j < 80; ++j) points += load_le16(&custom[12 + b * 322 + 2 + j * 4]) >= 2;
  ASSERT_GT(points, 0u);
  const auto p64 = pcap_payloads("pandar64_dual.pcap").at(0);
  EXPECT_EQ(c_check_sensor_settings(custom.data(), custom.size(), config.data(), config.size(), points, p64.data(),
                                    p64.size()),
            0);
}


// Stream health from C: the C monitor's counters equal the C++ HealthMonitor's on the same bytes
// (a sequence-less Pandar64 with 100 packets dropped and 9 frozen timestamps; the QT128C2X capture
// with distance-1 units in channels 70 and 100, resealed), and the counts the test built in.
TEST(CApi, StreamHealth) {
  auto p64 = pcap_payloads("pandar64_dual.pcap");
  for (std::size_t i = 301; i <= 309; ++i) {
    for (std::size_t b = 1182; b < 1186; ++b) p64[i][b] = p64[300][b];  // timestamp (tail 1172 + 10)
    for (std::size_t b = 1188; b < 1194; ++b) p64[i][b] = p64[300][b];  // date-time (tail + 16)
  }
  for (auto& q : p64) q.resize(1194);
  p64.erase(p64.begin() + 700, p64.begin() + 800);
  auto qt = pcap_payloads("qt128c2x_dual.pcap");
  for (std::size_t i = 10; i < 15; ++i) {
    store_le16(&qt[i][12 + 2 + 4 * 69], 1);
    store_le16(&qt[i][12 + 514 + 2 + 4 * 69], 1);
  }
  for (std::size_t i = 20; i < 23; ++i) store_le16(&qt[i][12 + 2 + 4 * 99], 1);
  for (std::size_t i = 10; i < 23; ++i) qt128_seal(qt[i]);
  for (const auto& [packets, model] : {std::pair{p64, Model::pandar64}, std::pair{qt, Model::qt128c2x}}) {
    for (const Returns returns : {Returns::all, Returns::distinct}) {
      std::vector<std::uint8_t> bytes;
      std::vector<std::size_t> sizes;
      for (const auto& q : packets) {
        bytes.insert(bytes.end(), q.begin(), q.end());
        sizes.push_back(q.size());
      }
      hesai_health_counts c{};
      std::uint64_t c_points = 0;
      int failures = 0;
      EXPECT_EQ(c_health_run(static_cast<hesai_model>(model), bytes.data(), sizes.data(), sizes.size(),
                             static_cast<int>(returns), &c, &c_points, &failures),
                HESAI_ERROR_ok);
      EXPECT_EQ(failures, 0);
      Decoder d(model);
      HealthMonitor m;
      static PacketPoints pts;
      std::uint64_t cpp_points = 0;
      for (const auto& q : packets) {
        PacketInfo info;
        UnitScan scan;
        ASSERT_EQ(d.decode(view(q), info, pts, scan, returns), Error::ok);
        m.observe(info);
        m.observe_units(scan);
        cpp_points += pts.count;
      }
      const HealthCounts& h = m.counts();
      EXPECT_EQ(c_points, cpp_points);
      EXPECT_EQ(c.packets, h.packets);
      EXPECT_EQ(c.lost, h.lost);
      EXPECT_EQ(c.time_stalls, h.time_stalls);
      EXPECT_EQ(c.time_virtual, h.time_virtual);
      EXPECT_EQ(c.time_jumps, h.time_jumps);
      EXPECT_EQ(c.reordered, h.reordered);
      EXPECT_EQ(c.duplicates, h.duplicates);
      EXPECT_EQ(c.blockage_units, h.blockage_units);
      EXPECT_EQ(c.duplicate_returns, h.duplicate_returns);
      EXPECT_EQ(c.beyond_rated_range, h.beyond_rated_range);
      for (std::size_t ch = 0; ch < kMaxChannels; ++ch) EXPECT_EQ(c.blockage_by_channel[ch], h.blockage_by_channel[ch]);
      EXPECT_EQ(c.fov_gap, h.fov_gap ? 1 : 0);
      // What the test built in.
      EXPECT_EQ(c.lost, model == Model::pandar64 ? 100u : 0u);
      EXPECT_EQ(c.time_stalls, model == Model::pandar64 ? 9u : 0u);
      EXPECT_EQ(c.blockage_units, model == Model::qt128c2x ? 13u : 0u);
      EXPECT_EQ(c.blockage_by_channel[69], model == Model::qt128c2x ? 10u : 0u);
      EXPECT_EQ(c.blockage_by_channel[99], model == Model::qt128c2x ? 3u : 0u);
    }
  }
}

}  // namespace
