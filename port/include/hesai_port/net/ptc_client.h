// A PTC client: one request at a time to a sensor's TCP command port (9347), framed and checked by
// the core's codec (hesai/ptc.h).
//
// Every request has one deadline, the client's timeout from the moment request() is called: it
// covers connecting (when the request opens the connection), sending and the whole answer, so a
// sensor that accepts slowly, stays silent, or sends a byte now and then costs at most the timeout. A response's announced length is checked against the command's bound
// (ptc::max_response_bytes, 1 MiB for files) before any byte of its payload is stored. After any
// framing error (another magic, another command's echo, a length past the bound, an answer cut
// short, a timeout) the connection is closed; the next request connects again.
//
// The byte stream is a PtcTransport: plain TCP here (TcpTransport). PTCS, PTC over TLS, would be
// another transport; the project takes on no TLS library, so a unit set to TLS-only is out of reach.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "hesai/bytes.h"
#include "hesai/ptc.h"

namespace hesai::port {

/// Fills `out` with `n` random bytes from the kernel (/dev/urandom), for the randoms of a
/// signature session. False when it cannot.
bool random_bytes(std::uint8_t* out, std::size_t n);

/// A connected byte stream with deadlines (monotonic_ns() values).
class PtcTransport {
 public:
  enum class Io { ok, timeout, closed, error };
  virtual ~PtcTransport() = default;
  virtual Io send_all(const std::uint8_t* data, std::size_t size, std::int64_t deadline_ns) = 0;
  /// Reads exactly `size` bytes; closed when the peer ends the stream first.
  virtual Io receive_exact(std::uint8_t* data, std::size_t size, std::int64_t deadline_ns) = 0;
};

/// Plain TCP over IPv4.
class TcpTransport final : public PtcTransport {
 public:
  TcpTransport() = default;
  ~TcpTransport() override;
  TcpTransport(const TcpTransport&) = delete;
  TcpTransport& operator=(const TcpTransport&) = delete;

  /// Connects to an IPv4 address of `host` (a dotted quad or a name) within `timeout_ms`.
  /// Returns Io::ok, Io::timeout, or Io::error with a message in `error`.
  Io connect(const std::string& host, std::uint16_t port, int timeout_ms, std::string& error);
  /// Connects to `ipv4` (in_addr.s_addr, network byte order) before `deadline_ns` (monotonic_ns()).
  Io connect_ipv4(std::uint32_t ipv4, std::uint16_t port, std::int64_t deadline_ns, std::string& error);
  Io send_all(const std::uint8_t* data, std::size_t size, std::int64_t deadline_ns) override;
  Io receive_exact(std::uint8_t* data, std::size_t size, std::int64_t deadline_ns) override;

 private:
  int fd_ = -1;
};

/// How a request ended.
enum class PtcOutcome {
  ok,
  unreachable,   ///< the connection was refused or could not be made
  timeout,       ///< no (whole) answer within the timeout
  cut_short,     ///< the sensor closed the connection within a header or a payload
  framing,       ///< a header the codec refused (error: ptc_bad_magic, ptc_command_mismatch, ptc_length_exceeds_bound)
  sensor_error,  ///< a non-zero return code (return_code)
  io_error,      ///< a socket error other than the above
};

struct PtcResult {
  PtcOutcome outcome = PtcOutcome::ok;
  Error error = Error::ok;        ///< the codec's error for framing and sensor_error
  std::uint8_t return_code = 0;   ///< for sensor_error
  std::string message;            ///< names the host and port, the command and what went wrong
  bool ok() const { return outcome == PtcOutcome::ok; }
};

class PtcClient {
 public:
  static constexpr int kDefaultTimeoutMs = 3000;

  PtcClient(std::string host, std::uint16_t port = ptc::kDefaultPort, int timeout_ms = kDefaultTimeoutMs);
  /// A client of the address `ipv4` (in_addr.s_addr, network byte order), already resolved from
  /// `host`, which names it in messages only: a caller that also filters datagrams by the sensor's
  /// address resolves the name once, and both use the same address.
  PtcClient(std::string host, std::uint32_t ipv4, std::uint16_t port, int timeout_ms);

  /// Sends `command` with `payload` and reads the answer's payload into `response` (resized to
  /// the announced length, which is at most ptc::max_response_bytes(command)). Requests from
  /// several threads are serialised: one is on the wire at a time.
  PtcResult request(ptc::Command command, ByteView payload, std::vector<std::uint8_t>& response);
  /// Closes the connection (the next request opens another).
  void close() {
    std::lock_guard<std::mutex> lock(mutex_);
    transport_.reset();
  }

  const std::string& host() const { return host_; }
  std::uint16_t port() const { return port_; }

 private:
  PtcResult fail(PtcOutcome outcome, ptc::Command command, const std::string& what);

  std::string host_;
  std::uint16_t port_;
  int timeout_ms_;
  bool resolved_ = false;    // ipv4_ given: host_ is not resolved again
  std::uint32_t ipv4_ = 0;
  std::unique_ptr<PtcTransport> transport_;  // connected, or null
  std::mutex mutex_;                         // one request on the wire at a time
};

}  // namespace hesai::port
