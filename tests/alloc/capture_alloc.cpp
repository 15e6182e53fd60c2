// Zero-allocation proof for the capture reader (port/): reading a whole capture, datagram by
// datagram, makes no heap allocation. Only built with the POSIX port (HESAI_BUILD_CLI).
#if defined(HESAI_HAVE_PORT)
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "alloc_counter.h"
#include "hesai_port/base/crc32_ieee.h"
#include "hesai_port/capture/capture.h"
#include "hesai_port/capture/mcap_parser.h"

TEST(ZeroAllocation, CaptureParser) {
  std::ifstream in(HESAI_DATA_DIR "/pandar64_dual.pcap", std::ios::binary);
  const std::vector<std::uint8_t> file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(file.empty());

  hesai::port::CaptureParser parser;
  hesai::port::UdpDatagram d;
  std::size_t datagrams = 0;
  hesai::port::CaptureError opened = hesai::port::CaptureError::not_open, reopened = opened;
  const std::size_t n = hesai_test::allocations_during([&] {
    opened = parser.open(hesai::ByteView{file.data(), file.size()});
    while (parser.next(d) == hesai::port::CaptureStatus::datagram) ++datagrams;
    reopened = parser.open(hesai::ByteView{file.data(), file.size() - 7});  // an error path too
    while (parser.next(d) == hesai::port::CaptureStatus::datagram) {
    }
  });
  EXPECT_EQ(n, 0u);
  EXPECT_EQ(opened, hesai::port::CaptureError::ok);
  EXPECT_EQ(datagrams, 2400u);
  EXPECT_EQ(reopened, hesai::port::CaptureError::ok);  // the file header is whole; the last record is cut
  EXPECT_EQ(parser.error(), hesai::port::CaptureError::truncated);
}

TEST(ZeroAllocation, CaptureFileNext) {
  hesai::port::CaptureFile f;
  ASSERT_EQ(f.open(HESAI_DATA_DIR "/qt128c2x_dual.pcap"), hesai::port::CaptureError::ok);
  hesai::port::UdpDatagram d;
  std::size_t datagrams = 0;
  const std::size_t n = hesai_test::allocations_during([&] {
    while (f.parser().next(d) == hesai::port::CaptureStatus::datagram) ++datagrams;
  });
  EXPECT_EQ(n, 0u);
  EXPECT_EQ(datagrams, 1800u);
}
namespace {

// A small MCAP file of one PandarScan message with `packets` copies of a 1198-byte packet, in an
// uncompressed chunk with its CRC (layout: the MCAP spec; CDR: see hesai_port/capture/mcap_parser.h).
std::vector<std::uint8_t> pandar_scan_mcap(std::size_t packets) {
  std::vector<std::uint8_t> f = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
  auto le = [](std::vector<std::uint8_t>& v, std::uint64_t x, int n) {
    for (int i = 0; i < n; ++i) v.push_back(static_cast<std::uint8_t>(x >> (8 * i)));
  };
  auto str = [&](std::vector<std::uint8_t>& v, const std::string& s) {
    le(v, s.size(), 4);
    v.insert(v.end(), s.begin(), s.end());
  };
  auto rec = [&](std::vector<std::uint8_t>& v, std::uint8_t op, const std::vector<std::uint8_t>& body) {
    v.push_back(op);
    le(v, body.size(), 8);
    v.insert(v.end(), body.begin(), body.end());
  };
  std::vector<std::uint8_t> b;
  str(b, "ros2");
  str(b, "alloc test");
  rec(f, 0x01, b);
  std::vector<std::uint8_t> chunk;
  b.clear();
  le(b, 1, 2);
  str(b, "pandar_msgs/msg/PandarScan");
  str(b, "ros2msg");
  str(b, "");
  rec(chunk, 0x03, b);
  b.clear();
  le(b, 1, 2);
  le(b, 1, 2);
  str(b, "/pandar_packets");
  str(b, "cdr");
  le(b, 0, 4);
  rec(chunk, 0x04, b);
  b.clear();
  le(b, 1, 2);
  le(b, 0, 4);
  le(b, 0, 8);
  le(b, 0, 8);
  const std::vector<std::uint8_t> cdr_header = {0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};  // encapsulation, stamp
  b.insert(b.end(), cdr_header.begin(), cdr_header.end());
  str(b, std::string("hesai\0", 6));  // frame_id; 2 bytes of padding follow
  le(b, 0, 2);
  le(b, packets, 4);
  for (std::size_t i = 0; i < packets; ++i) {
    le(b, 1593086529 + i, 4);
    le(b, 0, 4);
    for (std::size_t k = 0; k < 1500; ++k) b.push_back(static_cast<std::uint8_t>(k));
    le(b, 1198, 4);
  }
  rec(chunk, 0x05, b);
  b.clear();
  for (int i = 0; i < 3; ++i) le(b, i < 2 ? 0 : chunk.size(), 8);
  le(b, hesai::port::crc32_ieee(chunk.data(), chunk.size()), 4);
  str(b, "");
  le(b, chunk.size(), 8);
  b.insert(b.end(), chunk.begin(), chunk.end());
  rec(f, 0x06, b);
  b.clear();
  le(b, 0, 4);
  rec(f, 0x0F, b);  // Data End
  b.clear();
  le(b, 0, 8);
  le(b, 0, 8);
  le(b, 0, 4);
  rec(f, 0x02, b);  // Footer: no summary section
  f.insert(f.end(), {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'});
  return f;
}

// After the chunk: Data End (9 + 4 bytes), Footer (9 + 20), the closing magic (8).
constexpr std::size_t kMcapTail = 13 + 29 + 8;

}  // namespace

TEST(ZeroAllocation, McapParser) {
  const std::vector<std::uint8_t> file = pandar_scan_mcap(5);
  static hesai::port::McapParser parser;  // its id tables are 32 KiB
  hesai::port::UdpDatagram d;
  std::size_t datagrams = 0;
  std::size_t bytes = 0;
  hesai::port::CaptureError opened = hesai::port::CaptureError::not_open;
  hesai::port::CaptureStatus last = hesai::port::CaptureStatus::datagram;
  hesai::port::CaptureError cut_error = hesai::port::CaptureError::ok;
  const std::size_t n = hesai_test::allocations_during([&] {
    opened = parser.open(hesai::ByteView{file.data(), file.size()});
    while ((last = parser.next(d)) == hesai::port::CaptureStatus::datagram) {
      ++datagrams;
      bytes += d.payload.size;
    }
    if (parser.open(hesai::ByteView{file.data(), file.size() - kMcapTail - 20}) == hesai::port::CaptureError::ok) {
      while (parser.next(d) == hesai::port::CaptureStatus::datagram) {
      }
    }
    cut_error = parser.error();
  });
  EXPECT_EQ(n, 0u);
  EXPECT_EQ(opened, hesai::port::CaptureError::ok);
  EXPECT_EQ(last, hesai::port::CaptureStatus::end);
  EXPECT_EQ(datagrams, 5u);
  EXPECT_EQ(bytes, 5u * 1198u);
  EXPECT_EQ(cut_error, hesai::port::CaptureError::truncated);  // the chunk record passes the end
}
#endif
