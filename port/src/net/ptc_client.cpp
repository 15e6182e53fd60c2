#include "hesai_port/net/ptc_client.h"

#include <arpa/inet.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <netinet/in.h>

#include "hesai_port/base/clock.h"
#include "hesai_port/base/text.h"
#include "hesai_port/net/tls.h"

namespace hesai::port {
namespace {

// How a certificate names a serial (subject_names_serial), for the refusals.
constexpr const char* kSerialRule =
    "its serialNumber, or its CN where it has none, must equal the serial exactly";

std::string hex_byte(std::uint8_t b) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%02X", b);
  return text;
}

}  // namespace

PtcClient::PtcClient(std::string host, std::uint16_t port, int timeout_ms)
    : host_(std::move(host)), connect_host_(host_), port_(port), timeout_ms_(timeout_ms) {}

PtcClient::PtcClient(std::string host, std::uint32_t ipv4, std::uint16_t port, int timeout_ms)
    : host_(std::move(host)), port_(port), timeout_ms_(timeout_ms) {
  char text[INET_ADDRSTRLEN] = {};
  in_addr a{};
  a.s_addr = ipv4;
  inet_ntop(AF_INET, &a, text, sizeof text);  // a dotted quad: connecting resolves nothing
  connect_host_ = text;
}

PtcResult PtcClient::fail(PtcOutcome outcome, ptc::Command command, const std::string& what) {
  transport_.reset();
  PtcResult r;
  r.outcome = outcome;
  const std::uint8_t c = static_cast<std::uint8_t>(command);
  r.message = host_ + ":" + std::to_string(port_) + ": command " + hex_byte(c) + " (" + ptc::command_name(c) + "): " + what;
  return r;
}

std::string PtcClient::seconds() const {
  return std::to_string(timeout_ms_ / 1000) + "." + std::to_string(timeout_ms_ % 1000 / 100) + " s";
}

PtcResult PtcClient::request(ptc::Command command, ByteView payload, std::vector<std::uint8_t>& response) {
  std::lock_guard<std::mutex> lock(mutex_);
  response.clear();
  const std::int64_t deadline = monotonic_ns() + static_cast<std::int64_t>(timeout_ms_) * 1000000;
  // A request started once the flag is up runs to its deadline (the clean-up after a stop).
  active_stop_ = stop_ != nullptr && !stop_->load() ? stop_ : nullptr;
  if (transport_) transport_->set_stop(active_stop_);
  if (!transport_) {
    if (PtcResult r = open(command, deadline); !r.ok()) return r;
  }
  return exchange(command, payload, response, deadline);
}

PtcResult PtcClient::open(ptc::Command command, std::int64_t deadline) {
  std::string error;
  if (!tls_) {
    auto tcp = std::make_unique<TcpTransport>();
    tcp->set_stop(active_stop_);
    const PtcTransport::Io io = tcp->connect(connect_host_, port_, deadline, error);
    if (io == PtcTransport::Io::stopped) return fail(PtcOutcome::stopped, command, "interrupted while connecting");
    if (io == PtcTransport::Io::timeout) return fail(PtcOutcome::timeout, command, error + " within " + seconds());
    if (io != PtcTransport::Io::ok) return fail(PtcOutcome::unreachable, command, error);
    transport_ = std::move(tcp);
    return PtcResult{};
  }
  auto tls = std::make_unique<TlsTransport>();
  tls->set_stop(active_stop_);
  const PtcTransport::Io io = tls->connect(tls_, connect_host_, port_, deadline, error);
  if (io == PtcTransport::Io::stopped) return fail(PtcOutcome::stopped, command, "interrupted while connecting");
  if (io == PtcTransport::Io::timeout) return fail(PtcOutcome::timeout, command, error + " within " + seconds());
  if (io != PtcTransport::Io::ok && !tls->tcp_connected()) return fail(PtcOutcome::unreachable, command, error);
  if (io != PtcTransport::Io::ok) return fail(PtcOutcome::tls, command, "TLS: " + error);
  const std::vector<SubjectName> subject = tls->peer_subject();
  const TlsClientOptions& o = tls_->client_options();
  // The serial the user expects, before any command reaches the unit.
  if (!o.expect_serial.empty() && !subject_names_serial(subject, o.expect_serial))
    return fail(PtcOutcome::tls, command,
                "TLS: the unit's certificate (" + subject_text(subject) + ") does not name the expected serial '" +
                    terminal_text(o.expect_serial) + "' (--expect-serial; " + kSerialRule + "); no command was sent");
  transport_ = std::move(tls);
  if (o.insecure) return PtcResult{};
  // The serial the unit gives for itself: its certificate must name it.
  std::vector<std::uint8_t> inventory;
  if (PtcResult r = exchange(ptc::Command::inventory, {}, inventory, deadline); !r.ok()) {
    if (command != ptc::Command::inventory) r.message += " (the inventory is asked first on a PTCS connection, for its serial)";
    return r;
  }
  ptc::Inventory inv;
  if (const Error e = ptc::parse_inventory(ByteView{inventory.data(), inventory.size()}, inv); e != Error::ok)
    return fail(PtcOutcome::tls, command,
                            "TLS: the inventory (" + std::to_string(inventory.size()) +
                    " bytes) gives no serial to check the certificate by: " + error_name(e));
  std::string serial(inv.serial);  // without the spaces a unit may pad it with
  const std::size_t first = serial.find_first_not_of(' ');
  serial = first == std::string::npos ? std::string() : serial.substr(first, serial.find_last_not_of(' ') - first + 1);
  if (!subject_names_serial(subject, serial))
    return fail(PtcOutcome::tls, command,
                "TLS: the unit's certificate (" + subject_text(subject) + ") does not name the serial '" +
                    terminal_text(serial) + "' of its inventory (0x07; " + kSerialRule +
                    "): not the unit it claims to be");
  return PtcResult{};
}

PtcResult PtcClient::exchange(ptc::Command command, ByteView payload, std::vector<std::uint8_t>& response,
                              std::int64_t deadline) {
  response.clear();
  const auto io_failure = [&](PtcTransport::Io io, const char* during) {
    const std::string cause = transport_ ? transport_->last_error() : std::string();
    switch (io) {
      case PtcTransport::Io::timeout: return fail(PtcOutcome::timeout, command, std::string("no ") + during + " within " + seconds());
      case PtcTransport::Io::stopped: return fail(PtcOutcome::stopped, command, std::string("interrupted during the ") + during);
      case PtcTransport::Io::closed: return fail(PtcOutcome::cut_short, command, std::string("the sensor closed the connection within the ") + during);
      default:
        if (!cause.empty()) return fail(PtcOutcome::tls, command, std::string("TLS error during the ") + during + ": " + cause);
        return fail(PtcOutcome::io_error, command, std::string("socket error during the ") + during + ": " + std::strerror(errno));
    }
  };

  std::vector<std::uint8_t> frame(ptc::kHeaderBytes + payload.size);
  std::size_t written = 0;
  if (ptc::encode_request(command, payload, frame.data(), frame.size(), written) != Error::ok)
    return fail(PtcOutcome::io_error, command, "request too large");
  if (const auto io = transport_->send_all(frame.data(), written, deadline); io != PtcTransport::Io::ok)
    return io_failure(io, "request");

  std::uint8_t header_bytes[ptc::kHeaderBytes];
  if (const auto io = transport_->receive_exact(header_bytes, sizeof header_bytes, deadline); io != PtcTransport::Io::ok)
    return io_failure(io, "response header");
  ptc::Header header;
  const std::uint32_t bound = ptc::max_response_bytes(command);
  const Error e = ptc::check_response(ByteView{header_bytes, sizeof header_bytes}, command, bound, header);
  if (e == Error::ptc_bad_magic || e == Error::ptc_command_mismatch || e == Error::ptc_length_exceeds_bound) {
    const std::string what =
        e == Error::ptc_bad_magic
            ? "the response does not start with 47 74 (got " + hex_byte(header_bytes[0]) + " " + hex_byte(header_bytes[1]) + ")"
        : e == Error::ptc_command_mismatch
            ? "the response echoes command " + hex_byte(header.command)
            : "the response announces " + std::to_string(header.length) + " bytes, above this command's bound of " +
                  std::to_string(bound);
    PtcResult r = fail(PtcOutcome::framing, command, what);
    r.error = e;
    return r;
  }
  // The length is within the bound: the payload may be stored (and, after an error code, read to
  // keep the stream in step).
  response.resize(header.length);
  if (const auto io = transport_->receive_exact(response.data(), response.size(), deadline); io != PtcTransport::Io::ok) {
    response.clear();
    PtcResult r = io_failure(io, "response payload");
    if (r.outcome == PtcOutcome::cut_short || r.outcome == PtcOutcome::timeout)
      r.message += " (" + std::to_string(header.length) + " bytes announced)";
    return r;
  }
  if (e == Error::ptc_sensor_error) {
    response.clear();
    const std::uint8_t c = static_cast<std::uint8_t>(command);
    PtcResult r;
    r.outcome = PtcOutcome::sensor_error;
    r.error = e;
    r.return_code = header.return_code;
    r.message = host_ + ":" + std::to_string(port_) + ": command " + hex_byte(c) + " (" + ptc::command_name(c) +
                "): the sensor answered '" + ptc::return_code_name(header.return_code) + "' (return code " +
                std::to_string(header.return_code) + ")";
    return r;
  }
  return PtcResult{};
}

}  // namespace hesai::port
