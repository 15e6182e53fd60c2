// A PTC client: one request at a time to a sensor's TCP command port (9347), framed and checked by
// the core's codec (hesai/ptc.h).
//
// Every request has one deadline, the client's timeout from the moment it starts: connecting (and,
// over TLS, the handshake and the serial check) when no connection is open, sending, and reading
// the answer. A sensor that stays silent, or sends a byte now and then, costs at most the timeout.
// A response's announced length is checked against the command's bound
// (ptc::max_response_bytes, 1 MiB for files) before any byte of its payload is stored. After any
// framing error (another magic, another command's echo, a length past the bound, an answer cut
// short, a timeout) the connection is closed; the next request connects again. With a stop flag
// (set_stop), a request in flight ends within 100 ms of the flag going up.
//
// The byte stream is a PtcTransport: plain TCP (TcpTransport), or PTCS, PTC over TLS (TlsTransport,
// hesai_port/net/tls.h) once use_tls() is called. Over TLS, each new connection is checked before
// the request goes out: the chain to the CA (TlsContext), then the serial. The unit's certificate
// must name (subject_names_serial: its serialNumber, or its CN where it has none, equal to the
// serial, byte for byte) the expected serial when one is given (before any command is sent), and
// the serial of the unit's own inventory (0x07, asked first on every connection; skipped with the
// insecure option, which checks no chain either); a mismatch names both, escaped for a terminal
// (terminal_text), as either may hold anything.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "hesai/bytes.h"
#include "hesai/ptc.h"
#include "hesai_port/net/transport.h"

namespace hesai::port {

class TlsContext;

/// How a request ended.
enum class PtcOutcome {
  ok,
  unreachable,   ///< the connection was refused or could not be made
  timeout,       ///< no (whole) answer within the timeout
  cut_short,     ///< the sensor closed the connection within a header or a payload
  framing,       ///< a header the codec refused (error: ptc_bad_magic, ptc_command_mismatch, ptc_length_exceeds_bound)
  sensor_error,  ///< a non-zero return code (return_code)
  io_error,      ///< a socket error other than the above
  tls,           ///< PTCS: the handshake failed or the unit's certificate is not the one expected
  stopped,       ///< the stop flag (set_stop) went up during the request
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

  /// Speaks PTCS from the next connection on (null: plain TCP again).
  void use_tls(std::shared_ptr<TlsContext> tls) {
    std::lock_guard<std::mutex> lock(mutex_);
    tls_ = std::move(tls);
    transport_.reset();
  }

  /// Sends `command` with `payload` and reads the answer's payload into `response` (resized to
  /// the announced length, which is at most ptc::max_response_bytes(command)). Requests from
  /// several threads are serialised: one is on the wire at a time.
  PtcResult request(ptc::Command command, ByteView payload, std::vector<std::uint8_t>& response);
  /// A flag (a signal handler's, say) that ends the request in flight, within 100 ms of its going
  /// up, as PtcOutcome::stopped (the connection closed). A request started while it is up runs to
  /// its own deadline: a program's clean-up after a stop (ending a signature session) still
  /// reaches the unit. Null: none. The flag must outlive the client.
  void set_stop(const std::atomic<bool>* stop) {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = stop;
  }
  /// Closes the connection (the next request opens another).
  void close() {
    std::lock_guard<std::mutex> lock(mutex_);
    transport_.reset();
  }

  const std::string& host() const { return host_; }
  std::uint16_t port() const { return port_; }

 private:
  PtcResult fail(PtcOutcome outcome, ptc::Command command, const std::string& what);
  // Opens transport_ (over TLS: handshake and serial checks) by `deadline`.
  PtcResult open(ptc::Command command, std::int64_t deadline);
  // One request and its answer on the open transport_.
  PtcResult exchange(ptc::Command command, ByteView payload, std::vector<std::uint8_t>& response, std::int64_t deadline);
  std::string seconds() const;

  std::string host_;          // as given, for messages
  std::string connect_host_;  // what is connected to: host_, or the dotted quad it was resolved to
  std::uint16_t port_;
  int timeout_ms_;
  std::shared_ptr<TlsContext> tls_;          // null: plain TCP
  std::unique_ptr<PtcTransport> transport_;  // connected, or null
  std::mutex mutex_;                         // one request on the wire at a time
  const std::atomic<bool>* stop_ = nullptr;         // set_stop()
  const std::atomic<bool>* active_stop_ = nullptr;  // the request's: stop_, unless it was up at its start
};

}  // namespace hesai::port
