// The decode path of every model, on the bundled real captures, allocates nothing.
#include <gtest/gtest.h>

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
  const auto packets = hesai_test::pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_FALSE(packets.empty());
  static PacketPoints pts;
  PacketInfo info;
  std::uint8_t key[32] = {1, 2, 3};
  const std::size_t n = hesai_test::allocations_during([&] {
    Decoder dec(Model::qt128c2x);
    dec.set_session_key(key);
    dec.set_allow_unsigned(true);
    for (const auto& p : packets) dec.decode(ByteView{p.data(), p.size()}, info, pts);
  });
  EXPECT_EQ(n, 0u);
}

}  // namespace
