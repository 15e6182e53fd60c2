// Zero-allocation proof for the PTC codec: a request encoded and every response parser run, on
// success and error paths, into caller storage.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include "alloc_counter.h"
#include "hesai/ptc.h"

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
