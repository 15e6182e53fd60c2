// Zero-allocation proof for the PTC codec: a request encoded and every response parser run, on
// success and error paths, into caller storage.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include "alloc_counter.h"
#include "hesai/ptc.h"
#include "hesai/ptc_settings.h"

TEST(ZeroAllocation, PtcCodec) {
  namespace ptc = hesai::ptc;
  using hesai::ByteView;
  using hesai::Error;
  std::array<std::uint8_t, 256> payload{};  // zeros: long enough for every layout
  payload[108] = 32;                          // QT128 inventory: product model 32 and 128 lines
  payload[110] = 128;
  const std::array<std::uint8_t, 8> header = {0x47, 0x74, 0x07, 0x00, 0x00, 0x00, 0x00, 0x90};
  std::array<std::uint8_t, 64> out{};
  std::uint8_t random[32];
  Error e[9] = {};
  const std::size_t n = hesai_test::allocations_during([&] {
    std::size_t written = 0;
    ptc::Header h;
    ptc::Inventory inv;
    ptc::Config cfg;
    ptc::Status st;
    bool on = false;
    e[0] = ptc::encode_request(ptc::Command::signature_start, ByteView{payload.data(), 32}, out.data(), out.size(), written);
    e[1] = ptc::check_response(ByteView{header.data(), header.size()}, ptc::Command::inventory, 4096, h);
    e[2] = ptc::check_response(ByteView{header.data(), header.size()}, ptc::Command::status, 4096, h);  // mismatch
    e[3] = ptc::parse_inventory(ByteView{payload.data(), 144}, inv);
    e[4] = ptc::parse_config(ByteView{payload.data(), 47}, cfg);
    e[5] = ptc::parse_status(ByteView{payload.data(), 58}, hesai::Model::qt128c2x, st);
    e[6] = ptc::parse_status(ByteView{payload.data(), 20}, hesai::Model::pandar64, st);  // too short
    e[7] = ptc::parse_session_start(ByteView{payload.data(), 32}, random);
    e[8] = ptc::parse_signature_state(ByteView{payload.data(), 1}, on);
  });
  EXPECT_EQ(n, 0u);
  const Error expected[9] = {Error::ok, Error::ok, Error::ptc_command_mismatch, Error::ok, Error::ok,
                             Error::ok, Error::ptc_payload_length, Error::ok, Error::ok};
  for (int i = 0; i < 9; ++i) EXPECT_EQ(e[i], expected[i]) << i;
}

// The settings (hesai/ptc_settings.h): every set payload encoded and read back, the read-back from
// a configuration, the allowed values and the names, into caller storage.
TEST(ZeroAllocation, PtcSettings) {
  namespace ptc = hesai::ptc;
  using hesai::ByteView;
  using hesai::Error;
  std::array<std::uint8_t, 64> config{};
  Error e[ptc::kSettingCount + 3] = {};
  bool same = true;
  std::size_t named = 0;
  const std::size_t n = hesai_test::allocations_during([&] {
    ptc::Config cfg;
    e[0] = ptc::parse_config(ByteView{config.data(), 47}, cfg);
    ptc::Settings current, back;
    ptc::settings_from_config(cfg, current);
    for (std::size_t i = 0; i < ptc::kSettingCount; ++i) {
      const auto s = static_cast<ptc::Setting>(i);
      std::uint8_t payload[ptc::kMaxSetPayloadBytes];
      std::size_t size = 0;
      ptc::encode_setting(s, current, payload, size);
      ptc::Setting read;
      e[1 + i] = ptc::parse_setting(static_cast<std::uint8_t>(ptc::set_command(s)), ByteView{payload, size}, read, back);
      same = same && ptc::same_setting(s, current, back);
    }
    std::uint16_t rates[ptc::kMaxSpinRates];
    named += ptc::allowed_spin_rates(hesai::Model::qt128c2x, rates);
    std::uint8_t code = 0;
    named += ptc::return_mode_code(hesai::Model::pandar_xt32, "last_first", 10, code) ? std::size_t{code} : 0u;
    named += ptc::return_mode_name(hesai::Model::pandar64, 7) == nullptr;
    ptc::Fov fov;
    ptc::PtpDiagStatus diag;
    e[ptc::kSettingCount + 1] = ptc::parse_fov(ByteView{config.data(), 5}, fov);
    e[ptc::kSettingCount + 2] = ptc::parse_ptp_diag_status(ByteView{config.data(), 15}, diag);  // too short
  });
  EXPECT_EQ(n, 0u);
  for (std::size_t i = 0; i <= ptc::kSettingCount + 1; ++i) EXPECT_EQ(e[i], Error::ok) << i;
  EXPECT_EQ(e[ptc::kSettingCount + 2], Error::ptc_payload_length);
  EXPECT_TRUE(same);
  EXPECT_EQ(named, 2u + 4u + 1u);  // two rates, code 4, no mode 7
}
