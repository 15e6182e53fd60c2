#include "hesai_port/net/udp.h"

#include <arpa/inet.h>
#include <cerrno>
#include <climits>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include "hesai_port/base/clock.h"

// Set by port/CMakeLists.txt: 1 for the Linux path (recvmmsg, SO_TIMESTAMPNS, SO_RXQ_OVFL).
#if !defined(HESAI_UDP_RECVMMSG)
#define HESAI_UDP_RECVMMSG 0
#endif

namespace hesai::port {

namespace {
// Each datagram's buffer holds one byte more than kMaxDatagram: a datagram that fills it is
// larger than kMaxDatagram (how the recvfrom path, which has no MSG_TRUNC flag, sees truncation).
constexpr std::size_t kSlot = UdpReceiver::kMaxDatagram + 1;
#if HESAI_UDP_RECVMMSG
constexpr std::size_t kControlEach = CMSG_SPACE(sizeof(timespec)) + CMSG_SPACE(sizeof(std::uint32_t));
#else
constexpr std::size_t kControlEach = 0;
#endif

// Whether `a` is in 224.0.0.0/4 (class D: the top four bits 1110).
bool is_multicast(in_addr a) { return (ntohl(a.s_addr) >> 28) == 0xE; }

// A UDP socket closed on exec.
int udp_socket() {
#if defined(SOCK_CLOEXEC)
  return socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
#else
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd >= 0 && fcntl(fd, F_SETFD, FD_CLOEXEC) != 0) {
    close(fd);
    return -1;
  }
  return fd;
#endif
}
}  // namespace

const char* UdpReceiver::method() { return HESAI_UDP_RECVMMSG ? "recvmmsg" : "recvfrom"; }
bool UdpReceiver::kernel_drops_known() { return HESAI_UDP_RECVMMSG != 0; }
bool UdpReceiver::kernel_timestamps() { return HESAI_UDP_RECVMMSG != 0; }

UdpReceiver::UdpReceiver() : buffers_(kBatch * kSlot), control_(kBatch * kControlEach) {}

UdpReceiver::~UdpReceiver() {
  if (fd_ >= 0) close(fd_);
}

bool is_ipv4_multicast(const std::string& address) {
  in_addr a{};
  return inet_pton(AF_INET, address.c_str(), &a) == 1 && is_multicast(a);
}

bool UdpReceiver::open(const std::string& address, std::uint16_t port, std::string& error) {
  return open(address, port, UdpReceiveOptions{}, error);
}

bool UdpReceiver::open(const std::string& address, std::uint16_t port, const UdpReceiveOptions& options,
                       std::string& error) {
  in_addr local{};
  if (inet_pton(AF_INET, address.c_str(), &local) != 1) {
    error = "not an IPv4 address: " + address;
    return false;
  }
  const std::string& group_text = options.multicast_group;
  const bool multicast = !group_text.empty();
  in_addr group{};
  if (multicast && (inet_pton(AF_INET, group_text.c_str(), &group) != 1 || !is_multicast(group))) {
    error = "not an IPv4 multicast group (224.0.0.0 to 239.255.255.255): " + group_text;
    return false;
  }
  if (options.rcvbuf_request == 0 || options.rcvbuf_request > static_cast<std::size_t>(INT_MAX)) {
    error = "receive buffer size out of range (1 to " + std::to_string(INT_MAX) + " bytes): " +
            std::to_string(options.rcvbuf_request);
    return false;
  }
  fd_ = udp_socket();
  if (fd_ < 0) {
    error = std::string("socket: ") + std::strerror(errno);
    return false;
  }
  auto fail = [&](const std::string& what) {
    error = what + ": " + std::strerror(errno);
    close(fd_);
    fd_ = -1;
    return false;
  };
  const int one = 1;
  // Several listeners may share the port (and a multicast group's datagrams).
  setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  setsockopt(fd_, SOL_SOCKET, SO_BROADCAST, &one, sizeof one);
#if HESAI_UDP_RECVMMSG
  setsockopt(fd_, SOL_SOCKET, SO_TIMESTAMPNS, &one, sizeof one);  // kernel receive time
  setsockopt(fd_, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one);     // kernel drop counter
#else
  // receive() reads until the socket is empty.
  const int flags = fcntl(fd_, F_GETFL);
  if (flags < 0 || fcntl(fd_, F_SETFL, flags | O_NONBLOCK) != 0) return fail("fcntl O_NONBLOCK");
#endif
  const int rcvbuf = static_cast<int>(options.rcvbuf_request);
  if (setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf) != 0) return fail("SO_RCVBUF");
  int reported = 0;
  socklen_t reported_len = sizeof reported;
  if (getsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &reported, &reported_len) != 0) return fail("SO_RCVBUF");
  rcvbuf_granted_ = static_cast<std::size_t>(reported) / kRcvbufReportFactor;
  // With a group: bound to the group, so that only its datagrams arrive on this socket.
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_port = htons(port);
  sa.sin_addr = multicast ? group : local;
  const std::string bound = multicast ? group_text : address;
  if (bind(fd_, reinterpret_cast<const sockaddr*>(&sa), sizeof sa) != 0)
    return fail("bind " + bound + ":" + std::to_string(port));
  if (multicast) {
    ip_mreq join{};
    join.imr_multiaddr = group;
    join.imr_interface = local;  // INADDR_ANY ("0.0.0.0"): the kernel picks the interface
    if (setsockopt(fd_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &join, sizeof join) != 0)
      return fail("join " + group_text + " on " + address);
  }
  socklen_t len = sizeof sa;
  getsockname(fd_, reinterpret_cast<sockaddr*>(&sa), &len);
  port_ = ntohs(sa.sin_port);
  return true;
}

int UdpReceiver::receive(std::vector<Datagram>& out, int timeout_ms) {
  out.clear();
  pollfd pfd{fd_, POLLIN, 0};
  const int ready = poll(&pfd, 1, timeout_ms);
  if (ready < 0) return errno == EINTR ? 0 : -1;
  if (ready == 0) return 0;

#if HESAI_UDP_RECVMMSG
  mmsghdr msgs[kBatch];
  iovec iovs[kBatch];
  sockaddr_in sources[kBatch];
  for (std::size_t i = 0; i < kBatch; ++i) {
    iovs[i].iov_base = buffers_.data() + i * kSlot;
    iovs[i].iov_len = kMaxDatagram;
    std::memset(&msgs[i], 0, sizeof msgs[i]);
    msgs[i].msg_hdr.msg_iov = &iovs[i];
    msgs[i].msg_hdr.msg_iovlen = 1;
    msgs[i].msg_hdr.msg_name = &sources[i];
    msgs[i].msg_hdr.msg_namelen = sizeof sources[i];
    msgs[i].msg_hdr.msg_control = control_.data() + i * kControlEach;
    msgs[i].msg_hdr.msg_controllen = kControlEach;
  }
  const int n = recvmmsg(fd_, msgs, kBatch, MSG_DONTWAIT, nullptr);
  if (n < 0) return (errno == EAGAIN || errno == EINTR) ? 0 : -1;
  const std::int64_t fallback = realtime_ns();
  for (int i = 0; i < n; ++i) {
    Datagram d;
    d.data = buffers_.data() + static_cast<std::size_t>(i) * kSlot;
    d.size = msgs[i].msg_len;
    d.truncated = (msgs[i].msg_hdr.msg_flags & MSG_TRUNC) != 0;
    d.time_ns = fallback;
    d.source_ipv4 = sources[i].sin_addr.s_addr;
    d.source_port = ntohs(sources[i].sin_port);
    for (cmsghdr* c = CMSG_FIRSTHDR(&msgs[i].msg_hdr); c != nullptr; c = CMSG_NXTHDR(&msgs[i].msg_hdr, c)) {
      if (c->cmsg_level != SOL_SOCKET) continue;
      if (c->cmsg_type == SCM_TIMESTAMPNS) {
        timespec ts;
        std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
        d.time_ns = static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
      } else if (c->cmsg_type == SO_RXQ_OVFL) {
        std::uint32_t drops;
        std::memcpy(&drops, CMSG_DATA(c), sizeof drops);
        kernel_drops_ = drops;
      }
    }
    out.push_back(d);
  }
  return n;
#else
  // One recvfrom per datagram on the non-blocking socket, until it is empty or kBatch are read.
  for (std::size_t i = 0; i < kBatch; ++i) {
    std::uint8_t* slot = buffers_.data() + i * kSlot;
    sockaddr_in source{};
    socklen_t source_len = sizeof source;
    const ssize_t got = recvfrom(fd_, slot, kSlot, 0, reinterpret_cast<sockaddr*>(&source), &source_len);
    if (got < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) break;
      if (out.empty()) return -1;
      break;  // the error shows again on the next call
    }
    Datagram d;
    d.data = slot;
    d.truncated = static_cast<std::size_t>(got) > kMaxDatagram;
    d.size = d.truncated ? kMaxDatagram : static_cast<std::size_t>(got);
    d.time_ns = realtime_ns();
    d.source_ipv4 = source.sin_addr.s_addr;
    d.source_port = ntohs(source.sin_port);
    out.push_back(d);
  }
  return static_cast<int>(out.size());
#endif
}

bool resolve_ipv4(const std::string& host, std::uint32_t& address, std::string& error) {
  addrinfo hints{};
  hints.ai_family = AF_INET;
  addrinfo* res = nullptr;
  if (const int rc = getaddrinfo(host.c_str(), nullptr, &hints, &res); rc != 0) {
    error = "cannot resolve " + host + ": " + gai_strerror(rc);
    return false;
  }
  sockaddr_in sa{};
  std::memcpy(&sa, res->ai_addr, sizeof sa);
  freeaddrinfo(res);
  address = sa.sin_addr.s_addr;
  return true;
}

UdpSender::~UdpSender() {
  if (fd_ >= 0) close(fd_);
}

bool UdpSender::open(const std::string& host_port, std::string& error) { return open(host_port, "", error); }

bool UdpSender::open(const std::string& host_port, const std::string& multicast_if, std::string& error) {
  const std::size_t colon = host_port.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == host_port.size()) {
    error = "expected HOST:PORT, got '" + host_port + "'";
    return false;
  }
  const std::string host = host_port.substr(0, colon);
  const std::string port = host_port.substr(colon + 1);
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* res = nullptr;
  if (const int rc = getaddrinfo(host.c_str(), port.c_str(), &hints, &res); rc != 0) {
    error = "cannot resolve " + host_port + ": " + gai_strerror(rc);
    return false;
  }
  sockaddr_in to{};
  std::memcpy(&to, res->ai_addr, sizeof to);
  const bool multicast = is_multicast(to.sin_addr);
  in_addr interface_address{};
  if (!multicast_if.empty() && (!multicast || inet_pton(AF_INET, multicast_if.c_str(), &interface_address) != 1)) {
    error = multicast ? "not an IPv4 address: " + multicast_if
                      : "a multicast interface goes with a multicast destination (224.0.0.0/4), not " + host_port;
    freeaddrinfo(res);
    return false;
  }
  fd_ = udp_socket();
  const int one = 1;
  if (fd_ >= 0) setsockopt(fd_, SOL_SOCKET, SO_BROADCAST, &one, sizeof one);
  if (fd_ >= 0 && multicast) {
    const unsigned char loop = 1;  // listeners on this host receive the group's datagrams too
    setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop);
    if (!multicast_if.empty() && setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_IF, &interface_address, sizeof interface_address) != 0) {
      error = "cannot send from " + multicast_if + ": " + std::strerror(errno);
      freeaddrinfo(res);
      close(fd_);
      fd_ = -1;
      return false;
    }
  }
  const int sndbuf = 4 * 1024 * 1024;
  if (fd_ >= 0) setsockopt(fd_, SOL_SOCKET, SO_SNDBUF, &sndbuf, sizeof sndbuf);
  if (fd_ >= 0 && (!source_.empty() || source_port_ != 0)) {
    const std::string address = source_.empty() ? "0.0.0.0" : source_;
    sockaddr_in from{};
    from.sin_family = AF_INET;
    from.sin_port = htons(source_port_);
    errno = 0;
    if (inet_pton(AF_INET, address.c_str(), &from.sin_addr) != 1 ||
        bind(fd_, reinterpret_cast<const sockaddr*>(&from), sizeof from) != 0) {
      error = "cannot send from " + address + ":" + std::to_string(source_port_) + ": " +
              (errno != 0 ? std::strerror(errno) : "not an IPv4 address");
      freeaddrinfo(res);
      close(fd_);
      fd_ = -1;
      return false;
    }
  }
  const bool ok = fd_ >= 0 && connect(fd_, res->ai_addr, res->ai_addrlen) == 0;
  freeaddrinfo(res);
  if (!ok) {
    error = "cannot open " + host_port + ": " + std::strerror(errno);
    return false;
  }
  return true;
}

bool UdpSender::send(const std::uint8_t* data, std::size_t size) {
  for (int attempt = 0; attempt < 1000; ++attempt) {
    const ssize_t n = ::send(fd_, data, size, 0);
    if (n == static_cast<ssize_t>(size)) return true;
    if (n < 0 && errno == ECONNREFUSED) return true;  // nobody listens yet: the datagram is gone, as on a wire
    if (n < 0 && errno != ENOBUFS && errno != EAGAIN && errno != EINTR) return false;
    // The send buffer is full: give the receiver a moment.
    const std::int64_t t = monotonic_ns() + 20000;
    sleep_until_ns(t);
  }
  return false;
}

}  // namespace hesai::port
