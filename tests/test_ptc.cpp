// The PTC codec (hesai/ptc.h) on responses built byte by byte here, field by field in the order of
// tier4/nebula's hesai_cmd_response.hpp structs (big-endian), with the values each field should
// parse to written beside it. The expectations come from those layouts, not from the codec.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "hesai/decoder.h"
#include "hesai/hkdf.h"
#include "hesai/ptc.h"
#include "hesai/ptc_settings.h"
#include "hesai/detail/qt128_packet.h"
#include "test_support.h"

namespace {

using hesai::ByteView;
using hesai::Error;
using hesai::Model;
namespace ptc = hesai::ptc;
using Bytes = std::vector<std::uint8_t>;

void text(Bytes& b, const char* s, std::size_t field) {
  const std::size_t n = std::strlen(s);
  for (std::size_t i = 0; i < field; ++i) b.push_back(i < n ? static_cast<std::uint8_t>(s[i]) : 0);
}
void be16(Bytes& b, std::uint16_t v) {
  b.push_back(static_cast<std::uint8_t>(v >> 8));
  b.push_back(static_cast<std::uint8_t>(v));
}
void be32(Bytes& b, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) b.push_back(static_cast<std::uint8_t>(v >> s));
}

// HesaiInventoryBase::Internal: sn[18], date_of_manufacture[16], mac[6], sw_ver[16], hw_ver[16],
// control_fw_ver[16], sensor_fw_ver[16].
Bytes inventory_common() {
  Bytes b;
  text(b, "PT2020123456789ABC", 18);  // all 18 bytes used: no NUL in the field
  text(b, "2020-10-09", 16);
  for (int m : {0x00, 0x1C, 0x2D, 0xAB, 0xCD, 0xEF}) b.push_back(static_cast<std::uint8_t>(m));
  text(b, "2.1.5", 16);
  text(b, "1.0", 16);
  text(b, "3.4.6", 16);
  text(b, "7.8.9", 16);
  return b;
}

TEST(Ptc, RequestBytes) {
  // 47 74, command, return code 0, length big-endian, payload.
  const std::uint8_t random[3] = {0xAA, 0xBB, 0xCC};
  std::uint8_t out[16];
  std::size_t n = 0;
  ASSERT_EQ(ptc::encode_request(ptc::Command::signature_start, ByteView{random, 3}, out, sizeof out, n), Error::ok);
  const std::uint8_t expected[] = {0x47, 0x74, 0x2E, 0x00, 0x00, 0x00, 0x00, 0x03, 0xAA, 0xBB, 0xCC};
  ASSERT_EQ(n, sizeof expected);
  EXPECT_EQ(std::memcmp(out, expected, n), 0);
  ASSERT_EQ(ptc::encode_request(ptc::Command::inventory, {}, out, 8, n), Error::ok);
  const std::uint8_t inventory[] = {0x47, 0x74, 0x07, 0x00, 0x00, 0x00, 0x00, 0x00};
  EXPECT_EQ(std::memcmp(out, inventory, 8), 0);
  EXPECT_EQ(ptc::encode_request(ptc::Command::signature_start, ByteView{random, 3}, out, 10, n), Error::buffer_too_small);
}

TEST(Ptc, ResponseHeaderChecks) {
  ptc::Header h;
  // 0x05 answered with 0x00012345 bytes (74 565), return code 0.
  const std::uint8_t good[] = {0x47, 0x74, 0x05, 0x00, 0x00, 0x01, 0x23, 0x45};
  ASSERT_EQ(ptc::check_response(ByteView{good, 8}, ptc::Command::calibration, 1u << 20, h), Error::ok);
  EXPECT_EQ(h.command, 0x05);
  EXPECT_EQ(h.return_code, 0);
  EXPECT_EQ(h.length, 74565u);
  EXPECT_EQ(ptc::check_response(ByteView{good, 7}, ptc::Command::calibration, 1u << 20, h), Error::truncated);

  const std::uint8_t magic[] = {0x47, 0x75, 0x05, 0x00, 0x00, 0x00, 0x00, 0x00};
  EXPECT_EQ(ptc::check_response(ByteView{magic, 8}, ptc::Command::calibration, 100, h), Error::ptc_bad_magic);
  const std::uint8_t echo[] = {0x47, 0x74, 0x09, 0x00, 0x00, 0x00, 0x00, 0x00};
  EXPECT_EQ(ptc::check_response(ByteView{echo, 8}, ptc::Command::calibration, 100, h), Error::ptc_command_mismatch);
  EXPECT_EQ(h.command, 0x09);  // named in the message
  // The bound: 74 565 is one above 74 564.
  EXPECT_EQ(ptc::check_response(ByteView{good, 8}, ptc::Command::calibration, 74564, h), Error::ptc_length_exceeds_bound);
  EXPECT_EQ(ptc::check_response(ByteView{good, 8}, ptc::Command::calibration, 74565, h), Error::ok);
  const std::uint8_t huge[] = {0x47, 0x74, 0x05, 0x00, 0xFF, 0xFF, 0xFF, 0xF0};
  EXPECT_EQ(ptc::check_response(ByteView{huge, 8}, ptc::Command::calibration, ptc::max_response_bytes(ptc::Command::calibration), h),
            Error::ptc_length_exceeds_bound);
  EXPECT_EQ(h.length, 0xFFFFFFF0u);
  // Return code 5, unsupported command (nebula g_ptc_error_code_unsupported_cmd).
  const std::uint8_t refused[] = {0x47, 0x74, 0x05, 0x05, 0x00, 0x00, 0x00, 0x00};
  EXPECT_EQ(ptc::check_response(ByteView{refused, 8}, ptc::Command::calibration, 100, h), Error::ptc_sensor_error);
  EXPECT_EQ(h.return_code, 5);
  EXPECT_STREQ(ptc::return_code_name(5), "unsupported command");
  EXPECT_STREQ(ptc::return_code_name(1), "invalid input parameter");
  EXPECT_STREQ(ptc::return_code_name(6), "FPGA communication failed");
  EXPECT_STREQ(ptc::return_code_name(8), "unknown return code");
}

TEST(Ptc, Bounds) {
  EXPECT_EQ(ptc::max_response_bytes(ptc::Command::calibration), 1u << 20);
  EXPECT_EQ(ptc::max_response_bytes(ptc::Command::firetimes), 1u << 20);
  EXPECT_EQ(ptc::max_response_bytes(ptc::Command::channel_config), 1u << 20);
  EXPECT_EQ(ptc::max_response_bytes(ptc::Command::inventory), 4096u);
  EXPECT_EQ(ptc::max_response_bytes(ptc::Command::signature_start), 4096u);
}

TEST(Ptc, InventoryXtLayout) {
  // HesaiInventory_XT16_32_40P: zero_angle_offset i16, product_model, motor_type, num_of_lines, reserved[11].
  Bytes b = inventory_common();
  be16(b, static_cast<std::uint16_t>(-25));
  b.push_back(25);  // PandarXT32
  b.push_back(0);
  b.push_back(32);
  b.resize(b.size() + 11, 0);
  ASSERT_EQ(b.size(), 120u);
  ptc::Inventory inv;
  ASSERT_EQ(ptc::parse_inventory(ByteView{b.data(), b.size()}, inv), Error::ok);
  EXPECT_STREQ(inv.serial, "PT2020123456789ABC");
  EXPECT_STREQ(inv.manufacture_date, "2020-10-09");
  const std::uint8_t mac[6] = {0x00, 0x1C, 0x2D, 0xAB, 0xCD, 0xEF};
  EXPECT_EQ(std::memcmp(inv.mac, mac, 6), 0);
  EXPECT_STREQ(inv.software_version, "2.1.5");
  EXPECT_STREQ(inv.hardware_version, "1.0");
  EXPECT_STREQ(inv.control_firmware, "3.4.6");
  EXPECT_STREQ(inv.sensor_firmware, "7.8.9");
  EXPECT_TRUE(inv.has_model);
  EXPECT_EQ(inv.product_model, 25);
  EXPECT_EQ(inv.model, Model::pandar_xt32);
  EXPECT_EQ(inv.lines, 32);
  EXPECT_EQ(inv.zero_angle_offset, -25);
}

TEST(Ptc, InventoryQt128Layout) {
  // HesaiInventory_QT128: zero_angle_offset i16, angle_offset_cc i16, product_model, motor_type,
  // num_of_lines, pn[32], reserved.
  Bytes b = inventory_common();
  be16(b, 0);
  be16(b, 0);
  b.push_back(32);  // QT128C2X
  b.push_back(0);
  b.push_back(128);
  text(b, "QT128C2X-PN", 32);
  b.push_back(0);
  ASSERT_EQ(b.size(), 144u);
  ptc::Inventory inv;
  ASSERT_EQ(ptc::parse_inventory(ByteView{b.data(), b.size()}, inv), Error::ok);
  EXPECT_EQ(inv.model, Model::qt128c2x);
  EXPECT_EQ(inv.lines, 128);
  // The same bytes read in the XT layout would give product model 0 (the high byte of the
  // counter-clockwise offset): the layout is chosen by where the model and lines sit.
  b[108] = 25;
  ASSERT_EQ(ptc::parse_inventory(ByteView{b.data(), b.size()}, inv), Error::ok);
  EXPECT_EQ(inv.product_model, 0);
  EXPECT_EQ(inv.model, Model::pandar40p);
}

TEST(Ptc, InventoryShortAndNumbers) {
  Bytes b = inventory_common();
  ptc::Inventory inv;
  ASSERT_EQ(ptc::parse_inventory(ByteView{b.data(), b.size()}, inv), Error::ok);  // 104 bytes: no model
  EXPECT_FALSE(inv.has_model);
  EXPECT_EQ(inv.model, Model::unknown);
  inv.serial[0] = 'X';
  EXPECT_EQ(ptc::parse_inventory(ByteView{b.data(), 103}, inv), Error::ptc_payload_length);
  EXPECT_EQ(inv.serial[0], 'X');  // untouched
  // nebula nebula_model_to_hesai_model_no.
  EXPECT_EQ(ptc::model_from_product_number(0), Model::pandar40p);
  EXPECT_EQ(ptc::model_from_product_number(2), Model::pandar64);
  EXPECT_EQ(ptc::model_from_product_number(15), Model::pandar_qt64);
  EXPECT_EQ(ptc::model_from_product_number(26), Model::pandar_xt16);
  EXPECT_EQ(ptc::model_from_product_number(38), Model::pandar_xt32m2x);
  EXPECT_EQ(ptc::model_from_product_number(42), Model::unknown);  // OT128: not decoded here
}

TEST(Ptc, Config) {
  // HesaiConfigBase::Internal then HesaiConfig_XT_40P_64_QT128::Internal.
  Bytes b = {192, 168, 1, 201, 255, 255, 255, 0, 192, 168, 1, 1, 192, 168, 1, 100};
  be16(b, 2368);   // dest_LiDAR_udp_port
  be16(b, 10110);  // dest_gps_udp_port
  be16(b, 1200);   // spin_rate
  b.push_back(1);  // sync
  be16(b, 90);     // sync_angle
  be16(b, 100);    // start_angle
  be16(b, 3500);   // stop_angle
  for (int v : {2, 1, 0, 0x39, 0, 1, 1}) b.push_back(static_cast<std::uint8_t>(v));  // clock_source .. vlan_flag
  be16(b, 7);      // vlan_id
  ASSERT_EQ(b.size(), 38u);
  ptc::Config c;
  ASSERT_EQ(ptc::parse_config(ByteView{b.data(), b.size()}, c), Error::ok);
  EXPECT_FALSE(c.has_extra);
  for (int v : {1, 0, 2}) b.push_back(static_cast<std::uint8_t>(v));  // clock_data_fmt, noise_filtering, reflectivity_mapping
  b.resize(b.size() + 6, 0);
  ASSERT_EQ(ptc::parse_config(ByteView{b.data(), b.size()}, c), Error::ok);
  EXPECT_EQ(c.ip[3], 201);
  EXPECT_EQ(c.mask[3], 0);
  EXPECT_EQ(c.destination_ip[3], 100);
  EXPECT_EQ(c.destination_port, 2368);
  EXPECT_EQ(c.gps_port, 10110);
  EXPECT_EQ(c.spin_rate_rpm, 1200);
  EXPECT_EQ(c.sync, 1);
  EXPECT_EQ(c.sync_angle, 90);
  EXPECT_EQ(c.start_angle, 100);
  EXPECT_EQ(c.stop_angle, 3500);
  EXPECT_EQ(c.clock_source, 2);
  EXPECT_EQ(c.udp_sequence, 1);
  EXPECT_EQ(c.return_mode, 0x39);
  EXPECT_EQ(c.motor_status, 1);
  EXPECT_EQ(c.vlan_flag, 1);
  EXPECT_EQ(c.vlan_id, 7);
  EXPECT_TRUE(c.has_extra);
  EXPECT_EQ(c.clock_data_format, 1);
  EXPECT_EQ(c.reflectivity_mapping, 2);
  EXPECT_EQ(ptc::parse_config(ByteView{b.data(), 37}, c), Error::ptc_payload_length);
}

// HesaiLidarStatus_XT_40p (8 temperatures) and HesaiLidarStatusQT128 (9): system_uptime u32,
// motor_speed u16, temperature i32[N], gps_pps_lock, gps_gprmc_status, startup_times u32,
// total_operation_time u32, ptp_status, reserved[5].
Bytes status_bytes(std::size_t temperatures) {
  Bytes b;
  be32(b, 86400);
  be16(b, 600);
  for (std::size_t i = 0; i < temperatures; ++i) be32(b, static_cast<std::uint32_t>(i == 0 ? -1050 : 4000 + 10 * static_cast<int>(i)));
  b.push_back(1);
  b.push_back(0);
  be32(b, 321);
  be32(b, 98765);
  b.push_back(2);
  b.resize(b.size() + 5, 0);
  return b;
}

TEST(Ptc, StatusTemperaturesPerModel) {
  const Bytes eight = status_bytes(8), nine = status_bytes(9);
  ASSERT_EQ(eight.size(), 54u);
  ASSERT_EQ(nine.size(), 58u);
  ptc::Status s;
  ASSERT_EQ(ptc::parse_status(ByteView{nine.data(), nine.size()}, Model::qt128c2x, s), Error::ok);
  EXPECT_EQ(s.temperature_count, 9);
  EXPECT_EQ(s.uptime_s, 86400u);
  EXPECT_EQ(s.motor_speed_rpm, 600);
  EXPECT_EQ(s.temperature_centi_c[0], -1050);  // -10.50 C
  EXPECT_EQ(s.temperature_centi_c[8], 4080);
  EXPECT_EQ(s.gps_pps_lock, 1);
  EXPECT_EQ(s.gprmc_status, 0);
  EXPECT_EQ(s.startups, 321u);
  EXPECT_EQ(s.operating_time_min, 98765u);
  EXPECT_EQ(s.ptp_status, 2);
  EXPECT_STREQ(ptc::ptp_status_name(2), "locked");
  for (Model m : {Model::pandar40p, Model::pandar64, Model::pandar_xt16, Model::pandar_xt32, Model::unknown}) {
    ASSERT_EQ(ptc::parse_status(ByteView{eight.data(), eight.size()}, m, s), Error::ok) << hesai::model_name(m);
    EXPECT_EQ(s.temperature_count, 8);
    EXPECT_EQ(s.temperature_centi_c[7], 4070);
    EXPECT_EQ(s.startups, 321u);
    EXPECT_EQ(s.ptp_status, 2);
  }
  // Without the reserved bytes a status still parses; one byte short of the fields does not.
  EXPECT_EQ(ptc::parse_status(ByteView{nine.data(), 53}, Model::qt128c2x, s), Error::ok);
  EXPECT_EQ(ptc::parse_status(ByteView{nine.data(), 52}, Model::qt128c2x, s), Error::ptc_payload_length);
  EXPECT_EQ(ptc::parse_status(ByteView{eight.data(), 48}, Model::pandar64, s), Error::ptc_payload_length);
}

TEST(Ptc, SignatureSessionPayloads) {
  std::uint8_t r[32];
  Bytes random(32);
  for (std::size_t i = 0; i < 32; ++i) random[i] = static_cast<std::uint8_t>(0xA0 + i);
  ASSERT_EQ(ptc::parse_session_start(ByteView{random.data(), 32}, r), Error::ok);
  EXPECT_EQ(std::memcmp(r, random.data(), 32), 0);
  EXPECT_EQ(ptc::parse_session_start(ByteView{random.data(), 31}, r), Error::ptc_payload_length);
  random.push_back(0);
  EXPECT_EQ(ptc::parse_session_start(ByteView{random.data(), 33}, r), Error::ptc_payload_length);
  bool on = false;
  const std::uint8_t one = 1, zero = 0;
  ASSERT_EQ(ptc::parse_signature_state(ByteView{&one, 1}, on), Error::ok);
  EXPECT_TRUE(on);
  ASSERT_EQ(ptc::parse_signature_state(ByteView{&zero, 1}, on), Error::ok);
  EXPECT_FALSE(on);
  EXPECT_EQ(ptc::parse_signature_state(ByteView{random.data(), 2}, on), Error::ptc_payload_length);
}

// qt128::sign on a real packet: the decoder verifies it under the same key, and rejects it under
// another; the CRCs still hold (the signature is outside them).
TEST(Ptc, Qt128SignVerifiesWithTheSessionKey) {
  const auto packets = hesai_test::pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_FALSE(packets.empty());
  std::uint8_t key[32], other[32];
  const std::uint8_t lidar[32] = {1}, client[32] = {2};
  const char secret[] = "12345678";
  ASSERT_EQ(hesai::hesai_session_key(ByteView{reinterpret_cast<const std::uint8_t*>(secret), 8}, lidar, client, key), Error::ok);
  std::memcpy(other, key, 32);
  other[31] ^= 1;
  Bytes p = packets[3];
  ASSERT_EQ(hesai::qt128::sign(p.data(), p.size(), key), Error::ok);
  EXPECT_NE(std::memcmp(p.data(), packets[3].data(), p.size()), 0);
  EXPECT_EQ(std::memcmp(p.data(), packets[3].data(), p.size() - 32), 0);  // only the signature changed
  hesai::Decoder d(Model::qt128c2x);
  ASSERT_EQ(d.set_session_key(key), Error::ok);
  hesai::PacketInfo info;
  ASSERT_EQ(d.validate(ByteView{p.data(), p.size()}, info), Error::ok);
  EXPECT_EQ(info.signature, hesai::SignatureStatus::valid);
  ASSERT_EQ(d.set_session_key(other), Error::ok);
  EXPECT_EQ(d.validate(ByteView{p.data(), p.size()}, info), Error::signature_invalid);
  EXPECT_EQ(hesai::qt128::sign(p.data(), p.size() - 1, key), Error::bad_length);
}

}  // namespace

// ---- Settings (hesai/ptc_settings.h) ----

namespace {

Bytes encoded(ptc::Setting s, const ptc::Settings& v) {
  std::uint8_t out[ptc::kMaxSetPayloadBytes];
  std::size_t size = 0;
  ptc::encode_setting(s, v, out, size);
  return Bytes(out, out + size);
}

}  // namespace

// The set payloads in the SDK's order (ptc_client.cc SetSpinSpeed, SetReturnMode, SetStandbyMode,
// SetSyncAngle, SetDesIpandPort, SetAllChannelFov with fov_model 0), big-endian, the bytes written
// by hand; and the stand-in's reading of the same bytes.
TEST(Ptc, SetPayloadsInTheSdkOrder) {
  ptc::Settings v;
  v.rpm = 1200;
  v.return_mode = 5;
  v.standby = 1;
  v.sync = 1;
  v.sync_angle = 45;
  const std::uint8_t ip[4] = {192, 168, 1, 100};
  std::memcpy(v.destination_ip, ip, 4);
  v.destination_port = 2368;
  v.gps_port = 10110;
  v.fov_start = 100;   // 10.0 degrees
  v.fov_end = 3505;    // 350.5 degrees
  struct Case {
    ptc::Setting setting;
    std::uint8_t command;
    Bytes bytes;
  };
  const Case cases[] = {
      {ptc::Setting::rpm, 0x17, {0x04, 0xB0}},
      {ptc::Setting::return_mode, 0x1E, {0x05}},
      {ptc::Setting::standby, 0x1C, {0x01}},
      {ptc::Setting::sync_angle, 0x18, {0x01, 0x00, 0x2D}},
      {ptc::Setting::destination, 0x20, {0xC0, 0xA8, 0x01, 0x64, 0x09, 0x40, 0x27, 0x7E}},
      {ptc::Setting::fov, 0x22, {0x00, 0x00, 0x64, 0x0D, 0xB1}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(ptc::setting_name(c.setting));
    EXPECT_EQ(static_cast<int>(ptc::set_command(c.setting)), c.command);
    EXPECT_EQ(encoded(c.setting, v), c.bytes);
    ptc::Setting read = ptc::Setting::rpm;
    ptc::Settings back;
    ASSERT_EQ(ptc::parse_setting(c.command, ByteView{c.bytes.data(), c.bytes.size()}, read, back), Error::ok);
    EXPECT_EQ(read, c.setting);
    EXPECT_TRUE(ptc::same_setting(c.setting, back, v));
    Bytes longer = c.bytes;
    longer.push_back(0);
    EXPECT_EQ(ptc::parse_setting(c.command, ByteView{longer.data(), longer.size()}, read, back), Error::ptc_payload_length);
    EXPECT_EQ(ptc::parse_setting(c.command, ByteView{c.bytes.data(), c.bytes.size() - 1}, read, back),
              Error::ptc_payload_length);
  }
  ptc::Setting read;
  ptc::Settings back;
  EXPECT_EQ(ptc::parse_setting(0x08, ByteView{}, read, back), Error::ptc_command_mismatch);  // not a set command
  const Bytes per_channel = {0x01, 0x00, 0x64, 0x0D, 0xB1};  // method 1: another layout
  EXPECT_EQ(ptc::parse_setting(0x22, ByteView{per_channel.data(), per_channel.size()}, read, back), Error::invalid_argument);
  EXPECT_STREQ(ptc::command_name(0x17), "set_spin_rate");
  EXPECT_STREQ(ptc::command_name(0x10), "reboot");
  EXPECT_STREQ(ptc::command_name(0x06), "ptp_diagnostics");
}

// A configuration in nebula's order (HesaiConfigBase, then HesaiConfig_XT_40P_64_QT128) read as
// the settings: the sync angle from 0.01 degree to whole degrees, the FOV in 0.1 degree.
TEST(Ptc, SettingsFromConfigInNebulaOrder) {
  Bytes b = {10, 0, 0, 2, 255, 255, 255, 0, 10, 0, 0, 1, 10, 0, 0, 9};
  be16(b, 2370);   // dest_LiDAR_udp_port
  be16(b, 10111);  // dest_gps_udp_port
  be16(b, 600);    // spin_rate
  b.push_back(1);  // sync
  be16(b, 9000);   // sync_angle: 90.00 degrees
  be16(b, 305);    // start_angle: 30.5 degrees
  be16(b, 3300);   // stop_angle: 330.0 degrees
  for (int v : {1, 1, 0, 4, 1, 0, 0}) b.push_back(static_cast<std::uint8_t>(v));  // clock_source .. vlan_flag
  be16(b, 0);
  for (int v : {0, 0, 1}) b.push_back(static_cast<std::uint8_t>(v));
  b.resize(b.size() + 6, 0);
  ptc::Config c;
  ASSERT_EQ(ptc::parse_config(ByteView{b.data(), b.size()}, c), Error::ok);
  ptc::Settings s;
  ptc::settings_from_config(c, s);
  EXPECT_EQ(s.rpm, 600);
  EXPECT_EQ(s.sync, 1);
  EXPECT_EQ(s.sync_angle, 90);
  EXPECT_EQ(s.return_mode, 4);
  EXPECT_EQ(s.standby, 1);
  EXPECT_EQ(s.destination_ip[0], 10);
  EXPECT_EQ(s.destination_ip[3], 9);
  EXPECT_EQ(s.destination_port, 2370);
  EXPECT_EQ(s.gps_port, 10111);
  EXPECT_EQ(s.fov_start, 305);
  EXPECT_EQ(s.fov_end, 3300);
  // A sync that is off equals any other that is off, whatever angle it keeps.
  ptc::Settings off_a, off_b;
  off_a.sync_angle = 10;
  off_b.sync_angle = 20;
  EXPECT_TRUE(ptc::same_setting(ptc::Setting::sync_angle, off_a, off_b));
  off_a.sync = off_b.sync = 1;
  EXPECT_FALSE(ptc::same_setting(ptc::Setting::sync_angle, off_a, off_b));
  EXPECT_EQ(ptc::parse_config(ByteView{b.data(), 37}, c), Error::ptc_payload_length);
}

// nebula return_mode_from_int_hesai per model, its use_http_set_spin_rate, its FOV exclusions;
// the manuals' spin rates.
TEST(Ptc, AllowedValuesPerModel) {
  struct Case {
    Model model;
    std::vector<const char*> modes;  // by code 0..5, "" where the model has none
    std::vector<std::uint16_t> rates;
    bool http, fov;
  };
  const std::vector<const char*> six = {"last", "strongest", "last_strongest", "first", "last_first", "first_strongest"};
  const Case cases[] = {
      {Model::pandar40, {"last", "strongest", "last_strongest", "", "", ""}, {600, 1200}, true, false},
      {Model::pandar40p, {"last", "strongest", "last_strongest", "", "", ""}, {600, 1200}, true, true},
      {Model::pandar64, {"last", "strongest", "last_strongest", "", "", ""}, {600, 1200}, true, false},
      {Model::pandar_qt64, {"last", "", "last_first", "first", "", ""}, {300, 600, 1200}, true, true},
      {Model::qt128c2x, six, {600, 1200}, false, true},
      {Model::pandar_xt16, six, {300, 600, 1200}, false, true},
      {Model::pandar_xt32, six, {300, 600, 1200}, false, true},
      {Model::pandar_xt32m2x, six, {300, 600, 1200}, false, true},
      {Model::unknown, six, {300, 600, 1200}, true, true},  // as ptc_settings.h documents for it
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(hesai::model_name(c.model));
    for (std::uint8_t code = 0; code < 6; ++code) {
      const char* name = ptc::return_mode_name(c.model, code);
      if (c.modes[code][0] == '\0') {
        EXPECT_EQ(name, nullptr) << int(code);
        continue;
      }
      ASSERT_NE(name, nullptr) << int(code);
      EXPECT_STREQ(name, c.modes[code]);
      std::uint8_t back = 99;
      EXPECT_TRUE(ptc::return_mode_code(c.model, c.modes[code], std::strlen(c.modes[code]), back));
      EXPECT_EQ(back, code);
    }
    EXPECT_EQ(ptc::return_mode_name(c.model, 6), nullptr);
    std::uint16_t rates[ptc::kMaxSpinRates];
    const std::size_t n = ptc::allowed_spin_rates(c.model, rates);
    EXPECT_EQ(std::vector<std::uint16_t>(rates, rates + n), c.rates);
    EXPECT_EQ(ptc::spin_rate_over_http(c.model), c.http);
    EXPECT_EQ(ptc::fov_supported(c.model), c.fov);
  }
  std::uint8_t code = 0;
  EXPECT_FALSE(ptc::return_mode_code(Model::pandar64, "first", 5, code));
  EXPECT_FALSE(ptc::return_mode_code(Model::qt128c2x, "lastx", 5, code));
  EXPECT_FALSE(ptc::return_mode_code(Model::qt128c2x, "las", 3, code));
  ptc::Setting s;
  EXPECT_TRUE(ptc::setting_from_name("sync_angle", 10, s));
  EXPECT_EQ(s, ptc::Setting::sync_angle);
  EXPECT_FALSE(ptc::setting_from_name("sync_angles", 11, s));
  EXPECT_FALSE(ptc::setting_from_name("rp", 2, s));
}

// ptc.h: 9 temperatures in the QT128C2X's status (nebula HesaiLidarStatusQT128), 8 in the
// others' and an unknown model's (nebula HesaiLidarStatus_XT_40p, SDK PtcClient::GetLidarStatus).
TEST(Ptc, StatusTemperatureCountPerModel) {
  for (std::size_t m = 0; m < hesai::kModelCount; ++m) {
    const auto model = static_cast<Model>(m);
    EXPECT_EQ(ptc::status_temperature_count(model), model == Model::qt128c2x ? 9u : 8u) << hesai::model_name(model);
  }
  EXPECT_EQ(ptc::status_temperature_count(static_cast<Model>(200)), 8u);  // not a model: as unknown
}

TEST(Ptc, CodedFieldNames) {
  EXPECT_STREQ(ptc::clock_source_name(0), "GPS");
  EXPECT_STREQ(ptc::clock_source_name(1), "PTP");
  EXPECT_STREQ(ptc::clock_source_name(2), "unknown");
  EXPECT_STREQ(ptc::standby_name(0), "in operation");
  EXPECT_STREQ(ptc::standby_name(1), "standby");
  EXPECT_STREQ(ptc::trigger_method_name(1), "angle-based");
  EXPECT_STREQ(ptc::motor_direction_name(1), "counter-clockwise");
  EXPECT_STREQ(ptc::on_off_name(1), "on");
  EXPECT_STREQ(ptc::on_off_name(7), "unknown");
  EXPECT_STREQ(ptc::reflectivity_mapping_name(1), "nonlinear");
}

// Pandar64 manual, Appendix B.1: which states give synchronised times.
TEST(Ptc, TimeSource) {
  ptc::Status s;
  const ptc::TimeSource by_ptp_state[4] = {ptc::TimeSource::free_run, ptc::TimeSource::ptp, ptc::TimeSource::ptp,
                                           ptc::TimeSource::free_run};
  for (std::uint8_t state = 0; state < 4; ++state) {
    s.ptp_status = state;
    EXPECT_EQ(ptc::time_source(1, s), by_ptp_state[state]) << int(state);
  }
  s.ptp_status = 2;
  EXPECT_EQ(ptc::time_source(0, s), ptc::TimeSource::free_run);  // GPS clock source, GPS unlocked
  s.gps_pps_lock = 1;
  EXPECT_EQ(ptc::time_source(0, s), ptc::TimeSource::free_run);  // PPS without the GPRMC: no date
  s.gprmc_status = 1;
  EXPECT_EQ(ptc::time_source(0, s), ptc::TimeSource::gps);
  EXPECT_EQ(ptc::time_source(7, s), ptc::TimeSource::free_run);
  EXPECT_STREQ(ptc::time_source_name(ptc::TimeSource::free_run), "free_run");
  EXPECT_STREQ(ptc::time_source_name(ptc::TimeSource::ptp), "ptp");
  EXPECT_STREQ(ptc::time_source_name(ptc::TimeSource::gps), "gps");
}

// nebula HesaiPtpDiagStatus: master_offset i64, ptp_state i32, elapsed_millisec i32, big-endian.
TEST(Ptc, PtpDiagStatus) {
  Bytes b = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFB};  // -5
  be32(b, 2);
  be32(b, 1234);
  ptc::PtpDiagStatus d;
  ASSERT_EQ(ptc::parse_ptp_diag_status(ByteView{b.data(), b.size()}, d), Error::ok);
  EXPECT_EQ(d.master_offset, -5);
  EXPECT_EQ(d.ptp_state, 2);
  EXPECT_EQ(d.elapsed_ms, 1234);
  EXPECT_EQ(ptc::parse_ptp_diag_status(ByteView{b.data(), 15}, d), Error::ptc_payload_length);
  const Bytes fov = {0x00, 0x01, 0x2C, 0x0B, 0xB8};  // method 0, 30.0 to 300.0 degrees
  ptc::Fov f;
  ASSERT_EQ(ptc::parse_fov(ByteView{fov.data(), fov.size()}, f), Error::ok);
  EXPECT_EQ(f.method, 0);
  EXPECT_EQ(f.start, 300);
  EXPECT_EQ(f.end, 3000);
  EXPECT_EQ(ptc::parse_fov(ByteView{fov.data(), 4}, f), Error::ptc_payload_length);
}
