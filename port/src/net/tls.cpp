#include "hesai_port/net/tls.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include "hesai/ct.h"
#include "hesai_port/base/clock.h"
#include "wait.h"

#if HESAI_WITH_TLS
#include <csignal>
#include <ctime>
#include <openssl/err.h>
#include <openssl/pem.h>
#include <openssl/ssl.h>
#include <openssl/x509.h>
#include <openssl/x509v3.h>
#include <pthread.h>
#endif

namespace hesai::port {

#if HESAI_WITH_TLS

namespace {

// Blocks SIGPIPE in this thread while OpenSSL writes to a socket (its socket BIO sends without
// MSG_NOSIGNAL), and consumes a SIGPIPE the write raised: a peer that went away is an error code,
// not the end of the program.
class SigpipeGuard {
 public:
  SigpipeGuard() {
    sigemptyset(&pipe_);
    sigaddset(&pipe_, SIGPIPE);
    sigset_t pending;
    sigemptyset(&pending);
    was_pending_ = sigpending(&pending) == 0 && sigismember(&pending, SIGPIPE) == 1;
    blocked_ = pthread_sigmask(SIG_BLOCK, &pipe_, &old_) == 0;
  }
  ~SigpipeGuard() {
    if (!blocked_) return;
    sigset_t pending;
    sigemptyset(&pending);
    if (!was_pending_ && sigpending(&pending) == 0 && sigismember(&pending, SIGPIPE) == 1) {
      const timespec zero{0, 0};
      while (sigtimedwait(&pipe_, nullptr, &zero) < 0 && errno == EINTR) {
      }
    }
    pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  SigpipeGuard(const SigpipeGuard&) = delete;
  SigpipeGuard& operator=(const SigpipeGuard&) = delete;

 private:
  sigset_t pipe_{}, old_{};
  bool was_pending_ = false, blocked_ = false;
};

// OpenSSL's reasons in its error queue, "reason; reason" (the queue emptied).
std::string openssl_reasons() {
  std::string out;
  for (unsigned long e = ERR_get_error(); e != 0; e = ERR_get_error()) {
    const char* reason = ERR_reason_error_string(e);
    std::string text = reason != nullptr ? reason : "error " + std::to_string(ERR_GET_REASON(e));
    if (out.find(text) == std::string::npos) out += (out.empty() ? "" : "; ") + text;
  }
  return out.empty() ? "no reason given" : out;
}

// A TLS alert that refuses a certificate (RFC 8446 6.2), as OpenSSL reports a received one.
bool certificate_alert(int reason) {
  switch (reason) {
    case SSL_R_SSLV3_ALERT_BAD_CERTIFICATE:
    case SSL_R_SSLV3_ALERT_UNSUPPORTED_CERTIFICATE:
    case SSL_R_SSLV3_ALERT_CERTIFICATE_REVOKED:
    case SSL_R_SSLV3_ALERT_CERTIFICATE_EXPIRED:
    case SSL_R_SSLV3_ALERT_CERTIFICATE_UNKNOWN:
    case SSL_R_TLSV1_ALERT_UNKNOWN_CA:
    case SSL_R_TLSV1_ALERT_ACCESS_DENIED:
    case SSL_R_TLSV1_ALERT_DECRYPT_ERROR:
#ifdef SSL_R_TLSV13_ALERT_CERTIFICATE_REQUIRED
    case SSL_R_TLSV13_ALERT_CERTIFICATE_REQUIRED:
#endif
      return true;
    default: return false;
  }
}

bool version_failure(int reason) {
  switch (reason) {
    case SSL_R_TLSV1_ALERT_PROTOCOL_VERSION:
    case SSL_R_UNSUPPORTED_PROTOCOL:
    case SSL_R_WRONG_SSL_VERSION:
    case SSL_R_NO_PROTOCOLS_AVAILABLE:
    case SSL_R_VERSION_TOO_LOW:
      return true;
    default: return false;
  }
}

int no_passphrase(char*, int, int, void*) { return -1; }

// Loads the key of `key_file` (read_private_key_file's checks) and the certificate chain of
// `cert_file` into `ctx`, and checks that they belong together.
bool load_identity(SSL_CTX* ctx, const std::string& cert_file, const std::string& key_file, std::string& error) {
  std::string pem;
  if (!read_private_key_file(key_file, pem, error)) return false;
  BIO* bio = BIO_new_mem_buf(pem.data(), static_cast<int>(pem.size()));
  EVP_PKEY* key = bio != nullptr ? PEM_read_bio_PrivateKey(bio, nullptr, no_passphrase, nullptr) : nullptr;
  BIO_free(bio);
  secure_wipe(&pem[0], pem.size());
  if (key == nullptr) {
    error = "cannot read a private key (PEM, without a passphrase) from '" + key_file + "': " + openssl_reasons();
    return false;
  }
  ERR_clear_error();
  if (SSL_CTX_use_certificate_chain_file(ctx, cert_file.c_str()) != 1) {
    EVP_PKEY_free(key);
    error = "cannot load the certificate '" + cert_file + "': " + openssl_reasons();
    return false;
  }
  const bool used = SSL_CTX_use_PrivateKey(ctx, key) == 1;
  EVP_PKEY_free(key);
  if (!used || SSL_CTX_check_private_key(ctx) != 1) {
    error = "the key '" + key_file + "' is not the key of the certificate '" + cert_file + "': " + openssl_reasons();
    return false;
  }
  return true;
}

bool load_ca(SSL_CTX* ctx, const std::string& ca_file, std::string& error) {
  ERR_clear_error();
  if (SSL_CTX_load_verify_locations(ctx, ca_file.c_str(), nullptr) != 1) {
    error = "cannot load the CA file '" + ca_file + "': " + openssl_reasons();
    return false;
  }
  return true;
}

}  // namespace

bool tls_available() { return true; }

TlsContext::~TlsContext() { SSL_CTX_free(ctx_); }

std::shared_ptr<TlsContext> TlsContext::client(const TlsClientOptions& options, std::string& error) {
  std::shared_ptr<TlsContext> c(new TlsContext);
  c->client_options_ = options;
  ERR_clear_error();
  c->ctx_ = SSL_CTX_new(TLS_client_method());
  if (c->ctx_ == nullptr) {
    error = "cannot make a TLS context: " + openssl_reasons();
    return nullptr;
  }
  SSL_CTX* ctx = c->ctx_;
  SSL_CTX_set_min_proto_version(ctx, TLS1_3_VERSION);
  SSL_CTX_set_session_cache_mode(ctx, SSL_SESS_CACHE_OFF);
  if (options.insecure) {
    SSL_CTX_set_verify(ctx, SSL_VERIFY_NONE, nullptr);
  } else {
    if (!load_ca(ctx, options.ca_file, error)) return nullptr;
    // The chain must reach a certificate of the CA file, which may be an intermediate (the
    // vendor ships its root, its intermediate and the chain of both). No host name or address is
    // checked: the serial is (PtcClient).
    X509_STORE_set_flags(SSL_CTX_get_cert_store(ctx), X509_V_FLAG_PARTIAL_CHAIN);
    SSL_CTX_set_verify(ctx, SSL_VERIFY_PEER, nullptr);
  }
  if (!options.key_file.empty() && !load_identity(ctx, options.cert_file, options.key_file, error)) return nullptr;
  return c;
}

std::shared_ptr<TlsContext> TlsContext::server(const TlsServerOptions& options, std::string& error) {
  std::shared_ptr<TlsContext> c(new TlsContext);
  c->client_ = false;
  c->server_options_ = options;
  ERR_clear_error();
  c->ctx_ = SSL_CTX_new(TLS_server_method());
  if (c->ctx_ == nullptr) {
    error = "cannot make a TLS context: " + openssl_reasons();
    return nullptr;
  }
  SSL_CTX* ctx = c->ctx_;
  SSL_CTX_set_min_proto_version(ctx, TLS1_3_VERSION);
  SSL_CTX_set_session_cache_mode(ctx, SSL_SESS_CACHE_OFF);
  SSL_CTX_set_num_tickets(ctx, 0);
  if (!load_identity(ctx, options.cert_file, options.key_file, error)) return nullptr;
  if (!options.client_ca_file.empty()) {
    if (!load_ca(ctx, options.client_ca_file, error)) return nullptr;
    STACK_OF(X509_NAME)* names = SSL_load_client_CA_file(options.client_ca_file.c_str());
    if (names != nullptr) SSL_CTX_set_client_CA_list(ctx, names);
    SSL_CTX_set_verify(ctx, SSL_VERIFY_PEER | SSL_VERIFY_FAIL_IF_NO_PEER_CERT, nullptr);
  }
  return c;
}

namespace {

// Why an SSL call failed with SSL_ERROR_SSL (OpenSSL's error queue, which this empties), for the
// side `client`: a chain that does not verify, no TLS 1.3, a certificate the peer refused.
std::string ssl_failure(SSL* ssl, const TlsContext& context) {
  const unsigned long first = ERR_peek_error();
  const int reason = ERR_GET_REASON(first);
  const bool client = context.is_client();
  const char* peer = client ? "the unit" : "the client";
  const long verify = SSL_get_verify_result(ssl);
  if (reason == SSL_R_CERTIFICATE_VERIFY_FAILED && verify != X509_V_OK) {
    const std::string ca = client ? context.client_options().ca_file : context.server_options().client_ca_file;
    openssl_reasons();
    return std::string(client ? "the unit's" : "the client's") + " certificate does not verify against the CA file '" +
           ca + "': " + X509_verify_cert_error_string(verify) + " (X509 verify error " + std::to_string(verify) + ")";
  }
  const std::string reasons = openssl_reasons();
  if (version_failure(reason))
    return std::string(peer) + " offers no TLS 1.3, the minimum (" + reasons + ")";
  if (reason == SSL_R_WRONG_VERSION_NUMBER || reason == SSL_R_HTTP_REQUEST || reason == SSL_R_RECORD_LENGTH_MISMATCH)
    return std::string(peer) + " does not speak TLS (" + reasons + ")" + (client ? ": is it set to PTCS?" : "");
  if (client && certificate_alert(reason)) {
    const TlsClientOptions& o = context.client_options();
    if (o.cert_file.empty())
      return "the unit requires a client certificate (mTLS) and none was given (--cert, --key): " + reasons;
    return "the unit refused this client's certificate '" + o.cert_file + "': " + reasons;
  }
  if (!client && reason == SSL_R_PEER_DID_NOT_RETURN_A_CERTIFICATE)
    return "the client sent no certificate (mTLS): " + reasons;
  return reasons;
}

// After a write that found the connection closed: the alert the peer sent before it closed, if
// one is there to read (a unit that refuses this client's certificate sends it and may reset the
// connection at once, before the client's first request goes out: TLS 1.3 ends the client's
// handshake before the server has checked its certificate). Empty when none: no error but the
// close. The socket is non-blocking: this does not wait.
std::string alert_before_close(SSL* ssl, const TlsContext& context) {
  ERR_clear_error();
  std::uint8_t byte = 0;
  std::size_t n = 0;
  int r = 0;
  {
    SigpipeGuard guard;
    r = SSL_read_ex(ssl, &byte, 1, &n);
  }
  if (r != 1 && SSL_get_error(ssl, r) == SSL_ERROR_SSL) {
    const int reason = ERR_GET_REASON(ERR_peek_error());
#ifdef SSL_R_UNEXPECTED_EOF_WHILE_READING
    if (reason != SSL_R_UNEXPECTED_EOF_WHILE_READING) return ssl_failure(ssl, context);
#else
    (void)reason;
    return ssl_failure(ssl, context);
#endif
  }
  ERR_clear_error();
  return {};
}

}  // namespace

TlsTransport::~TlsTransport() {
  if (ssl_ != nullptr) {
    SigpipeGuard guard;
    if (fd_ >= 0 && error_.empty()) SSL_shutdown(ssl_);  // close_notify, once, without waiting
    SSL_free(ssl_);
  }
}

PtcTransport::Io TlsTransport::connect(std::shared_ptr<TlsContext> context, const std::string& host, std::uint16_t port,
                                       std::int64_t deadline_ns, std::string& error) {
  context_ = std::move(context);
  tcp_.set_stop(stop_);
  if (const Io io = tcp_.connect(host, port, deadline_ns, error); io != Io::ok) return io;
  fd_ = tcp_.fd();
  ERR_clear_error();
  ssl_ = SSL_new(context_->native());
  if (ssl_ == nullptr || SSL_set_fd(ssl_, fd_) != 1) {
    error = error_ = "cannot start TLS: " + openssl_reasons();
    return Io::error;
  }
  return handshake(true, deadline_ns, error);
}

PtcTransport::Io TlsTransport::accept(std::shared_ptr<TlsContext> context, int fd, std::int64_t deadline_ns,
                                      std::string& error) {
  context_ = std::move(context);
  fd_ = fd;
  fcntl(fd_, F_SETFL, fcntl(fd_, F_GETFL) | O_NONBLOCK);
  ERR_clear_error();
  ssl_ = SSL_new(context_->native());
  if (ssl_ == nullptr || SSL_set_fd(ssl_, fd_) != 1) {
    error = error_ = "cannot start TLS: " + openssl_reasons();
    return Io::error;
  }
  return handshake(false, deadline_ns, error);
}

PtcTransport::Io TlsTransport::handshake(bool client, std::int64_t deadline_ns, std::string& error) {
  for (;;) {
    ERR_clear_error();
    errno = 0;
    int r = 0;
    {
      SigpipeGuard guard;
      r = client ? SSL_connect(ssl_) : SSL_accept(ssl_);
    }
    if (r == 1) return Io::ok;
    // 0 (a controlled end) and negative returns (a failure, or I/O to wait for) alike.
    const int e = SSL_get_error(ssl_, r);
    if (e == SSL_ERROR_WANT_READ || e == SSL_ERROR_WANT_WRITE) {
      if (const Wait w = wait_fd(fd_, e == SSL_ERROR_WANT_READ ? POLLIN : POLLOUT, deadline_ns, stop_); w != Wait::ready) {
        error = w == Wait::stopped ? "interrupted" : "no TLS handshake";
        return w == Wait::stopped ? Io::stopped : Io::timeout;
      }
      continue;
    }
    const char* peer = client ? "the unit" : "the client";
    if (e == SSL_ERROR_SSL) {
      error = ssl_failure(ssl_, *context_);
    } else if (e == SSL_ERROR_ZERO_RETURN || (e == SSL_ERROR_SYSCALL && (errno == 0 || errno == ECONNRESET || errno == EPIPE))) {
      ERR_clear_error();
      error = std::string(peer) + " closed the connection during the TLS handshake" +
              (client ? " (is it set to PTCS?)" : "");
    } else {
      const int saved = errno;
      ERR_clear_error();
      error = std::string("socket error during the TLS handshake: ") + std::strerror(saved);
    }
    error_ = error;
    return Io::error;
  }
}

namespace {

// Moves `size` bytes by `step` (SSL_write_ex or SSL_read_ex of the bytes left from `done`, setting
// the count it moved; a read may write too, a key update, so both run under the SIGPIPE guard),
// waiting on the socket for what OpenSSL wants between steps. Any other outcome is the caller's
// to classify: `failure` gets SSL_get_error's code, with errno and OpenSSL's error queue as the
// failed step left them.
template <typename Step, typename Failure>
PtcTransport::Io ssl_transfer(SSL* ssl, int fd, const std::atomic<bool>* stop, std::size_t size, std::int64_t deadline_ns,
                              Step step, Failure failure) {
  std::size_t done = 0;
  while (done < size) {
    ERR_clear_error();
    errno = 0;
    std::size_t n = 0;
    int r = 0;
    {
      SigpipeGuard guard;
      r = step(done, n);
    }
    if (r == 1) {
      done += n;
      continue;
    }
    const int e = SSL_get_error(ssl, r);
    if (e == SSL_ERROR_WANT_READ || e == SSL_ERROR_WANT_WRITE) {
      if (const Wait w = wait_fd(fd, e == SSL_ERROR_WANT_READ ? POLLIN : POLLOUT, deadline_ns, stop); w != Wait::ready)
        return w == Wait::stopped ? PtcTransport::Io::stopped : PtcTransport::Io::timeout;
      continue;
    }
    return failure(e);
  }
  return PtcTransport::Io::ok;
}

}  // namespace

PtcTransport::Io TlsTransport::send_all(const std::uint8_t* data, std::size_t size, std::int64_t deadline_ns) {
  const auto step = [&](std::size_t done, std::size_t& n) { return SSL_write_ex(ssl_, data + done, size - done, &n); };
  return ssl_transfer(ssl_, fd_, stop_, size, deadline_ns, step, [&](int e) {
    if (e == SSL_ERROR_SSL) {
      error_ = ssl_failure(ssl_, *context_);
      return Io::error;
    }
    const int saved = errno;
    ERR_clear_error();
    if (e == SSL_ERROR_ZERO_RETURN || saved == 0 || saved == EPIPE || saved == ECONNRESET) {
      if (std::string alert = alert_before_close(ssl_, *context_); !alert.empty()) {
        error_ = std::move(alert);  // the cause, not its consequence
        return Io::error;
      }
      error_ = "the peer closed the connection";
      return Io::closed;
    }
    error_ = std::string("socket error: ") + std::strerror(saved);
    return Io::error;
  });
}

PtcTransport::Io TlsTransport::receive_exact(std::uint8_t* data, std::size_t size, std::int64_t deadline_ns) {
  const auto step = [&](std::size_t done, std::size_t& n) { return SSL_read_ex(ssl_, data + done, size - done, &n); };
  return ssl_transfer(ssl_, fd_, stop_, size, deadline_ns, step, [&](int e) {
    if (e == SSL_ERROR_ZERO_RETURN) {
      ERR_clear_error();
      error_ = "the peer ended the TLS session";
      return Io::closed;
    }
    if (e == SSL_ERROR_SSL) {
      const int reason = ERR_GET_REASON(ERR_peek_error());
#ifdef SSL_R_UNEXPECTED_EOF_WHILE_READING
      if (reason == SSL_R_UNEXPECTED_EOF_WHILE_READING) {
        ERR_clear_error();
        error_ = "the peer closed the connection without ending the TLS session";
        return Io::closed;
      }
#endif
      (void)reason;
      error_ = ssl_failure(ssl_, *context_);
      return Io::error;
    }
    const int saved = errno;
    ERR_clear_error();
    if (saved == 0 || saved == ECONNRESET) {
      error_ = "the peer closed the connection";
      return Io::closed;
    }
    error_ = std::string("socket error: ") + std::strerror(saved);
    return Io::error;
  });
}

bool TlsTransport::pending() const { return ssl_ != nullptr && SSL_pending(ssl_) > 0; }

std::vector<SubjectName> TlsTransport::peer_subject() const {
  std::vector<SubjectName> out;
  if (ssl_ == nullptr) return out;
#if OPENSSL_VERSION_NUMBER >= 0x30000000L
  X509* cert = SSL_get1_peer_certificate(ssl_);
#else
  X509* cert = SSL_get_peer_certificate(ssl_);
#endif
  if (cert == nullptr) return out;
  const X509_NAME* subject = X509_get_subject_name(cert);
  for (const auto& [nid, field] : {std::pair<int, const char*>{NID_commonName, "CN"}, {NID_serialNumber, "serialNumber"}}) {
    for (int i = X509_NAME_get_index_by_NID(subject, nid, -1); i >= 0; i = X509_NAME_get_index_by_NID(subject, nid, i)) {
      unsigned char* utf8 = nullptr;
      const int len = ASN1_STRING_to_UTF8(&utf8, X509_NAME_ENTRY_get_data(X509_NAME_get_entry(subject, i)));
      if (len >= 0 && utf8 != nullptr) out.push_back({field, std::string(reinterpret_cast<const char*>(utf8), static_cast<std::size_t>(len))});
      OPENSSL_free(utf8);
    }
  }
  X509_free(cert);
  return out;
}

#else  // !HESAI_WITH_TLS

bool tls_available() { return false; }

TlsContext::~TlsContext() = default;

std::shared_ptr<TlsContext> TlsContext::client(const TlsClientOptions&, std::string& error) {
  error = "built without TLS";
  return nullptr;
}

std::shared_ptr<TlsContext> TlsContext::server(const TlsServerOptions&, std::string& error) {
  error = "built without TLS";
  return nullptr;
}

TlsTransport::~TlsTransport() = default;

PtcTransport::Io TlsTransport::connect(std::shared_ptr<TlsContext>, const std::string&, std::uint16_t, std::int64_t,
                                       std::string& error) {
  error = error_ = "built without TLS";
  return Io::error;
}

PtcTransport::Io TlsTransport::accept(std::shared_ptr<TlsContext>, int, std::int64_t, std::string& error) {
  error = error_ = "built without TLS";
  return Io::error;
}

PtcTransport::Io TlsTransport::handshake(bool, std::int64_t, std::string& error) {
  error = "built without TLS";
  return Io::error;
}

PtcTransport::Io TlsTransport::send_all(const std::uint8_t*, std::size_t, std::int64_t) { return Io::error; }
PtcTransport::Io TlsTransport::receive_exact(std::uint8_t*, std::size_t, std::int64_t) { return Io::error; }
bool TlsTransport::pending() const { return false; }
std::vector<SubjectName> TlsTransport::peer_subject() const { return {}; }

#endif

}  // namespace hesai::port
