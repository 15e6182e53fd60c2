// What the registry of sensors tells a user (model.h: packets per rotation; ptc.h: the PTC
// product number, from model_list.h; decoder.h: write_udp_sequence), checked against the bundled captures and the layouts' prose,
// never against the tables that define them.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "hesai/decoder.h"
#include "hesai/model.h"
#include "hesai/ptc.h"
#include "test_support.h"

namespace {

using hesai::Error;
using hesai_test::pcap_payloads;
using hesai_test::view;
using hesai::Model;

struct Capture {
  const char* file;
  Model model;
};
const Capture kCaptures[] = {
    {"pandar40p_dual.pcap", Model::pandar40p}, {"pandar64_dual.pcap", Model::pandar64},
    {"qt128c2x_dual.pcap", Model::qt128c2x},   {"pandar_qt64.pcap", Model::pandar_qt64},
    {"pandar_xt16.pcap", Model::pandar_xt16},  {"pandar_xt32.pcap", Model::pandar_xt32},
    {"pandar_xt32m2x.pcap", Model::pandar_xt32m2x},
};

// The packets of each capture between two consecutive wraps of the first block's azimuth (from
// above 270 degrees to below 90), counted by their UDP sequence numbers (so that the packets the
// XT32M2X capture lost count too; the Pandar40P capture has none and lost none: by their index)
// and scaled to 600 rpm by the packets' motor speed: within one
// packet of packets_per_rotation() for the capture's returns per firing.
TEST(Registry, PacketsPerRotationAsTheCapturesShowThem) {
  for (const Capture& c : kCaptures) {
    SCOPED_TRACE(c.file);
    hesai::Decoder d(c.model);
    std::vector<std::uint32_t> wraps;  // the sequence numbers (or indices) of the packets after a wrap
    std::uint16_t previous = 0, rpm = 0;
    std::uint8_t returns = 0;
    std::uint32_t index = 0;
    for (const auto& p : pcap_payloads(c.file)) {
      hesai::PacketInfo info;
      ASSERT_EQ(d.validate(view(p), info), Error::ok);
      const std::uint16_t az = info.block_azimuth[0];
      if (index > 0 && previous > 27000 && az < 9000) wraps.push_back(info.has_sequence ? info.sequence : index);
      ++index;
      previous = az;
      rpm = info.motor_rpm;
      returns = info.returns;
    }
    ASSERT_GE(wraps.size(), 2u);
    ASSERT_GT(rpm, 0);
    const double counted = static_cast<double>(wraps[1] - wraps[0]) * rpm / 600.0;
    EXPECT_NEAR(static_cast<double>(hesai::packets_per_rotation(c.model, returns)), counted, 1.0);
  }
  EXPECT_EQ(hesai::packets_per_rotation(Model::pandar64, 1), 300u);  // 1 800 firings, 6 a packet
  EXPECT_EQ(hesai::packets_per_rotation(Model::unknown, 2), 0u);
}

// nebula hesai_hw_interface.cpp, nebula_model_to_hesai_model_no: 0 Pandar40P, 2 Pandar64,
// 15 PandarQT, 25 PandarXT32, 26 PandarXT16, 32 QT128C2X, 38 PandarXT32M.
TEST(Registry, PtcProductNumbers) {
  EXPECT_EQ(hesai::ptc::product_number(Model::pandar40p), 0);
  EXPECT_EQ(hesai::ptc::product_number(Model::pandar64), 2);
  EXPECT_EQ(hesai::ptc::product_number(Model::pandar_qt64), 15);
  EXPECT_EQ(hesai::ptc::product_number(Model::pandar_xt32), 25);
  EXPECT_EQ(hesai::ptc::product_number(Model::pandar_xt16), 26);
  EXPECT_EQ(hesai::ptc::product_number(Model::qt128c2x), 32);
  EXPECT_EQ(hesai::ptc::product_number(Model::pandar_xt32m2x), 38);
  EXPECT_EQ(hesai::ptc::product_number(Model::pandar40), 255);
  EXPECT_EQ(hesai::ptc::product_number(Model::unknown), 255);
}

// write_udp_sequence on the first packet of every capture. Where the packet carries a sequence
// (every capture's does, as its length or flags bit 0 shows, but the Pandar40P's: its 1262-byte
// packets are given the four bytes of the 1266-byte form), validate() reads the new number
// back and accepts the packet (QT128C2X: CRC3 re-sealed); the bytes that changed are the four of
// the field, which the layouts put last (Pandar40P 1266 and Pandar64 1198 bytes: "UDP sequence"
// after the tail; PandarQT64 and XT: the tail's last field), and, on the QT128C2X, the field in
// its tail and CRC3 after it.
TEST(Registry, WriteUdpSequence) {
  for (const Capture& c : kCaptures) {
    SCOPED_TRACE(c.file);
    std::vector<std::uint8_t> p = pcap_payloads(c.file).front();
    if (c.model == Model::pandar40p) {
      ASSERT_EQ(p.size(), 1262u);
      EXPECT_EQ(hesai::write_udp_sequence(p.data(), p.size(), 7), Error::unsupported_section);
      p.resize(1266, 0);
    }
    const std::vector<std::uint8_t> before = p;
    hesai::Decoder d(c.model);
    hesai::PacketInfo info;
    ASSERT_EQ(d.validate(view(p), info), Error::ok);
    ASSERT_TRUE(info.has_sequence);
    constexpr std::uint32_t kSequence = 0xA1B2C3D4u;
    ASSERT_NE(info.sequence, kSequence);
    ASSERT_EQ(hesai::write_udp_sequence(p.data(), p.size(), kSequence), Error::ok);
    ASSERT_EQ(d.validate(view(p), info), Error::ok);
    EXPECT_EQ(info.sequence, kSequence);
    std::vector<std::size_t> changed;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p[i] != before[i]) changed.push_back(i);
    ASSERT_FALSE(changed.empty());
    if (c.model == Model::qt128c2x) {
      EXPECT_LE(changed.size(), 8u);  // the sequence and CRC3
    } else {
      EXPECT_GE(changed.front(), p.size() - 4);  // only the last four bytes
      const std::vector<std::uint8_t> le = {0xD4, 0xC3, 0xB2, 0xA1};
      EXPECT_EQ(std::vector<std::uint8_t>(p.end() - 4, p.end()), le);
    }
  }
}

// A packet without the field is left alone: the Pandar64 cut to its 1194 bytes without the
// sequence, and a GPS packet.
TEST(Registry, WriteUdpSequenceWithoutTheField) {
  std::vector<std::uint8_t> p = pcap_payloads("pandar64_dual.pcap").front();
  ASSERT_EQ(p.size(), 1198u);
  p.resize(1194);
  const std::vector<std::uint8_t> before = p;
  EXPECT_EQ(hesai::write_udp_sequence(p.data(), p.size(), 7), Error::unsupported_section);
  EXPECT_EQ(p, before);
  std::vector<std::uint8_t> gps(512, 0);
  gps[0] = 0xFF;
  gps[1] = 0xEE;
  EXPECT_EQ(hesai::write_udp_sequence(gps.data(), gps.size(), 7), Error::unsupported_section);
  std::vector<std::uint8_t> junk(100, 0x11);
  EXPECT_EQ(hesai::write_udp_sequence(junk.data(), junk.size(), 7), Error::bad_magic);
}

}  // namespace
