// Live UDP: a batched receiver with kernel receive timestamps, a sender, and clocks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hesai::port {

/// Wall-clock time, ns since the Unix epoch (CLOCK_REALTIME).
std::int64_t realtime_ns();
/// Monotonic time, ns (CLOCK_MONOTONIC), for pacing and timeouts.
std::int64_t monotonic_ns();
/// Sleeps until the monotonic clock reaches `deadline_ns`.
void sleep_until_ns(std::int64_t deadline_ns);

/// One received datagram; `data` points into the receiver's buffers until the next receive().
struct Datagram {
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
  std::int64_t time_ns = 0;  ///< kernel receive time (SO_TIMESTAMPNS) or, without it, realtime_ns()
  bool truncated = false;    ///< larger than the buffer (MSG_TRUNC): not a sensor packet
};

/// A UDP socket bound to an address and port that receives in batches with recvmmsg().
class UdpReceiver {
 public:
  static constexpr std::size_t kBatch = 64;
  static constexpr std::size_t kMaxDatagram = 2048;  ///< larger than any sensor packet

  UdpReceiver();
  ~UdpReceiver();
  UdpReceiver(const UdpReceiver&) = delete;
  UdpReceiver& operator=(const UdpReceiver&) = delete;

  /// Binds to `address` (IPv4 dotted quad, "0.0.0.0" for all) and `port` (0: any free port).
  /// Returns false with a message in `error`.
  bool open(const std::string& address, std::uint16_t port, std::string& error);
  /// The bound port (useful after binding port 0).
  std::uint16_t port() const { return port_; }
  int fd() const { return fd_; }
  /// Receives up to kBatch datagrams, waiting at most `timeout_ms` (0: poll, -1: forever).
  /// Returns how many were received into `out` (0 on timeout), or -1 on a socket error.
  int receive(std::vector<Datagram>& out, int timeout_ms);
  /// Datagrams the kernel dropped because the socket buffer was full (SO_RXQ_OVFL), when known.
  std::uint64_t kernel_drops() const { return kernel_drops_; }

 private:
  int fd_ = -1;
  std::uint16_t port_ = 0;
  std::uint64_t kernel_drops_ = 0;
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
  /// Sends one datagram; returns false on a socket error (retries briefly when the send
  /// buffer is full).
  bool send(const std::uint8_t* data, std::size_t size);

 private:
  int fd_ = -1;
};

}  // namespace hesai::port
