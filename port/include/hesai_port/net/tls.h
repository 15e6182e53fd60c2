// PTCS, PTC over TLS (QT128C2X manual 4.9 and chapter 5: "the same data format as the cleartext
// PTC", TLS 1.3 or above), through OpenSSL, for the PTC client (ptc_client.h) and the stand-in
// sensor (ptc_server.h).
//
// A client's TlsContext holds what every connection checks: TLS 1.3 at least; the unit's
// certificate chain to the CA file (unless insecure); no host name or address (a unit's
// certificate names its serial, and its address is the user's to change); for mTLS, this side's
// certificate and key. PtcClient then checks the serial (see ptc_client.h). A TlsTransport is one
// connection on a non-blocking socket: the handshake, every read and every write are polled
// against the caller's deadline, and every OpenSSL return is classified by SSL_get_error.
//
// Built without OpenSSL (HESAI_WITH_TLS=0), tls_available() is false and every context fails to
// build with the message "built without TLS".
//
// Threads: a TlsContext is shared read-only by its connections; a TlsTransport belongs to one
// thread at a time (PtcClient serialises its requests).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hesai_port/net/transport.h"

struct ssl_ctx_st;  // OpenSSL's SSL_CTX
struct ssl_st;      // OpenSSL's SSL

namespace hesai::port {

/// True when this build has TLS (OpenSSL found at configure time, HESAI_WITH_TLS).
bool tls_available();

/// Reads a private key file as ssh reads an identity file: a symbolic link is followed, but the
/// file it reaches must be a regular file that neither group nor others may access in any way
/// (mode 0600 or 0400). It is opened once, without blocking (a FIFO is refused, not waited on), and
/// checked on that descriptor (fstat), so what is checked is what is read. At most 64 KiB. False
/// with a message that names the path and why.
bool read_private_key_file(const std::string& path, std::string& pem, std::string& error);

/// One entry of a certificate's subject that may name a unit: its commonName or serialNumber.
struct SubjectName {
  std::string field;  ///< "CN" or "serialNumber"
  std::string value;
};

/// Whether the certificate whose subject entries are `names` is the unit of `serial`. A
/// certificate names one serial: its serialNumber attribute where it has one (its CN is then only
/// a name), else its CN; that whole value must equal `serial`, byte for byte. "CN=Hesai QT128C2X
/// 1234" is not the certificate of unit "1234" (nor of "QT128C2X"); a subject with two CNs and
/// no serialNumber, or with two serialNumbers, names no unit. An empty serial is nobody's.
bool subject_names_serial(const std::vector<SubjectName>& names, const std::string& serial);
/// "CN=STANDIN, serialNumber=QT-1", or "no CN and no serialNumber", for messages: each value
/// escaped for a terminal (terminal_text, hesai_port/base/text.h), as a certificate may hold anything.
std::string subject_text(const std::vector<SubjectName>& names);

struct TlsClientOptions {
  std::string ca_file;                ///< PEM: the CA certificate(s) the unit's chain must reach
  std::string cert_file, key_file;    ///< PEM, mTLS: this side's certificate (chain) and key
  bool insecure = false;              ///< no chain check (and no serial check unless expect_serial)
  std::string expect_serial;          ///< the certificate must name it before any command is sent
};

struct TlsServerOptions {
  std::string cert_file, key_file;  ///< PEM: the unit's certificate (chain) and key
  std::string client_ca_file;       ///< PEM; given: mTLS, a client certificate is required and verified
};

/// An SSL_CTX with the project's settings. Made once, shared by connections.
class TlsContext {
 public:
  ~TlsContext();
  TlsContext(const TlsContext&) = delete;
  TlsContext& operator=(const TlsContext&) = delete;

  /// A client's context; null with a message (an unreadable CA file, a refused key file, a key
  /// that is not the certificate's, "built without TLS").
  static std::shared_ptr<TlsContext> client(const TlsClientOptions& options, std::string& error);
  /// The stand-in's context (TLS 1.3 only, as a unit).
  static std::shared_ptr<TlsContext> server(const TlsServerOptions& options, std::string& error);

  bool is_client() const { return client_; }
  const TlsClientOptions& client_options() const { return client_options_; }
  const TlsServerOptions& server_options() const { return server_options_; }
  ssl_ctx_st* native() const { return ctx_; }

 private:
  TlsContext() = default;
  ssl_ctx_st* ctx_ = nullptr;
  bool client_ = true;
  TlsClientOptions client_options_;
  TlsServerOptions server_options_;
};

/// One TLS connection over TCP.
class TlsTransport final : public PtcTransport {
 public:
  TlsTransport() = default;
  ~TlsTransport() override;
  TlsTransport(const TlsTransport&) = delete;
  TlsTransport& operator=(const TlsTransport&) = delete;

  /// Client: connects to `host`:`port` and completes the handshake by `deadline_ns`. Io::timeout
  /// ("no TLS handshake within ..." is the caller's to say), or Io::error with the cause in
  /// `error`: the verify error of the unit's chain (X509_verify_cert_error_string), a unit that
  /// offers no TLS 1.3, the handshake alert the unit sent.
  Io connect(std::shared_ptr<TlsContext> context, const std::string& host, std::uint16_t port,
             std::int64_t deadline_ns, std::string& error);
  /// Server: the handshake over the accepted socket `fd` (made non-blocking; closed by the
  /// caller, after this transport) by `deadline_ns`.
  Io accept(std::shared_ptr<TlsContext> context, int fd, std::int64_t deadline_ns, std::string& error);

  Io send_all(const std::uint8_t* data, std::size_t size, std::int64_t deadline_ns) override;
  Io receive_exact(std::uint8_t* data, std::size_t size, std::int64_t deadline_ns) override;
  /// After an Io::error or Io::closed: the cause, with OpenSSL's reason (a client certificate the
  /// unit refused shows here, at the first read: TLS 1.3 ends the client's handshake first).
  std::string last_error() const override { return error_; }

  /// The TCP connection was made (a failure after it is the handshake's).
  bool tcp_connected() const { return fd_ >= 0; }
  /// Decrypted bytes are waiting (a poll of the socket would not show them).
  bool pending() const;
  /// The peer certificate's subject CN and serialNumber entries (none without a certificate).
  std::vector<SubjectName> peer_subject() const;

 private:
  Io handshake(bool client, std::int64_t deadline_ns, std::string& error);

  std::shared_ptr<TlsContext> context_;
  TcpTransport tcp_;  // the client's socket
  int fd_ = -1;       // the socket in use (the client's tcp_, or the server's accepted one)
  ssl_st* ssl_ = nullptr;
  std::string error_;
};

}  // namespace hesai::port
