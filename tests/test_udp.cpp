// The live UDP receiver and sender over 127.0.0.1, on the receive path the build chose
// (recvmmsg on Linux, recvfrom with -DHESAI_PORTABLE_UDP=ON or elsewhere).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "hesai_port/base/clock.h"
#include "hesai_port/net/udp.h"
#include "udp_support.h"

using hesai::port::Datagram;
using hesai::port::UdpReceiveOptions;
using hesai::port::UdpReceiver;
using hesai::port::UdpSender;

namespace {

// A receiver on 127.0.0.1 (any free port) and a sender to it.
struct Loopback {
  UdpReceiver rx;
  UdpSender tx;
  bool open() {
    std::string error;
    EXPECT_TRUE(rx.open("127.0.0.1", 0, error)) << error;
    EXPECT_TRUE(tx.open("127.0.0.1:" + std::to_string(rx.port()), error)) << error;
    return error.empty();
  }
  // Receives until `n` datagrams came (copied out) or none came for 1 s.
  std::vector<std::vector<std::uint8_t>> receive(std::size_t n, std::vector<Datagram>* meta = nullptr) {
    std::vector<std::vector<std::uint8_t>> got;
    std::vector<Datagram> batch;
    while (got.size() < n) {
      EXPECT_GE(rx.receive(batch, 1000), 0);
      if (batch.empty()) break;
      for (const Datagram& d : batch) {
        got.emplace_back(d.data, d.data + d.size);
        if (meta) meta->push_back(d);
      }
    }
    return got;
  }
};

std::vector<std::uint8_t> pattern(std::size_t size, std::uint8_t seed) {
  std::vector<std::uint8_t> v(size);
  for (std::size_t i = 0; i < size; ++i) v[i] = static_cast<std::uint8_t>(seed + i * 7);
  return v;
}

}  // namespace

// The path is the one configured: recvfrom when forced by HESAI_PORTABLE_UDP, recvmmsg on Linux
// otherwise (tests/CMakeLists.txt states the expectation from the option and the system name).
TEST(Udp, ReceivePathIsTheConfiguredOne) {
  EXPECT_STREQ(UdpReceiver::method(), HESAI_TEST_UDP_METHOD);
  EXPECT_EQ(UdpReceiver::kernel_drops_known(), std::string(HESAI_TEST_UDP_METHOD) == "recvmmsg");
}

// Sizes from 1 byte to kMaxDatagram arrive whole, in order, stamped between the send and the
// receive; a datagram larger than kMaxDatagram is flagged truncated and cut to kMaxDatagram.
TEST(Udp, ReceivesWhatWasSent) {
  Loopback l;
  ASSERT_TRUE(l.open());
  const std::vector<std::size_t> sizes = {1, 1200, UdpReceiver::kMaxDatagram, UdpReceiver::kMaxDatagram + 100};
  [[maybe_unused]] const std::int64_t before = hesai::port::realtime_ns();  // not read under qemu-user
  for (std::size_t i = 0; i < sizes.size(); ++i)
    ASSERT_TRUE(l.tx.send(pattern(sizes[i], static_cast<std::uint8_t>(i)).data(), sizes[i]));
  std::vector<Datagram> meta;
  const auto got = l.receive(sizes.size(), &meta);
  [[maybe_unused]] const std::int64_t after = hesai::port::realtime_ns();
  ASSERT_EQ(got.size(), sizes.size());
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const bool too_big = sizes[i] > UdpReceiver::kMaxDatagram;
    EXPECT_EQ(meta[i].truncated, too_big) << i;
    std::vector<std::uint8_t> expected = pattern(sizes[i], static_cast<std::uint8_t>(i));
    expected.resize(too_big ? UdpReceiver::kMaxDatagram : sizes[i]);
    EXPECT_EQ(got[i], expected) << i;
#if !defined(HESAI_CLI_EMULATOR)  // qemu-user need not translate the kernel's timestamp message
    EXPECT_GE(meta[i].time_ns, before) << i;
    EXPECT_LE(meta[i].time_ns, after) << i;
#endif
  }
}

// More datagrams than the socket buffer holds, sent before any is read: every one is either
// received or counted by the kernel (recvmmsg path), exactly. The counter travels with the next
// datagram queued, so one more is sent once the socket is drained. The portable path has no
// counter: it reports 0, and receives no more than was sent.
TEST(Udp, KernelDropsAccountForEveryDatagram) {
#if defined(HESAI_CLI_EMULATOR)
  GTEST_SKIP() << "qemu-user need not translate the kernel's drop-counter message: runs natively only";
#endif
  Loopback l;
  ASSERT_TRUE(l.open());
  const std::size_t flood = 10000;  // 12 MB of payload: beyond the buffer net.core.rmem_max allows here
  const std::vector<std::uint8_t> p = pattern(1200, 1);
  for (std::size_t i = 0; i < flood; ++i) ASSERT_TRUE(l.tx.send(p.data(), p.size()));
  std::size_t received = l.receive(flood).size();
  ASSERT_TRUE(l.tx.send(p.data(), p.size()));
  received += l.receive(1).size();
  RecordProperty("received", std::to_string(received));
  RecordProperty("kernel_drops", std::to_string(l.rx.kernel_drops()));
  if (UdpReceiver::kernel_drops_known()) {
    EXPECT_EQ(received + l.rx.kernel_drops(), flood + 1) << received << " received";
  } else {
    EXPECT_EQ(l.rx.kernel_drops(), 0u);
    EXPECT_LE(received, flood + 1);
  }
}

// A receiver that joined a multicast group on 127.0.0.1 gets what is sent to the group through
// 127.0.0.1; so does a second receiver sharing the port (SO_REUSEADDR), and a datagram sent to the
// port on 127.0.0.1 itself does not reach them (they are bound to the group). In a network
// namespace of the test's own where it can make one (root: CI), else on the host's loopback.
namespace {

void multicast_group_on_loopback(const char* group) {
  UdpReceiveOptions options;
  options.multicast_group = group;
  UdpReceiver first, second;
  std::string error;
  ASSERT_TRUE(first.open("127.0.0.1", 0, options, error)) << error;
  ASSERT_TRUE(second.open("127.0.0.1", first.port(), options, error)) << error;
  UdpSender to_group, to_port;
  ASSERT_TRUE(to_group.open(std::string(group) + ":" + std::to_string(first.port()), "127.0.0.1", error)) << error;
  ASSERT_TRUE(to_port.open("127.0.0.1:" + std::to_string(first.port()), error)) << error;
  ASSERT_TRUE(to_port.send(pattern(100, 9).data(), 100));
  for (std::uint8_t i = 0; i < 5; ++i) ASSERT_TRUE(to_group.send(pattern(1200, i).data(), 1200));
  for (UdpReceiver* rx : {&first, &second}) {
    std::vector<std::vector<std::uint8_t>> got;
    std::vector<Datagram> batch;
    while (got.size() < 5 && rx->receive(batch, 1000) > 0)
      for (const Datagram& d : batch) got.emplace_back(d.data, d.data + d.size);
    EXPECT_EQ(rx->receive(batch, 100), 0);  // nothing else: not the datagram to 127.0.0.1
    ASSERT_EQ(got.size(), 5u);
    for (std::uint8_t i = 0; i < 5; ++i) EXPECT_EQ(got[i], pattern(1200, i)) << int{i};
  }
}

}  // namespace

TEST(Udp, MulticastGroupOnLoopback) {
  const char* group = "239.255.14.1";
  std::string why;
  const auto where = hesai_test::multicast_loopback(group, [&] { multicast_group_on_loopback(group); }, why);
  if (where == hesai_test::MulticastNet::none) GTEST_SKIP() << why;
  RecordProperty("network", hesai_test::multicast_net_name(where));
  std::printf("ran in %s\n", hesai_test::multicast_net_name(where));
}

// A group outside 224.0.0.0/4 is refused before any socket opens; so is a multicast interface
// for a destination that is not a group.
TEST(Udp, MulticastNeedsAGroup) {
  EXPECT_TRUE(hesai::port::is_ipv4_multicast("224.0.0.0"));
  EXPECT_TRUE(hesai::port::is_ipv4_multicast("239.255.255.255"));
  for (const char* not_group : {"223.255.255.255", "240.0.0.0", "127.0.0.1", "0.0.0.0", "239.1.2", "group", ""})
    EXPECT_FALSE(hesai::port::is_ipv4_multicast(not_group)) << not_group;
  UdpReceiveOptions options;
  options.multicast_group = "10.1.2.3";
  UdpReceiver rx;
  std::string error;
  EXPECT_FALSE(rx.open("127.0.0.1", 0, options, error));
  EXPECT_NE(error.find("10.1.2.3"), std::string::npos) << error;
  EXPECT_LT(rx.fd(), 0);
  UdpSender tx;
  error.clear();
  EXPECT_FALSE(tx.open("127.0.0.1:2368", "127.0.0.1", error));
  EXPECT_NE(error.find("multicast"), std::string::npos) << error;
}

// SO_RCVBUF as socket(7) specifies it on Linux: the kernel grants min(request, rmem_max) (and
// reports twice that; rcvbuf_granted() is the usable half).
TEST(Udp, ReceiveBufferIsWhatTheKernelGranted) {
#if !defined(__linux__)
  GTEST_SKIP() << "net.core.rmem_max and the doubled report are Linux's";
#endif
  const std::size_t limit = hesai_test::rmem_max();
  if (limit == 0) GTEST_SKIP() << "/proc/sys/net/core/rmem_max is not readable";
  for (const std::size_t request : {std::size_t{65536}, limit, limit + 1024 * 1024}) {
    UdpReceiveOptions options;
    options.rcvbuf_request = request;
    UdpReceiver rx;
    std::string error;
    ASSERT_TRUE(rx.open("127.0.0.1", 0, options, error)) << error;
    EXPECT_EQ(rx.rcvbuf_granted(), std::min(request, limit)) << request;
  }
  UdpReceiveOptions zero;
  zero.rcvbuf_request = 0;
  UdpReceiver rx;
  std::string error;
  EXPECT_FALSE(rx.open("127.0.0.1", 0, zero, error));
}
