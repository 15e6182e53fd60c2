#include "hesai_port/net/ptc_server.h"

#include <arpa/inet.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include "hesai/ct.h"
#include "hesai/hkdf.h"
#include "hesai/ptc.h"
#include "hesai_port/base/clock.h"
#include "hesai_port/net/ptc_client.h"  // random_bytes
#include "hesai_port/net/tls.h"

namespace hesai::port {
namespace {

constexpr std::uint32_t kMaxRequestBytes = 4096;
constexpr int kIdleMs = 10000;

// Reads exactly `size` bytes within kIdleMs per wait; false when the client closed or went silent.
bool read_exact(int fd, std::uint8_t* data, std::size_t size, const std::atomic<bool>& stop) {
  std::size_t done = 0;
  while (done < size) {
    pollfd p{fd, POLLIN, 0};
    int waited = 0;
    int r = 0;
    while ((r = poll(&p, 1, 100)) == 0 && !stop && (waited += 100) < kIdleMs) {
    }
    if (r <= 0) return false;
    const ssize_t n = ::recv(fd, data + done, size - done, 0);
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

bool write_all(int fd, const std::uint8_t* data, std::size_t size) {
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::send(fd, data + done, size - done, MSG_NOSIGNAL);
    if (n <= 0) {
      if (n < 0 && errno == EINTR) continue;
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  return true;
}

void put_text(std::vector<std::uint8_t>& out, std::size_t at, const char* text, std::size_t field) {
  for (std::size_t i = 0; i < field && text[i] != '\0'; ++i) out[at + i] = static_cast<std::uint8_t>(text[i]);
}

void put_be16(std::vector<std::uint8_t>& out, std::size_t at, std::uint16_t v) {
  out[at] = static_cast<std::uint8_t>(v >> 8);
  out[at + 1] = static_cast<std::uint8_t>(v);
}

void put_be32(std::vector<std::uint8_t>& out, std::size_t at, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) out[at + i] = static_cast<std::uint8_t>(v >> (24 - 8 * i));
}


}  // namespace

PtcServer::~PtcServer() {
  if (fd_ >= 0) ::close(fd_);
  secure_wipe(key_.data(), key_.size());
  secure_wipe(content_.secret.data(), content_.secret.size());
}

bool PtcServer::open(const std::string& address, std::uint16_t port, StandInContent content, std::string& error) {
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_port = htons(port);
  if (inet_pton(AF_INET, address.c_str(), &sa.sin_addr) != 1) {
    error = "not an IPv4 address: " + address;
    return false;
  }
  fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const int one = 1;
  if (fd_ >= 0) setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  if (fd_ < 0 || bind(fd_, reinterpret_cast<const sockaddr*>(&sa), sizeof sa) != 0 || listen(fd_, 4) != 0) {
    error = "cannot serve PTC on " + address + ":" + std::to_string(port) + ": " + std::strerror(errno);
    return false;
  }
  socklen_t len = sizeof sa;
  getsockname(fd_, reinterpret_cast<sockaddr*>(&sa), &len);
  port_ = ntohs(sa.sin_port);
  content_ = std::move(content);
  opened_ns_ = monotonic_ns();
  return true;
}

void PtcServer::run() {
  while (!stop_) {
    pollfd p{fd_, POLLIN, 0};
    if (poll(&p, 1, 100) <= 0) continue;
    const int client = accept4(fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (client < 0) continue;
    serve(client);
    ::close(client);
  }
}

bool PtcServer::session_key(std::uint8_t key[32]) const {
  std::lock_guard<std::mutex> lock(session_mutex_);
  if (!session_on_) return false;
  std::memcpy(key, key_.data(), key_.size());
  return true;
}

void PtcServer::serve(int fd) {
  std::unique_ptr<TlsTransport> tls;
  if (tls_) {
    tls = std::make_unique<TlsTransport>();
    std::string error;
    if (tls->accept(tls_, fd, monotonic_ns() + static_cast<std::int64_t>(kIdleMs) * 1000000, error) != PtcTransport::Io::ok) {
      std::fprintf(stderr, "stand-in: TLS handshake: %s\n", error.c_str());
      tls.reset();
      // The alert has been sent: let it reach the client before the close (a close with unread
      // bytes would reset the connection, and the client might lose the alert).
      shutdown(fd, SHUT_WR);
      std::uint8_t drain[256];
      for (int i = 0; i < 20; ++i) {
        pollfd p{fd, POLLIN, 0};
        if (poll(&p, 1, 10) > 0 && ::recv(fd, drain, sizeof drain, MSG_DONTWAIT) == 0) break;
      }
      return;
    }
  }
  // A message's bytes: plain, or over TLS (waiting for a header, stop() is checked every 100 ms).
  const auto read = [&](std::uint8_t* data, std::size_t size, bool header) {
    if (!tls) return read_exact(fd, data, size, stop_);
    if (header) {
      int waited = 0;
      pollfd p{fd, POLLIN, 0};
      while (!tls->pending() && poll(&p, 1, 100) == 0)
        if (stop_ || (waited += 100) >= kIdleMs) return false;
    }
    return tls->receive_exact(data, size, monotonic_ns() + static_cast<std::int64_t>(kIdleMs) * 1000000) == PtcTransport::Io::ok;
  };
  const auto write = [&](const std::uint8_t* data, std::size_t size) {
    if (!tls) return write_all(fd, data, size);
    return tls->send_all(data, size, monotonic_ns() + static_cast<std::int64_t>(kIdleMs) * 1000000) == PtcTransport::Io::ok;
  };
  std::vector<std::uint8_t> request;
  while (!stop_) {
    std::uint8_t h[ptc::kHeaderBytes];
    if (!read(h, sizeof h, true)) return;
    ptc::Header header;
    if (ptc::parse_header(ByteView{h, sizeof h}, header) != Error::ok || header.length > kMaxRequestBytes) return;
    request.resize(header.length);
    if (!read(request.data(), request.size(), false)) return;
    std::uint8_t code = 0;
    const std::vector<std::uint8_t> payload = answer(header.command, request, code);
    std::uint8_t out[ptc::kHeaderBytes];
    ptc::encode_header(header.command, code, static_cast<std::uint32_t>(payload.size()), out);
    if (!write(out, sizeof out) || !write(payload.data(), payload.size())) return;
  }
}

std::vector<std::uint8_t> PtcServer::answer(std::uint8_t command, const std::vector<std::uint8_t>& request,
                                            std::uint8_t& code) {
  using ptc::Command;
  const auto file = [&](const std::string& text) {
    if (text.empty()) code = static_cast<std::uint8_t>(ptc::ReturnCode::unsupported_command);
    return std::vector<std::uint8_t>(text.begin(), text.end());
  };
  const Model model = content_.model;
  const std::uint16_t rpm = motor_rpm_ != 0 ? motor_rpm_.load() : 600;
  switch (static_cast<Command>(command)) {
    case Command::calibration: return file(content_.calibration);
    case Command::firetimes: return file(content_.firetimes);
    case Command::channel_config: return file(content_.channel_config);
    case Command::inventory: {
      const bool qt128 = model == Model::qt128c2x;
      std::vector<std::uint8_t> out(qt128 ? ptc::kInvQt128Bytes : ptc::kInvBytes, 0);
      put_text(out, ptc::kInvSerial, "STANDIN", ptc::kInvSerialBytes);
      put_text(out, ptc::kInvDate, "2026-11-25", ptc::kInvDateBytes);
      const std::uint8_t mac[6] = {0x02, 0, 0, 0, 0, 0x01};
      std::memcpy(out.data() + ptc::kInvMac, mac, sizeof mac);
      for (const std::size_t at : {ptc::kInvSoftware, ptc::kInvHardware, ptc::kInvControlFirmware, ptc::kInvSensorFirmware})
        put_text(out, at, "standin", ptc::kInvVersionBytes);
      out[qt128 ? ptc::kInvQt128Model : ptc::kInvModel] = ptc::product_number(model);
      out[qt128 ? ptc::kInvQt128Lines : ptc::kInvLines] = static_cast<std::uint8_t>(channel_count(model));
      return out;
    }
    case Command::config: {
      std::vector<std::uint8_t> out(ptc::kConfigBytes, 0);
      const std::uint8_t ip[4] = {127, 0, 0, 1}, mask[4] = {255, 0, 0, 0};
      std::memcpy(out.data(), ip, 4);
      std::memcpy(out.data() + 4, mask, 4);
      std::memcpy(out.data() + 12, ip, 4);
      put_be16(out, 16, 2368);
      put_be16(out, 18, 10110);
      put_be16(out, 20, rpm);
      out[30] = 1;  // UDP sequence on
      out[34] = 1;  // motor running
      return out;
    }
    case Command::status: {
      const std::size_t temperatures = ptc::status_temperature_count(model);
      std::vector<std::uint8_t> out(ptc::status_bytes(temperatures) + 5, 0);
      put_be32(out, 0, static_cast<std::uint32_t>((monotonic_ns() - opened_ns_) / 1000000000));
      put_be16(out, 4, motor_rpm_);
      for (std::size_t i = 0; i < temperatures; ++i) put_be32(out, 6 + 4 * i, 2500);
      put_be32(out, 6 + 4 * temperatures + 2, 1);  // start-ups
      return out;
    }
    case Command::signature_start: {
      std::uint8_t lidar_random[ptc::kRandomBytes];
      std::array<std::uint8_t, 32> key{};
      if (content_.secret.empty()) {
        code = static_cast<std::uint8_t>(ptc::ReturnCode::unsupported_command);
        return {};
      }
      if (request.size() != ptc::kRandomBytes || !random_bytes(lidar_random, sizeof lidar_random) ||
          hesai_session_key(ByteView{reinterpret_cast<const std::uint8_t*>(content_.secret.data()), content_.secret.size()},
                            lidar_random, request.data(), key.data()) != Error::ok) {
        code = static_cast<std::uint8_t>(ptc::ReturnCode::invalid_parameter);
        return {};
      }
      {
        std::lock_guard<std::mutex> lock(session_mutex_);
        key_ = key;
        session_on_ = true;
      }
      secure_wipe(key.data(), key.size());
      ++sessions_started_;
      return std::vector<std::uint8_t>(lidar_random, lidar_random + sizeof lidar_random);
    }
    case Command::signature_state: {
      std::lock_guard<std::mutex> lock(session_mutex_);
      return {static_cast<std::uint8_t>(session_on_ ? 1 : 0)};
    }
    case Command::signature_stop: {
      std::lock_guard<std::mutex> lock(session_mutex_);
      session_on_ = false;
      secure_wipe(key_.data(), key_.size());
      return {};
    }
  }
  code = static_cast<std::uint8_t>(ptc::ReturnCode::unsupported_command);
  return {};
}

}  // namespace hesai::port
