// The byte stream a PTC request travels on: plain TCP (TcpTransport, here) or TLS (TlsTransport,
// hesai_port/net/tls.h), each with a deadline on every wait and a stop flag. PtcClient
// (ptc_client.h) speaks PTC over either; the stand-in sensor (ptc_server.h) serves over either.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>

namespace hesai::port {

/// A connected byte stream with deadlines (monotonic_ns() values).
class PtcTransport {
 public:
  enum class Io { ok, timeout, closed, error, stopped };
  virtual ~PtcTransport() = default;
  /// From now on, every wait ends within 100 ms once `*stop` is true (Io::stopped); null: never.
  void set_stop(const std::atomic<bool>* stop) { stop_ = stop; }
  virtual Io send_all(const std::uint8_t* data, std::size_t size, std::int64_t deadline_ns) = 0;
  /// Reads exactly `size` bytes; closed when the peer ends the stream first.
  virtual Io receive_exact(std::uint8_t* data, std::size_t size, std::int64_t deadline_ns) = 0;
  /// After Io::error or Io::closed: the cause, when the transport knows more than errno (TLS).
  virtual std::string last_error() const { return {}; }

 protected:
  const std::atomic<bool>* stop_ = nullptr;
};

/// Plain TCP over IPv4.
class TcpTransport final : public PtcTransport {
 public:
  TcpTransport() = default;
  ~TcpTransport() override;
  TcpTransport(const TcpTransport&) = delete;
  TcpTransport& operator=(const TcpTransport&) = delete;

  /// Connects to an IPv4 address of `host` (a dotted quad or a name) by `deadline_ns`.
  /// Returns Io::ok, Io::timeout ("no connection" in `error`), or Io::error with a message.
  Io connect(const std::string& host, std::uint16_t port, std::int64_t deadline_ns, std::string& error);
  Io send_all(const std::uint8_t* data, std::size_t size, std::int64_t deadline_ns) override;
  Io receive_exact(std::uint8_t* data, std::size_t size, std::int64_t deadline_ns) override;
  int fd() const { return fd_; }

 private:
  int fd_ = -1;
};

}  // namespace hesai::port
