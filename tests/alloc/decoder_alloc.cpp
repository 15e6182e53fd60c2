// The decode path of every model, on the bundled real captures, allocates nothing.
#include <gtest/gtest.h>

#include "../packet_builder.h"
#include "../test_support.h"
#include "alloc_counter.h"
#include "hesai/decoder.h"

namespace {

using namespace hesai;

void decode_all_without_allocating(const char* capture, Model model) {
  const auto packets = hesai_test::pcap_payloads(capture);  // reading the file may allocate
  ASSERT_FALSE(packets.empty());
  static PacketPoints pts;
  PacketInfo info;
  std::size_t points = 0;
  Error worst = Error::ok;
  const std::size_t n = hesai_test::allocations_during([&] {
    Decoder dec(model);
    for (const auto& p : packets) {
      const Error e = dec.decode(ByteView{p.data(), p.size()}, info, pts);
      if (e != Error::ok) worst = e;
      points += pts.count;
    }
  });
  EXPECT_EQ(worst, Error::ok);
  EXPECT_GT(points, 0u);
  EXPECT_EQ(n, 0u) << capture;
}

TEST(ZeroAllocation, DecodePandar40P) { decode_all_without_allocating("pandar40p_dual.pcap", Model::pandar40p); }
TEST(ZeroAllocation, DecodePandar64) { decode_all_without_allocating("pandar64_dual.pcap", Model::pandar64); }
TEST(ZeroAllocation, DecodeQt128) { decode_all_without_allocating("qt128c2x_dual.pcap", Model::qt128c2x); }

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

}  // namespace
