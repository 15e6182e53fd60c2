#include "hesai_port/net/transport.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include "wait.h"

namespace hesai::port {

TcpTransport::~TcpTransport() {
  if (fd_ >= 0) ::close(fd_);
}

PtcTransport::Io TcpTransport::connect(const std::string& host, std::uint16_t port, std::int64_t deadline_ns,
                                       std::string& error) {
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* res = nullptr;
  const std::string service = std::to_string(port);
  if (const int rc = getaddrinfo(host.c_str(), service.c_str(), &hints, &res); rc != 0) {
    error = std::string("cannot resolve: ") + gai_strerror(rc);
    return Io::error;
  }
  fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd_ < 0) {
    error = std::string("socket: ") + std::strerror(errno);
    freeaddrinfo(res);
    return Io::error;
  }
  fcntl(fd_, F_SETFL, fcntl(fd_, F_GETFL) | O_NONBLOCK);
  const int one = 1;
  setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  const int rc = ::connect(fd_, res->ai_addr, res->ai_addrlen);
  freeaddrinfo(res);
  if (rc != 0 && errno != EINPROGRESS) {
    error = std::string("cannot connect: ") + std::strerror(errno);
    return Io::error;
  }
  if (rc != 0) {
    if (const Wait w = wait_fd(fd_, POLLOUT, deadline_ns, stop_); w != Wait::ready) {
      error = w == Wait::stopped ? "interrupted" : "no connection";
      return w == Wait::stopped ? Io::stopped : Io::timeout;
    }
    int so_error = 0;
    socklen_t len = sizeof so_error;
    getsockopt(fd_, SOL_SOCKET, SO_ERROR, &so_error, &len);
    if (so_error != 0) {
      error = std::string("cannot connect: ") + std::strerror(so_error);
      return Io::error;
    }
  }
  return Io::ok;
}

namespace {

// Moves `size` bytes by `step` (a send or a recv of the bytes left, returning what the call
// returns), waiting for `events` on `fd` while the socket has no room or no data. A step of 0 (recv:
// the peer ended the stream) and a reset or broken pipe are the peer's close; any other error is
// an error.
template <typename Step>
PtcTransport::Io transfer(int fd, std::size_t size, short events, std::int64_t deadline_ns,
                          const std::atomic<bool>* stop, Step step) {
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = step(done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
    } else if (n == 0) {
      return PtcTransport::Io::closed;
    } else if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) {
      if (const Wait w = wait_fd(fd, events, deadline_ns, stop); w != Wait::ready)
        return w == Wait::stopped ? PtcTransport::Io::stopped : PtcTransport::Io::timeout;
    } else {
      return (errno == EPIPE || errno == ECONNRESET) ? PtcTransport::Io::closed : PtcTransport::Io::error;
    }
  }
  return PtcTransport::Io::ok;
}

}  // namespace

PtcTransport::Io TcpTransport::send_all(const std::uint8_t* data, std::size_t size, std::int64_t deadline_ns) {
  return transfer(fd_, size, POLLOUT, deadline_ns, stop_,
                  [&](std::size_t done) { return ::send(fd_, data + done, size - done, MSG_NOSIGNAL); });
}

PtcTransport::Io TcpTransport::receive_exact(std::uint8_t* data, std::size_t size, std::int64_t deadline_ns) {
  return transfer(fd_, size, POLLIN, deadline_ns, stop_,
                  [&](std::size_t done) { return ::recv(fd_, data + done, size - done, 0); });
}

}  // namespace hesai::port
