#include "hesai_port/net/ptc_server.h"

#include <arpa/inet.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string_view>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include "hesai/ct.h"
#include "hesai/hkdf.h"
#include "hesai/ptc.h"
#include "hesai/ptc_settings.h"
#include "hesai_port/base/clock.h"
#include "hesai_port/base/random.h"
#include "hesai_port/net/transport.h"
#include "hesai_port/net/tls.h"

namespace hesai::port {
namespace {

constexpr std::uint32_t kMaxRequestBytes = 4096;
constexpr int kPollMs = 100;  // the longest wait before the stop flag is looked at again

constexpr std::int64_t ms_to_ns(int ms) { return static_cast<std::int64_t>(ms) * 1000000; }

// Wipes all of a string's storage, not only its size: a string moved from keeps its old bytes in
// its small-string buffer.
void wipe_string(std::string& s) {
  s.resize(s.capacity());
  secure_wipe(&s[0], s.size());
  s.clear();
}

void put_text(std::vector<std::uint8_t>& out, std::size_t at, std::string_view text, std::size_t field) {
  for (std::size_t i = 0; i < field && i < text.size(); ++i) out[at + i] = static_cast<std::uint8_t>(text[i]);
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
  wipe_string(content_.secret);
}

bool PtcServer::open(const std::string& address, std::uint16_t port, StandInContent content, std::string& error) {
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_port = htons(port);
  // The secret is wiped on every path: moved into content_ on success, wiped here otherwise.
  const auto refuse = [&](const std::string& message) {
    wipe_string(content.secret);
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    error = message;
    return false;
  };
  if (inet_pton(AF_INET, address.c_str(), &sa.sin_addr) != 1) return refuse("not an IPv4 address: " + address);
  fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const int one = 1;
  if (fd_ >= 0) setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  if (fd_ < 0 || bind(fd_, reinterpret_cast<const sockaddr*>(&sa), sizeof sa) != 0 || listen(fd_, 16) != 0)
    return refuse("cannot serve PTC on " + address + ":" + std::to_string(port) + ": " + std::strerror(errno));
  socklen_t len = sizeof sa;
  getsockname(fd_, reinterpret_cast<sockaddr*>(&sa), &len);
  port_ = ntohs(sa.sin_port);
  content_ = std::move(content);
  wipe_string(content.secret);
  opened_ns_ = monotonic_ns();
  const std::uint8_t loopback[4] = {127, 0, 0, 1};
  std::memcpy(settings_.destination_ip, loopback, 4);
  settings_.destination_port = 2368;
  settings_.gps_port = 10110;
  if (settings_.rpm == 0) settings_.rpm = 600;
  return true;
}

// One client's connection: what it sent that is not answered yet, and the answer being sent.
struct PtcServer::Connection {
  int fd = -1;
  std::int64_t opened_ns = 0;
  std::int64_t last_ns = 0;          // the last request received or answer sent: the idle clock
  std::int64_t answer_ready_ns = 0;  // when `out` was filled: the send deadline's start
  std::vector<std::uint8_t> in;      // at most one request being received, and what followed it
  std::vector<std::uint8_t> out;     // the answer being sent
  std::size_t sent = 0;
  std::uint32_t requests = 0;
};

void PtcServer::run() {
  if (tls_) {
    run_tls();
    return;
  }
  std::vector<Connection> connections;
  std::vector<pollfd> fds;
  while (!stop_) {
    fds.clear();
    fds.push_back(pollfd{fd_, static_cast<short>(connections.size() < kMaxConnections ? POLLIN : 0), 0});
    for (const Connection& c : connections)
      fds.push_back(pollfd{c.fd, static_cast<short>(c.sent < c.out.size() ? POLLOUT : POLLIN), 0});
    if (poll(fds.data(), static_cast<nfds_t>(fds.size()), kPollMs) < 0 && errno != EINTR) break;
    const std::int64_t now = monotonic_ns();
    const bool down = rebooting();
    for (std::size_t i = connections.size(); i-- > 0;) {
      Connection& c = connections[i];
      const short events = fds[i + 1].revents;
      // Down after a reboot: every connection is closed once its acknowledgement is sent.
      bool keep = !(down && c.sent >= c.out.size());
      if (!keep || (events & (POLLERR | POLLNVAL)) != 0) keep = false;
      else if ((events & POLLOUT) != 0) keep = on_writable(c);
      else if ((events & (POLLIN | POLLHUP)) != 0) keep = on_readable(c);
      if (keep && c.sent < c.out.size()) keep = now - c.answer_ready_ns < ms_to_ns(kSendMs);
      else if (keep) keep = now - c.last_ns < ms_to_ns(kIdleMs);
      if (keep) keep = now - c.opened_ns < ms_to_ns(kConnectionMs);
      if (!keep) {
        ::close(c.fd);
        connections.erase(connections.begin() + static_cast<std::ptrdiff_t>(i));
      }
    }
    if ((fds[0].revents & POLLIN) != 0 && connections.size() < kMaxConnections) {
      const int client = accept4(fd_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
      if (client >= 0 && rebooting()) {
        ::close(client);  // down: not answered
      } else if (client >= 0) {
        Connection c;
        c.fd = client;
        c.opened_ns = c.last_ns = monotonic_ns();
        connections.push_back(std::move(c));
      }
    }
  }
  for (const Connection& c : connections) ::close(c.fd);
}

bool PtcServer::on_readable(Connection& c) {
  // `in` holds less than one whole request here (a whole one is answered as soon as it is in).
  std::uint8_t buf[4096];
  const std::size_t room = ptc::kHeaderBytes + kMaxRequestBytes - c.in.size();
  const ssize_t n = ::recv(c.fd, buf, room < sizeof buf ? room : sizeof buf, 0);
  if (n == 0) return false;
  if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
  c.in.insert(c.in.end(), buf, buf + n);
  c.last_ns = monotonic_ns();
  return answer_pending(c);
}

bool PtcServer::on_writable(Connection& c) {
  const ssize_t n = ::send(c.fd, c.out.data() + c.sent, c.out.size() - c.sent, MSG_NOSIGNAL | MSG_DONTWAIT);
  if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
  c.sent += static_cast<std::size_t>(n);
  if (c.sent < c.out.size()) return true;
  c.out.clear();
  c.sent = 0;
  c.last_ns = monotonic_ns();
  if (c.requests >= kMaxRequests) return false;
  return answer_pending(c);  // a request that came with the previous one
}

bool PtcServer::answer_pending(Connection& c) {
  if (c.in.size() < ptc::kHeaderBytes) return true;
  ptc::Header header;
  if (ptc::parse_header(ByteView{c.in.data(), ptc::kHeaderBytes}, header) != Error::ok || header.length > kMaxRequestBytes)
    return false;
  const std::size_t whole = ptc::kHeaderBytes + header.length;
  if (c.in.size() < whole) return true;
  const std::vector<std::uint8_t> request(c.in.begin() + ptc::kHeaderBytes, c.in.begin() + static_cast<std::ptrdiff_t>(whole));
  c.in.erase(c.in.begin(), c.in.begin() + static_cast<std::ptrdiff_t>(whole));
  if (silent()) return true;  // read, never answered (the idle limit still closes the connection)
  std::uint8_t code = 0;
  const std::vector<std::uint8_t> payload = answer(header.command, request, code);
  if (cut_) {  // --cut-after-set: handled, not answered
    cut_ = false;
    return false;
  }
  c.out.assign(ptc::kHeaderBytes, 0);
  ptc::encode_header(header.command, code, static_cast<std::uint32_t>(payload.size()), c.out.data());
  c.out.insert(c.out.end(), payload.begin(), payload.end());
  c.sent = 0;
  c.answer_ready_ns = monotonic_ns();
  ++c.requests;
  return true;
}

bool PtcServer::rebooting() const { return monotonic_ns() < down_until_ns_; }

std::vector<std::uint8_t> PtcServer::config_answer() const {
  std::vector<std::uint8_t> out(ptc::kConfigBytes, 0);
  const std::uint8_t ip[4] = {127, 0, 0, 1}, mask[4] = {255, 0, 0, 0};
  std::memcpy(out.data(), ip, 4);
  std::memcpy(out.data() + 4, mask, 4);
  std::memcpy(out.data() + 12, settings_.destination_ip, 4);
  put_be16(out, 16, settings_.destination_port);
  put_be16(out, 18, settings_.gps_port);
  put_be16(out, 20, settings_.rpm);
  out[22] = settings_.sync;
  put_be16(out, 23, sync_centi_);
  put_be16(out, 25, settings_.fov_start);
  put_be16(out, 27, settings_.fov_end);
  out[29] = content_.ptp_state >= 0 ? 1 : 0;  // clock source: PTP with a PTP state, else GPS
  out[30] = 1;                                 // UDP sequence on
  out[32] = settings_.return_mode;
  out[33] = settings_.standby;
  out.resize(content_.config_bytes < out.size() ? content_.config_bytes : out.size());
  return out;
}

bool PtcServer::session_key(std::uint8_t key[32]) const {
  std::lock_guard<std::mutex> lock(session_mutex_);
  if (!session_on_) return false;
  std::memcpy(key, key_.data(), key_.size());
  return true;
}

void PtcServer::run_tls() {
  while (!stop_) {
    pollfd p{fd_, POLLIN, 0};
    if (poll(&p, 1, kPollMs) <= 0) continue;
    const int client = accept4(fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (client < 0) continue;
    if (rebooting()) {  // down: not answered
      ::close(client);
      continue;
    }
    serve_tls(client);
    ::close(client);
  }
}

void PtcServer::serve_tls(int fd) {
  const std::int64_t opened = monotonic_ns();
  const auto wait_deadline = [] { return monotonic_ns() + ms_to_ns(kSendMs); };
  auto tls = std::make_unique<TlsTransport>();  // freed before the caller closes fd
  std::string error;
  if (tls->accept(tls_, fd, wait_deadline(), error) != PtcTransport::Io::ok) {
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
  std::vector<std::uint8_t> request;
  for (std::uint32_t requests = 0; !stop_ && requests < kMaxRequests && monotonic_ns() - opened < ms_to_ns(kConnectionMs);
       ++requests) {
    // A header: the stop flag looked at every kPollMs, for at most kIdleMs.
    int waited = 0;
    pollfd p{fd, POLLIN, 0};
    while (!tls->pending() && poll(&p, 1, kPollMs) == 0)
      if (stop_ || (waited += kPollMs) >= kIdleMs) return;
    std::uint8_t h[ptc::kHeaderBytes];
    if (tls->receive_exact(h, sizeof h, wait_deadline()) != PtcTransport::Io::ok) return;
    ptc::Header header;
    if (ptc::parse_header(ByteView{h, sizeof h}, header) != Error::ok || header.length > kMaxRequestBytes) return;
    request.resize(header.length);
    if (tls->receive_exact(request.data(), request.size(), wait_deadline()) != PtcTransport::Io::ok) return;
    if (silent()) continue;  // read, never answered
    std::uint8_t code = 0;
    const std::vector<std::uint8_t> payload = answer(header.command, request, code);
    if (cut_) {  // --cut-after-set: handled, not answered
      cut_ = false;
      return;
    }
    std::uint8_t out[ptc::kHeaderBytes];
    ptc::encode_header(header.command, code, static_cast<std::uint32_t>(payload.size()), out);
    if (tls->send_all(out, sizeof out, wait_deadline()) != PtcTransport::Io::ok ||
        tls->send_all(payload.data(), payload.size(), wait_deadline()) != PtcTransport::Io::ok || rebooting())
      return;  // after a reboot's acknowledgement, the connection too
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
  {
    ptc::Setting setting;
    ptc::Settings asked = settings_;
    const Error e = ptc::parse_setting(command, ByteView{request.data(), request.size()}, setting, asked);
    if (e != Error::ptc_command_mismatch) {  // a set command
      if (content_.refuse[command] != 0) code = content_.refuse[command];
      else if (e != Error::ok) code = static_cast<std::uint8_t>(ptc::ReturnCode::invalid_parameter);
      else if (!content_.ignore[command]) {
        settings_ = asked;
        if (setting == ptc::Setting::sync_angle) sync_centi_ = static_cast<std::uint16_t>(asked.sync_angle * 100u);
        if (setting == ptc::Setting::rpm) motor_rpm_ = asked.rpm;
      }
      if (++sets_seen_ == content_.cut_after_set) {
        cut_ = true;
        down_until_ns_ = monotonic_ns() + ms_to_ns(content_.cut_down_ms);
      }
      return {};
    }
  }
  switch (static_cast<Command>(command)) {
    case Command::calibration: return file(content_.calibration);
    case Command::firetimes: return file(content_.firetimes);
    case Command::channel_config: return file(content_.channel_config);
    case Command::inventory: {
      const bool qt128 = model == Model::qt128c2x;
      std::vector<std::uint8_t> out(qt128 ? ptc::kInvQt128Bytes : ptc::kInvBytes, 0);
      put_text(out, ptc::kInvSerial, content_.serial, ptc::kInvSerialBytes);
      put_text(out, ptc::kInvDate, "2026-11-25", ptc::kInvDateBytes);
      const std::uint8_t mac[6] = {0x02, 0, 0, 0, 0, 0x01};
      std::memcpy(out.data() + ptc::kInvMac, mac, sizeof mac);
      for (const std::size_t at : {ptc::kInvSoftware, ptc::kInvHardware, ptc::kInvControlFirmware, ptc::kInvSensorFirmware})
        put_text(out, at, "standin", ptc::kInvVersionBytes);
      out[qt128 ? ptc::kInvQt128Model : ptc::kInvModel] = ptc::product_number(model);
      out[qt128 ? ptc::kInvQt128Lines : ptc::kInvLines] = static_cast<std::uint8_t>(channel_count(model));
      return out;
    }
    case Command::config: return config_answer();
    case Command::get_fov: {
      std::vector<std::uint8_t> out(5, 0);
      put_be16(out, 1, settings_.fov_start);
      put_be16(out, 3, settings_.fov_end);
      return out;
    }
    case Command::reboot:
      if (content_.reboot_ms >= 0) {
        down_until_ns_ = monotonic_ns() + ms_to_ns(content_.reboot_ms);
        opened_ns_ = down_until_ns_;  // the uptime counts from the restart
      }
      return {};
    case Command::ptp_diagnostics: {
      if (request.size() != 1 || request[0] != ptc::kPtpQueryStatus) break;
      std::vector<std::uint8_t> out(ptc::kPtpDiagStatusBytes, 0);
      put_be32(out, 8, static_cast<std::uint32_t>(content_.ptp_state >= 0 ? content_.ptp_state : 0));
      put_be32(out, 12, static_cast<std::uint32_t>((monotonic_ns() - opened_ns_) / 1000000));
      return out;
    }
    case Command::status: {
      const std::size_t temperatures = ptc::status_temperature_count(model);
      std::vector<std::uint8_t> out(ptc::status_bytes(temperatures) + 5, 0);
      put_be32(out, 0, static_cast<std::uint32_t>((monotonic_ns() - opened_ns_) / 1000000000));
      put_be16(out, 4, settings_.standby != 0 ? 0 : motor_rpm_.load());
      for (std::size_t i = 0; i < temperatures; ++i) put_be32(out, 6 + 4 * i, 2500);
      put_be32(out, 6 + 4 * temperatures + 2, 1);  // start-ups
      out[6 + 4 * temperatures + 10] = static_cast<std::uint8_t>(content_.ptp_state >= 0 ? content_.ptp_state : 0);
      return out;
    }
    case Command::signature_start: {
      std::uint8_t lidar_random[ptc::kRandomBytes];
      std::array<std::uint8_t, 32> key{};
      if (content_.secret.empty()) {
        code = static_cast<std::uint8_t>(ptc::ReturnCode::unsupported_command);
        return {};
      }
      if (sessions_started_ == 0 && on_first_session_) on_first_session_();
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
    default: break;  // the set commands are answered above; the others are not served
  }
  if (static_cast<Command>(command) == Command::ptp_diagnostics) {
    code = static_cast<std::uint8_t>(ptc::ReturnCode::invalid_parameter);
    return {};
  }
  code = static_cast<std::uint8_t>(ptc::ReturnCode::unsupported_command);
  return {};
}

}  // namespace hesai::port
