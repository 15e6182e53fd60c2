// The decode path of every model, on the bundled real captures, allocates nothing.
#include <gtest/gtest.h>

#include "../packet_builder.h"
#include "../test_support.h"
#include "alloc_counter.h"
#include "hesai/calibration.h"
#include "hesai/decoder.h"

namespace {

using namespace hesai;

void decode_all_without_allocating(const char* capture, Model model) {
  const auto packets = hesai_test::pcap_payloads(capture);  // reading the file may allocate
  ASSERT_FALSE(packets.empty());
  static PacketPoints pts;
  static PacketColumns<kMaxPointsPerPacket> columns;
  PacketInfo info;
  std::size_t points = 0, column_points = 0, surveyed_points = 0;
  Error worst = Error::ok;
  const std::size_t n = hesai_test::allocations_during([&] {
    Decoder dec(model);
    for (const auto& p : packets) {
      const Error e = dec.decode(ByteView{p.data(), p.size()}, info, pts);
      if (e != Error::ok) worst = e;
      points += pts.count;
      // What --packets does with the packets outside its range.
      UnitScan scan;
      std::size_t surveyed = 0;
      if (const Error s = dec.survey(ByteView{p.data(), p.size()}, info, scan, surveyed); s != Error::ok) worst = s;
      surveyed_points += surveyed;
      // The columnar output, on the vector path and the portable one.
      for (const DecodePath path : {DecodePath::best, DecodePath::avx2, DecodePath::portable}) {
        const Error c = dec.decode(ByteView{p.data(), p.size()}, info, columns, path);
        if (c != Error::ok) worst = c;
        column_points += columns.count;
      }
    }
  });
  EXPECT_EQ(worst, Error::ok);
  EXPECT_GT(points, 0u);
  EXPECT_EQ(column_points, 3 * points);
  EXPECT_EQ(surveyed_points, points);
  EXPECT_EQ(n, 0u) << capture;
}

TEST(ZeroAllocation, DecodePandar40P) { decode_all_without_allocating("pandar40p_dual.pcap", Model::pandar40p); }
TEST(ZeroAllocation, DecodePandar64) { decode_all_without_allocating("pandar64_dual.pcap", Model::pandar64); }
TEST(ZeroAllocation, DecodeQt128) { decode_all_without_allocating("qt128c2x_dual.pcap", Model::qt128c2x); }
TEST(ZeroAllocation, DecodePandarQt64) { decode_all_without_allocating("pandar_qt64.pcap", Model::pandar_qt64); }
TEST(ZeroAllocation, DecodePandarXt16) { decode_all_without_allocating("pandar_xt16.pcap", Model::pandar_xt16); }
TEST(ZeroAllocation, DecodePandarXt32) { decode_all_without_allocating("pandar_xt32.pcap", Model::pandar_xt32); }
TEST(ZeroAllocation, DecodePandarXt32m2x) { decode_all_without_allocating("pandar_xt32m2x.pcap", Model::pandar_xt32m2x); }

TEST(ZeroAllocation, SignedQt128WithKey) {
  // The capture's packets carry a signature section left all-zero (signing not started): every
  // other one is signed here, so that both the HMAC check and the unsigned path run.
  auto packets = hesai_test::pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_FALSE(packets.empty());
  const std::uint8_t key[32] = {1, 2, 3};
  for (std::size_t i = 0; i < packets.size(); i += 2) hesai_test::qt128_seal(packets[i], key);
  static PacketPoints pts;
  PacketInfo info;
  std::size_t valid = 0, unsigned_accepted = 0;
  Error worst = Error::ok;
  const std::size_t n = hesai_test::allocations_during([&] {
    Decoder dec(Model::qt128c2x);
    worst = dec.set_session_key(key);
    dec.set_allow_unsigned(true);
    for (const auto& p : packets) {
      const Error e = dec.decode(ByteView{p.data(), p.size()}, info, pts);
      if (e != Error::ok) worst = e;
      valid += info.signature == SignatureStatus::valid;
      unsigned_accepted += info.signature == SignatureStatus::accepted_unsigned;
    }
  });
  EXPECT_EQ(worst, Error::ok);
  EXPECT_EQ(valid, (packets.size() + 1) / 2);
  EXPECT_EQ(unsigned_accepted, packets.size() / 2);
  EXPECT_EQ(n, 0u);
}

// The settings of "Sensor settings we read": QT128 3-byte units, customised channels (the
// configuration set inside the counted region), Unix-seconds time; Pandar64 nonlinear reflectivity.
TEST(ZeroAllocation, SensorSettingVariants) {
  using namespace hesai_test;
  const auto qt = pcap_payloads("qt128c2x_dual.pcap");
  const auto p64 = pcap_payloads("pandar64_dual.pcap");
  const auto config_text = read_file(data_path("calibration/qt128c2x_channel_config.csv"));
  static ChannelConfig config;
  ASSERT_EQ(parse_channel_config_csv(view(config_text), config).error, Error::ok);
  std::vector<std::vector<std::uint8_t>> variants;  // built before counting
  for (std::size_t i = 0; i < 64; ++i) {
    const auto& p = qt[i];
    variants.push_back(qt128_rebuild(p, 128, 0x0D, {first_units(128), first_units(128)}));
    std::vector<std::size_t> keep;
    for (std::size_t j = 0; j < config.laser_num; ++j) keep.push_back(config.channel[(p[1066] & 1) ? 0 : 1][j] - 1u);
    variants.push_back(qt128_rebuild(p, static_cast<std::uint8_t>(config.laser_num), 0x4D, {keep, keep}));
    variants.push_back(p);
    qt128_set_unix_time(variants.back(), 1602245009u + static_cast<std::uint32_t>(i));
  }
  static PacketPoints pts;
  PacketInfo info;
  std::size_t points = 0;
  Error worst = Error::ok;
  const std::size_t n = hesai_test::allocations_during([&] {
    Decoder dec(Model::qt128c2x);
    if (dec.set_channel_config(config) != Error::ok) worst = Error::invalid_argument;
    for (const auto& p : variants) {
      const Error e = dec.decode(ByteView{p.data(), p.size()}, info, pts);
      if (e != Error::ok) worst = e;
      points += pts.count;
    }
    Decoder pandar64(Model::pandar64);
    if (pandar64.set_reflectivity(Reflectivity::nonlinear) != Error::ok) worst = Error::invalid_argument;
    for (std::size_t i = 0; i < 64; ++i) {
      const Error e = pandar64.decode(ByteView{p64[i].data(), p64[i].size()}, info, pts);
      if (e != Error::ok) worst = e;
      points += pts.count;
    }
  });
  EXPECT_EQ(worst, Error::ok);
  EXPECT_GT(points, 0u);
  EXPECT_EQ(n, 0u);
}

}  // namespace
