// Live UDP: a receiver and a sender (the clocks they stamp and pace by: hesai_port/base/clock.h).
//
// The receiver has two paths, chosen at configure time (port/CMakeLists.txt): on Linux, recvmmsg
// batches with kernel receive timestamps (SO_TIMESTAMPNS) and the kernel's drop counter
// (SO_RXQ_OVFL); on other POSIX systems, or with -DHESAI_PORTABLE_UDP=ON, plain recvfrom, one
// call per datagram, each stamped with the clock when it is read, and no drop counter.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hesai::port {

/// One received datagram; `data` points into the receiver's buffers until the next receive().
struct Datagram {
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
  std::int64_t time_ns = 0;  ///< kernel receive time (SO_TIMESTAMPNS) or, without it, realtime_ns() when read
  bool truncated = false;    ///< larger than the buffer (MSG_TRUNC): not a sensor packet
  std::uint32_t source_ipv4 = 0;  ///< sender's IPv4 address as in in_addr.s_addr (network byte order)
  std::uint16_t source_port = 0;  ///< sender's UDP port
};

/// The IPv4 address of `host` (a dotted quad or a name) as in in_addr.s_addr. False with a message.
bool resolve_ipv4(const std::string& host, std::uint32_t& address, std::string& error);

/// How a UdpReceiver opens its socket, beyond the address and port.
struct UdpReceiveOptions {
  /// IPv4 multicast group (224.0.0.0/4) to join, or empty for none. With a group, the socket is
  /// bound to the group and the port (so only the group's datagrams arrive) and joins it on the
  /// interface of the local address given to open() ("0.0.0.0": the kernel picks one).
  std::string multicast_group;
  /// Receive buffer requested (SO_RCVBUF); the kernel caps it at net.core.rmem_max.
  std::size_t rcvbuf_request = 16 * 1024 * 1024;  ///< about 7 s of a QT128 stream
};

/// Whether `address` is an IPv4 dotted quad in the multicast range 224.0.0.0/4.
bool is_ipv4_multicast(const std::string& address);

/// A UDP socket bound to an address and port that receives up to kBatch datagrams per call.
class UdpReceiver {
 public:
  static constexpr std::size_t kBatch = 64;
  static constexpr std::size_t kMaxDatagram = 2048;  ///< larger than any sensor packet

  /// The receive path built in: "recvmmsg" (Linux) or "recvfrom" (portable).
  static const char* method();
  /// Whether kernel_drops() counts anything: true on the recvmmsg path only.
  static bool kernel_drops_known();
  /// Whether Datagram::time_ns is the kernel's receive time (SO_TIMESTAMPNS): true on the
  /// recvmmsg path only (the portable path stamps a datagram when it is read).
  static bool kernel_timestamps();

  UdpReceiver();
  ~UdpReceiver();
  UdpReceiver(const UdpReceiver&) = delete;
  UdpReceiver& operator=(const UdpReceiver&) = delete;

  /// Binds to `address` (IPv4 dotted quad, "0.0.0.0" for all) and `port` (0: any free port).
  /// Returns false with a message in `error`.
  bool open(const std::string& address, std::uint16_t port, std::string& error);
  /// As above, with a multicast group to join and the receive buffer to request.
  bool open(const std::string& address, std::uint16_t port, const UdpReceiveOptions& options, std::string& error);
  /// getsockopt(SO_RCVBUF) reports this many times the usable size: 2 on Linux (socket(7): the
  /// kernel doubles the value set, for its bookkeeping), 1 elsewhere.
  static constexpr std::size_t kRcvbufReportFactor =
#if defined(__linux__)
      2;
#else
      1;
#endif
  /// The receive buffer the kernel granted, in usable bytes (what getsockopt reports, divided by
  /// kRcvbufReportFactor).
  std::size_t rcvbuf_granted() const { return rcvbuf_granted_; }
  /// The bound port (useful after binding port 0).
  std::uint16_t port() const { return port_; }
  int fd() const { return fd_; }
  /// Receives up to kBatch datagrams, waiting at most `timeout_ms` (0: poll, -1: forever).
  /// Returns how many were received into `out` (0 on timeout), or -1 on a socket error.
  int receive(std::vector<Datagram>& out, int timeout_ms);
  /// Datagrams the kernel dropped because the socket buffer was full (SO_RXQ_OVFL); always 0
  /// when !kernel_drops_known().
  std::uint64_t kernel_drops() const { return kernel_drops_; }

 private:
  int fd_ = -1;
  std::uint16_t port_ = 0;
  std::uint64_t kernel_drops_ = 0;
  std::size_t rcvbuf_granted_ = 0;
  std::vector<std::uint8_t> buffers_;
  std::vector<std::uint8_t> control_;
};

/// A UDP socket that sends datagrams to one destination.
class UdpSender {
 public:
  UdpSender() = default;
  ~UdpSender();
  UdpSender(const UdpSender&) = delete;
  UdpSender& operator=(const UdpSender&) = delete;

  /// Resolves "HOST:PORT" (IPv4 address or host name). Returns false with a message.
  bool open(const std::string& host_port, std::string& error);
  /// As above; when HOST is a multicast group, its datagrams leave through the interface of
  /// `multicast_if` (an IPv4 address; empty: the kernel's route for the group) and are looped
  /// back to listeners on this host.
  bool open(const std::string& host_port, const std::string& multicast_if, std::string& error);
  /// Before open(): send from this local IPv4 address (as a sensor sends from its own address)
  /// instead of the one the kernel picks, and from UDP port `port` (0: one the kernel picks), as a
  /// unit sends from a fixed port.
  void set_source(const std::string& address, std::uint16_t port = 0) {
    source_ = address;
    source_port_ = port;
  }
  /// Sends one datagram; returns false on a socket error (retries briefly when the send
  /// buffer is full).
  bool send(const std::uint8_t* data, std::size_t size);

 private:
  int fd_ = -1;
  std::string source_;
  std::uint16_t source_port_ = 0;
};

}  // namespace hesai::port
