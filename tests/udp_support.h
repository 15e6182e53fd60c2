// Test-only helpers for the live UDP tests, on plain POSIX sockets (not the port's code): whether
// this machine's loopback carries multicast, a network namespace of the test's own whose loopback
// does, and the kernel's receive-buffer limit.
#pragma once

#include <arpa/inet.h>
#include <net/if.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>
#if defined(__linux__)
#include <sched.h>
#endif

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>

namespace hesai_test {

/// Empty when a datagram sent to IPv4 multicast `group` through 127.0.0.1 (IP_MULTICAST_IF,
/// IP_MULTICAST_LOOP) reaches a socket that joined `group` on 127.0.0.1 within a second;
/// otherwise why not (for GTEST_SKIP: some sandboxes give the loopback no multicast).
inline std::string loopback_multicast_missing(const char* group) {
  in_addr g{}, lo{};
  inet_pton(AF_INET, group, &g);
  inet_pton(AF_INET, "127.0.0.1", &lo);
  const int rx = socket(AF_INET, SOCK_DGRAM, 0), tx = socket(AF_INET, SOCK_DGRAM, 0);
  std::string why;
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_addr = g;
  socklen_t len = sizeof sa;
  ip_mreq join{};
  join.imr_multiaddr = g;
  join.imr_interface = lo;
  const unsigned char loop = 1;
  const char probe = 'p';
  pollfd pfd{rx, POLLIN, 0};
  if (rx < 0 || tx < 0) why = std::string("socket: ") + std::strerror(errno);
  else if (bind(rx, reinterpret_cast<const sockaddr*>(&sa), sizeof sa) != 0 ||
           getsockname(rx, reinterpret_cast<sockaddr*>(&sa), &len) != 0)
    why = std::string("bind to ") + group + ": " + std::strerror(errno);
  else if (setsockopt(rx, IPPROTO_IP, IP_ADD_MEMBERSHIP, &join, sizeof join) != 0)
    why = std::string("join ") + group + " on 127.0.0.1: " + std::strerror(errno);
  else if (setsockopt(tx, IPPROTO_IP, IP_MULTICAST_IF, &lo, sizeof lo) != 0 ||
           setsockopt(tx, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop) != 0)
    why = std::string("multicast through 127.0.0.1: ") + std::strerror(errno);
  else if (sendto(tx, &probe, 1, 0, reinterpret_cast<const sockaddr*>(&sa), sizeof sa) != 1)
    why = std::string("send to ") + group + " through 127.0.0.1: " + std::strerror(errno);
  else if (poll(&pfd, 1, 1000) != 1)
    why = std::string("a datagram sent to ") + group + " through 127.0.0.1 did not come back within 1 s";
  if (rx >= 0) close(rx);
  if (tx >= 0) close(tx);
  return why.empty() ? why : "no multicast on the loopback here (" + why + ")";
}

/// Where multicast_loopback() ran a test body.
enum class MulticastNet { none, private_namespace, host_loopback };

inline const char* multicast_net_name(MulticastNet n) {
  switch (n) {
    case MulticastNet::private_namespace: return "a network namespace of the test's own";
    case MulticastNet::host_loopback: return "the host's loopback";
    case MulticastNet::none: break;
  }
  return "nowhere";
}

/// Runs `body` where IPv4 multicast to `group` through 127.0.0.1 works, and says where:
/// - first in a network namespace of its own (Linux, root or CAP_SYS_ADMIN): a thread that
///   unshare(CLONE_NEWNET)s, sets that namespace's loopback up with IFF_MULTICAST (SIOCSIFFLAGS)
///   and checks it with loopback_multicast_missing(); `body` runs on that thread, so the sockets
///   it opens and the processes it starts (fork copies the thread's namespace) live there and
///   reach nothing else; the namespace goes when the thread has ended and they are closed. The
///   host's interfaces and routes are not touched.
/// - else on the host's loopback, when loopback_multicast_missing() finds it carries multicast.
/// MulticastNet::none and `why` (for GTEST_SKIP) when neither does; then `body` did not run.
/// Inside `body` gtest's EXPECT and ASSERT work as on the test's own thread (ASSERT returns from
/// `body`); read /proc/thread-self/net, not /proc/net (the main thread's namespace).
template <typename F>
MulticastNet multicast_loopback(const char* group, F&& body, std::string& why) {
  std::string private_why = "network namespaces are Linux's";
#if defined(__linux__)
  bool ran = false;
  std::thread own([&] {
    if (unshare(CLONE_NEWNET) != 0) {
      private_why = std::string("unshare(CLONE_NEWNET): ") + std::strerror(errno);
      return;
    }
    const int fd = socket(AF_INET, SOCK_DGRAM, 0);
    ifreq lo{};
    std::strncpy(lo.ifr_name, "lo", IFNAMSIZ - 1);
    if (fd < 0 || ioctl(fd, SIOCGIFFLAGS, &lo) != 0) {
      private_why = std::string("the namespace's loopback: ") + std::strerror(errno);
    } else {
      lo.ifr_flags = static_cast<short>(lo.ifr_flags | IFF_UP | IFF_MULTICAST);
      if (ioctl(fd, SIOCSIFFLAGS, &lo) != 0)
        private_why = std::string("loopback up with multicast: ") + std::strerror(errno);
      else
        private_why = loopback_multicast_missing(group);
    }
    if (fd >= 0) close(fd);
    if (!private_why.empty()) return;
    ran = true;
    body();
  });
  own.join();
  if (ran) return MulticastNet::private_namespace;
#endif
  const std::string host_why = loopback_multicast_missing(group);
  if (host_why.empty()) {
    body();
    return MulticastNet::host_loopback;
  }
  why = "no network namespace of our own (" + private_why + "), and " + host_why;
  return MulticastNet::none;
}

/// net.core.rmem_max, the most SO_RCVBUF grants (socket(7); only SO_RCVBUFFORCE, which the port
/// does not use, goes beyond); 0 when /proc does not tell.
inline std::size_t rmem_max() {
  std::ifstream f("/proc/sys/net/core/rmem_max");
  std::size_t n = 0;
  f >> n;
  return f ? n : 0;
}

// A UDP port that is free on 127.0.0.1 now (the kernel picks it).
inline int free_udp_port() {
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof sa;
  if (bind(fd, reinterpret_cast<const sockaddr*>(&sa), sizeof sa) != 0 ||
      getsockname(fd, reinterpret_cast<sockaddr*>(&sa), &len) != 0) {
    close(fd);
    return 0;
  }
  close(fd);
  return ntohs(sa.sin_port);
}

// Waits until a socket is bound to UDP `address`:`port` (an IPv4 dotted quad), as /proc/net/udp
// lists it: the address as the kernel holds it (network byte order) printed as a host integer
// (passive: probing with a bind of our own could make the listener's bind fail).
inline bool wait_for_listener(int port, const char* address = "127.0.0.1") {
  in_addr a{};
  inet_pton(AF_INET, address, &a);
  // The kernel prints the address's four bytes as a u32 in its own byte order, which a test under
  // qemu-user for a target of the other byte order (s390x on x86-64) cannot know: accept either.
  const unsigned raw = static_cast<unsigned>(a.s_addr);
  const unsigned swapped = (raw >> 24) | ((raw >> 8) & 0xFF00u) | ((raw << 8) & 0xFF0000u) | (raw << 24);
  char local[32], local_swapped[32];
  std::snprintf(local, sizeof local, "%08X:%04X", raw, port);
  std::snprintf(local_swapped, sizeof local_swapped, "%08X:%04X", swapped, port);
  // The calling thread's namespace (multicast_loopback may have given it one of its own);
  // /proc/net is the main thread's. Kernels before 3.17 have no thread-self.
  const char* table = access("/proc/thread-self/net/udp", R_OK) == 0 ? "/proc/thread-self/net/udp" : "/proc/net/udp";
  for (int i = 0; i < 400; ++i) {
    std::ifstream f(table);
    std::string line;
    while (std::getline(f, line))
      if (line.find(local) != std::string::npos || line.find(local_swapped) != std::string::npos) return true;
    usleep(50000);
  }
  return false;
}

}  // namespace hesai_test
