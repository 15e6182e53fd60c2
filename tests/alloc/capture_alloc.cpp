// Zero-allocation proof for the capture reader (port/): reading a whole capture, datagram by
// datagram, makes no heap allocation. Only built with the POSIX port (HESAI_BUILD_CLI).
#if defined(HESAI_HAVE_PORT)
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <vector>

#include "alloc_counter.h"
#include "hesai_port/capture.h"

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
#endif
