// hesai replay: sends a capture's UDP payloads, paced as recorded; with --serve-ptc it also stands
// in for the sensor's PTC service (port/include/hesai_port/net/ptc_server.h) and, once a signature
// session starts, signs each QT128 packet with the session's key, as the sensor would.
#include <array>
#include <cctype>
#include <csignal>
#include <cstdio>
#include <thread>
#include <vector>

#include "hesai/ct.h"
#include "hesai/decoder.h"
#include "hesai_port/base/clock.h"
#include "hesai_port/capture/capture.h"
#include "hesai_port/net/ptc_server.h"
#include "hesai_port/net/tls.h"
#include "hesai_port/net/udp.h"
#include "commands.h"
#include "hesai_port/base/files.h"

namespace hesai::cli {
namespace {

// Writes `seq` into a packet's UDP sequence field, if it has one (QT128: CRC3 re-sealed).
// Returns false for packets without a sequence field.
bool renumber(std::vector<std::uint8_t>& p, std::uint32_t seq) {
  return write_udp_sequence(p.data(), p.size(), seq) == Error::ok;
}

// The model and motor speed of a capture's first point-cloud packet (Model::unknown: none).
Model first_model(const std::string& capture, std::uint16_t& rpm) {
  port::CaptureFile file;
  port::UdpDatagram d;
  if (file.open(capture) != port::CaptureError::ok) return Model::unknown;
  while (file.next(d) == port::CaptureStatus::datagram) {
    Model m = Model::unknown;
    PacketKind kind = PacketKind::point_cloud;
    if (identify(d.payload, m, kind) != Error::ok || kind != PacketKind::point_cloud) continue;
    Decoder decoder(m);
    PacketInfo info;
    rpm = decoder.validate(d.payload, info) == Error::ok ? info.motor_rpm : 0;
    return m;
  }
  return Model::unknown;
}

// Sleeps until `deadline_ns` (monotonic), in slices of at most 100 ms: Ctrl-C ends even a long
// pause of a slowed-down replay within one.
void sleep_unless_stopped(std::int64_t deadline_ns) {
  while (!g_stop) {
    const std::int64_t now = port::monotonic_ns();
    if (now >= deadline_ns) return;
    port::sleep_until_ns(deadline_ns - now < 100000000 ? deadline_ns : now + 100000000);
  }
}

// Wipes a key buffer when it goes out of scope, on every return path.
class WipeOnExit {
 public:
  WipeOnExit(void* p, std::size_t n) : p_(p), n_(n) {}
  ~WipeOnExit() { secure_wipe(p_, n_); }
  WipeOnExit(const WipeOnExit&) = delete;
  WipeOnExit& operator=(const WipeOnExit&) = delete;

 private:
  void* p_;
  std::size_t n_;
};

// The stand-in's options: --serve-ptc [ADDR:]PORT and the files it serves.
struct StandIn {
  std::string serve;  // [ADDR:]PORT; empty: no PTC service
  std::string calibration, firetimes, channel_config, secret_file;
  port::TlsServerOptions tls;  // --tls-cert, --tls-key, --client-ca: PTCS
  bool wait_for_session = false;
  bool never_sign = false;  // sessions accepted, no packet signed (a misbehaving unit)
  bool silent_after_session = false;  // PTC read and never answered once a session started
  int ptp_state = -1;       // --ptp-state: -1 none (clock source GPS, unlocked)
  // For tests, not in --help (docs/TESTING.md): --refuse-set CMD[:CODE] (the set command CMD,
  // 0x.. or decimal, answers CODE, default 1), --ignore-set CMD (acknowledged, not applied),
  // --config-bytes N (the configuration answer cut to N bytes), --reboot-seconds S|never (down after
  // 0x10; never: no restart).
  std::array<std::uint8_t, 256> refuse{};
  std::array<bool, 256> ignore{};
  std::size_t config_bytes = 47;
  int reboot_ms = 1500;
  std::uint32_t cut_after_set = 0;  // --cut-after-set N[:S]: the N-th set command handled, its connection
  int cut_down_ms = 0;              // closed unanswered, then down for S seconds (default 0)
  bool test_hooks = false;
};

// A command byte: 0x.. or decimal, 0 to 255.
bool parse_command_byte(const std::string& text, std::uint8_t& out) {
  std::uint64_t v = 0;
  bool ok = false;
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
    ok = text.size() <= 4;
    for (std::size_t i = 2; ok && i < text.size(); ++i) {
      const char c = static_cast<char>(std::tolower(static_cast<unsigned char>(text[i])));
      ok = (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
      v = v * 16 + static_cast<std::uint64_t>(c <= '9' ? c - '0' : c - 'a' + 10);
    }
  } else {
    ok = parse_u64(text, v) && v <= 255;
  }
  if (ok) out = static_cast<std::uint8_t>(v);
  return ok;
}

// One of the stand-in's test options (StandIn above); false when `a` is none of them. A bad value
// sets `error`.
bool parse_stand_in_test_option(const std::string& a, Args& args, StandIn& o, std::string& error) {
  std::string v;
  if (a != "--refuse-set" && a != "--ignore-set" && a != "--config-bytes" && a != "--reboot-seconds" && a != "--ptp-state" &&
      a != "--cut-after-set")
    return false;
  if (!args.value(a, v)) {
    error = a + " needs a value";
    return true;
  }
  if (a == "--ptp-state") {
    const char* names[] = {"free_run", "tracking", "locked", "frozen"};
    o.ptp_state = -1;
    for (int i = 0; i < 4; ++i)
      if (v == names[i]) o.ptp_state = i;
    if (o.ptp_state < 0) error = "--ptp-state takes free_run, tracking, locked or frozen, got '" + v + "'";
    return true;
  }
  o.test_hooks = true;
  std::uint8_t command = 0;
  if (a == "--refuse-set") {
    const std::size_t colon = v.find(':');
    std::uint64_t code = 1;
    if (!parse_command_byte(v.substr(0, colon), command) ||
        (colon != std::string::npos && (!parse_u64(v.substr(colon + 1), code) || code == 0 || code > 255)))
      error = "--refuse-set takes CMD[:CODE] (CODE 1 to 255), got '" + v + "'";
    else o.refuse[command] = static_cast<std::uint8_t>(code);
  } else if (a == "--ignore-set") {
    if (!parse_command_byte(v, command)) error = "--ignore-set takes a command byte, got '" + v + "'";
    else o.ignore[command] = true;
  } else if (a == "--cut-after-set") {
    const std::size_t colon = v.find(':');
    std::uint64_t n = 0;
    float seconds = 0;
    if (!parse_u64(v.substr(0, colon), n) || n == 0 || n > 1000 ||
        (colon != std::string::npos &&
         (!parse_float(v.substr(colon + 1), seconds) || !(seconds >= 0) || seconds > 600)))
      error = "--cut-after-set takes N[:SECONDS] (N 1 to 1000, SECONDS 0 to 600), got '" + v + "'";
    o.cut_after_set = static_cast<std::uint32_t>(n);
    o.cut_down_ms = static_cast<int>(seconds * 1000);
  } else if (a == "--config-bytes") {
    std::uint64_t n = 0;
    if (!parse_u64(v, n) || n > 47) error = "--config-bytes takes 0 to 47, got '" + v + "'";
    else o.config_bytes = static_cast<std::size_t>(n);
  } else {
    float seconds = 0;
    if (v == "never") o.reboot_ms = -1;  // 0x10 acknowledged, no restart
    else if (!parse_float(v, seconds) || !(seconds >= 0) || seconds > 600)
      error = "--reboot-seconds takes 0 to 600 or never, got '" + v + "'";
    else o.reboot_ms = static_cast<int>(seconds * 1000);
  }
  return true;
}

// Opens the stand-in's PTC service for `capture`; `address` is the address it serves on (the
// datagrams are sent from it too). Returns an exit status.
int open_stand_in(const StandIn& o, const std::string& capture, port::PtcServer& server, std::string& address) {
  const std::size_t colon = o.serve.rfind(':');
  address = colon == std::string::npos ? "127.0.0.1" : o.serve.substr(0, colon);
  std::uint64_t port = 0;
  if (!parse_u64(colon == std::string::npos ? o.serve : o.serve.substr(colon + 1), port) || port > 65535)
    return usage_error("replay", "--serve-ptc takes [ADDR:]PORT, got '" + o.serve + "'");
  port::StandInContent content;
  struct WipeContent {
    port::StandInContent& c;
    ~WipeContent() { wipe_secret(c.secret); }  // moved into the server, or never used: wiped either way
  } wipe_content{content};
  std::uint16_t rpm = 0;
  content.model = first_model(capture, rpm);
  content.ptp_state = o.ptp_state;
  content.refuse = o.refuse;
  content.ignore = o.ignore;
  content.config_bytes = o.config_bytes;
  content.reboot_ms = o.reboot_ms;
  content.silent_after_session = o.silent_after_session;
  content.cut_after_set = o.cut_after_set;
  content.cut_down_ms = o.cut_down_ms;
  std::string error;
  const std::pair<const std::string*, std::string*> files[] = {
      {&o.calibration, &content.calibration}, {&o.firetimes, &content.firetimes}, {&o.channel_config, &content.channel_config}};
  for (const auto& [path, text] : files) {
    if (!path->empty())
      if (const port::Status s = port::read_text_file(*path, *text); !s.ok()) return report("replay", s);
  }
  if (!o.secret_file.empty()) {
    if (const int st = read_secret(o.secret_file, content.secret, error); st != kExitOk) {
      std::fprintf(stderr, "hesai replay: %s\n", error.c_str());
      return st;
    }
  }
  if (!o.tls.cert_file.empty()) {
    if (!port::tls_available()) return usage_error("replay", "built without TLS: --tls-cert needs a build with OpenSSL");
    std::shared_ptr<port::TlsContext> tls = port::TlsContext::server(o.tls, error);
    if (!tls) {
      std::fprintf(stderr, "hesai replay: %s\n", error.c_str());
      return kExitInput;
    }
    server.use_tls(std::move(tls));
  }
  if (!server.open(address, static_cast<std::uint16_t>(port), std::move(content), error)) {
    std::fprintf(stderr, "hesai replay: %s\n", error.c_str());
    return kExitInput;
  }
  server.set_motor_speed(rpm);
  std::fprintf(stderr, "serving PTC on %s:%u%s\n", address.c_str(), server.port(),
               o.tls.cert_file.empty() ? "" : o.tls.client_ca_file.empty() ? " over TLS (PTCS)" : " over mTLS (PTCS)");
  return kExitOk;
}

// Runs a PtcServer on a thread of its own while in scope.
class ServerThread {
 public:
  ServerThread(port::PtcServer& server, bool run) : server_(server) {
    if (run) thread_ = std::thread([this] { server_.run(); });
  }
  ~ServerThread() {
    server_.stop();
    if (thread_.joinable()) thread_.join();
  }
  ServerThread(const ServerThread&) = delete;
  ServerThread& operator=(const ServerThread&) = delete;

 private:
  port::PtcServer& server_;
  std::thread thread_;
};

}  // namespace

int cmd_replay(Args& args) {
  std::string capture, to, multicast_if, error, rate_text = "1";
  std::uint64_t loops = 1;
  bool quiet = false, renumber_sequence = false;
  std::uint64_t unsigned_before_session = 0;  // --unsigned-before-session N (tests)
  std::uint64_t from_port = 0;  // --from-port; 0: the kernel's choice
  StandIn stand_in;
  while (!args.empty()) {
    const std::string a = args.take();
    std::string v;
    if (a == "--help" || a == "-h") {
      std::printf("usage: hesai replay CAPTURE --to HOST:PORT [--rate 1|N|max] [--loop N]\n\n"
                  "Sends the UDP payloads of a capture to HOST:PORT.\n\n"
                  "  --to HOST:PORT          destination (a multicast group too: looped back to this host)\n"
                  "  --multicast-if ADDR     with a multicast group: send through the interface of this\n"
                  "                          local IPv4 address (default: the kernel's route to the group)\n"
                  "  --rate 1|N|max          the recorded pace (1), N times faster, or as fast as possible\n"
                  "  --loop N                play the capture N times (default 1)\n"
                  "  --from-port PORT        send from this UDP port, as a unit sends from a fixed one (a\n"
                  "                          listener keeps each sender apart; default: one the kernel picks)\n"
                  "  --renumber              rewrite UDP sequence numbers to count up across loops (QT128:\n"
                  "                          CRC3 re-sealed; the capture's own signatures then no longer\n"
                  "                          verify, a stand-in's session signs after). With a session,\n"
                  "                          a loop not renumbered replays the numbers: listen refuses them\n"
                  "  --quiet                 no summary\n\n"
                  "A stand-in sensor (for tests, and for trying 'hesai sensor' and 'listen --sensor' without\n"
                  "hardware):\n"
                  "  --serve-ptc [ADDR:]PORT answer PTC on ADDR (default 127.0.0.1) and PORT (0: any free port,\n"
                  "                          printed); the datagrams are then sent from ADDR, as a sensor's\n"
                  "  --calibration FILE      served for PTC 0x05 (the file, byte for byte)\n"
                  "  --firetimes FILE        served for 0xA9\n"
                  "  --channel-config FILE   served for 0xA8\n"
                  "  --secret-file FILE      the shared secret: signature sessions (0x2E) are accepted, and\n"
                  "                          while one runs every QT128 packet is signed with its key\n"
                  "  --wait-for-session      send nothing until a signature session starts\n"
                  "  --never-sign            accept signature sessions but sign no packet (a unit that\n"
                  "                          misbehaves, for tests)\n"
                  "  --silent-after-session  once a signature session starts, accept PTC connections and\n"
                  "                          read requests but answer none (a unit whose PTC hangs, for tests)\n"
                  "  --ptp-state STATE       clock source PTP, in STATE (free_run, tracking, locked, frozen)\n"
                  "                          for the status (0x09) and PTP diagnostics (0x06); without it\n"
                  "                          the clock source is GPS, unlocked (free running)\n"
                  "  --tls-cert FILE --tls-key FILE  PTCS: serve over TLS 1.3 with this certificate (PEM; its\n"
                  "                          subject should name the serial the inventory gives, STANDIN)\n"
                  "                          and key (mode 0600)\n"
                  "  --client-ca FILE        mTLS: require a client certificate that chains to this CA (PEM)\n");
      return kExitOk;
    }
    if (a == "--to") { if (!args.value(a, to)) return usage_error("replay", "--to needs HOST:PORT"); }
    else if (a == "--multicast-if") { if (!args.value(a, multicast_if)) return usage_error("replay", "--multicast-if needs an address"); }
    else if (a == "--rate") { if (!args.value(a, rate_text)) return usage_error("replay", "--rate needs 1, N or max"); }
    else if (a == "--loop") { if (!args.value(a, v) || !parse_u64(v, loops) || loops == 0) return usage_error("replay", "--loop needs N >= 1"); }
    else if (a == "--from-port") {
      if (!args.value(a, v) || !parse_u64(v, from_port) || from_port == 0 || from_port > 65535)
        return usage_error("replay", "--from-port needs a UDP port, 1 to 65535");
    }
    else if (a == "--quiet") quiet = true;
    else if (a == "--renumber") renumber_sequence = true;
    else if (a == "--wait-for-session") stand_in.wait_for_session = true;
    else if (a == "--never-sign") stand_in.never_sign = true;
    else if (a == "--silent-after-session") stand_in.silent_after_session = true;
    else if (a == "--unsigned-before-session") {  // for tests, not in --help (docs/TESTING.md)
      if (!args.value(a, v) || !parse_u64(v, unsigned_before_session) || unsigned_before_session == 0 ||
          unsigned_before_session > 100000)
        return usage_error("replay", "--unsigned-before-session takes 1 to 100000 packets");
    }
    else if (parse_stand_in_test_option(a, args, stand_in, error)) {
      if (!error.empty()) return usage_error("replay", error);
    }
    else if (a == "--serve-ptc" || a == "--calibration" || a == "--firetimes" || a == "--channel-config" ||
             a == "--secret-file" || a == "--tls-cert" || a == "--tls-key" || a == "--client-ca") {
      std::string& target = a == "--serve-ptc"       ? stand_in.serve
                            : a == "--calibration"   ? stand_in.calibration
                            : a == "--firetimes"     ? stand_in.firetimes
                            : a == "--channel-config" ? stand_in.channel_config
                            : a == "--tls-cert"      ? stand_in.tls.cert_file
                            : a == "--tls-key"       ? stand_in.tls.key_file
                            : a == "--client-ca"     ? stand_in.tls.client_ca_file
                                                     : stand_in.secret_file;
      if (!args.value(a, target)) return usage_error("replay", a + " needs a value");
    }
    else if (a.rfind("--", 0) == 0) return usage_error("replay", "unknown option " + a);
    else if (capture.empty()) capture = a;
    else return usage_error("replay", "one capture at a time ('" + a + "')");
  }
  if (capture.empty()) return usage_error("replay", "missing CAPTURE");
  if (to.empty()) return usage_error("replay", "missing --to HOST:PORT");
  float rate = 0;  // 0: as fast as possible
  if (rate_text != "max" && (!parse_float(rate_text, rate) || rate <= 0))
    return usage_error("replay", "--rate takes 1, a factor N > 0, or max");

  const bool serving = !stand_in.serve.empty();
  if (!serving && (!stand_in.calibration.empty() || !stand_in.firetimes.empty() || !stand_in.channel_config.empty() ||
                   !stand_in.secret_file.empty() || stand_in.wait_for_session || stand_in.never_sign ||
                   stand_in.ptp_state >= 0 || stand_in.test_hooks))
    return usage_error("replay", "--calibration, --firetimes, --channel-config, --secret-file, --wait-for-session, "
                                 "--never-sign, --ptp-state and the stand-in's test options go with --serve-ptc");
  const port::TlsServerOptions& tls = stand_in.tls;
  if (!serving && (!tls.cert_file.empty() || !tls.key_file.empty() || !tls.client_ca_file.empty()))
    return usage_error("replay", "--tls-cert, --tls-key and --client-ca go with --serve-ptc");
  if (tls.cert_file.empty() != tls.key_file.empty())
    return usage_error("replay", "--tls-cert and --tls-key go together");
  if (!tls.client_ca_file.empty() && tls.cert_file.empty())
    return usage_error("replay", "--client-ca (mTLS) needs --tls-cert and --tls-key");
  if (stand_in.wait_for_session && stand_in.secret_file.empty())
    return usage_error("replay", "--wait-for-session needs --secret-file (no session can start without it)");
  if (stand_in.silent_after_session && (!serving || stand_in.secret_file.empty()))
    return usage_error("replay", "--silent-after-session needs --serve-ptc and --secret-file (no session can start without them)");

  port::CaptureFile file;
  if (!open_capture(capture, file)) return kExitInput;
  port::PtcServer server;
  std::string address;
  if (serving) {
    if (const int st = open_stand_in(stand_in, capture, server, address); st != kExitOk) return st;
  }
  port::UdpSender sender;
  sender.set_source(serving && address != "0.0.0.0" ? address : "", static_cast<std::uint16_t>(from_port));
  if (!sender.open(to, multicast_if, error)) return usage_error("replay", error);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  // --unsigned-before-session N: the first N datagrams of the capture, unsigned, sent when the
  // first 0x2E arrives and before it is answered (so received before the session's key is agreed);
  // the stream itself then starts 50 ms after the session (--wait-for-session), or more.
  std::vector<std::vector<std::uint8_t>> before_session;
  if (unsigned_before_session > 0) {
    if (!serving || !stand_in.wait_for_session)
      return usage_error("replay", "--unsigned-before-session needs --serve-ptc and --wait-for-session");
    port::CaptureFile first;
    if (!open_capture(capture, first)) return kExitInput;
    port::UdpDatagram d;
    while (before_session.size() < unsigned_before_session && first.next(d) == port::CaptureStatus::datagram)
      before_session.emplace_back(d.payload.data, d.payload.data + d.payload.size);
    server.on_first_session([&] {
      for (const auto& p : before_session) sender.send(p.data(), p.size());
    });
  }
  ServerThread ptc_thread(server, serving);
  while (stand_in.wait_for_session && server.sessions_started() == 0 && !g_stop)
    port::sleep_until_ns(port::monotonic_ns() + 10000000);
  if (unsigned_before_session > 0) port::sleep_until_ns(port::monotonic_ns() + 50000000);
  std::uint8_t key[32] = {};
  const WipeOnExit wipe_key_on_exit(key, sizeof key);  // every return below
  std::uint64_t signed_packets = 0;
  std::uint64_t sent = 0, failed = 0;
  std::uint32_t next_sequence = 0;
  std::vector<std::uint8_t> packet;
  const std::int64_t start = port::monotonic_ns();
  for (std::uint64_t loop = 0; loop < loops && !g_stop; ++loop) {
    if (loop > 0 && file.open(capture) != port::CaptureError::ok) {
      std::fprintf(stderr, "hesai: %s\n", file.message().c_str());
      return kExitInput;
    }
    port::UdpDatagram d;
    std::int64_t first_record = -1, loop_start = port::monotonic_ns();
    for (;;) {
      const port::CaptureStatus st = file.next(d);
      if (st == port::CaptureStatus::end || g_stop) break;
      if (st == port::CaptureStatus::error) {
        std::fprintf(stderr, "hesai: %s\n", file.message().c_str());
        return kExitInput;
      }
      if (rate > 0) {
        const std::int64_t t = static_cast<std::int64_t>(d.time_ns);
        if (first_record < 0) first_record = t;
        sleep_unless_stopped(loop_start + static_cast<std::int64_t>(static_cast<double>(t - first_record) / rate));
      }
      // A running session signs every QT128 packet that has room for a signature.
      const bool sign = serving && !stand_in.never_sign && server.session_key(key);
      bool ok;
      if (renumber_sequence || sign) {
        packet.assign(d.payload.data, d.payload.data + d.payload.size);
        if (renumber_sequence && renumber(packet, next_sequence)) ++next_sequence;
        if (sign && qt128::sign(packet.data(), packet.size(), key) == Error::ok) ++signed_packets;
        ok = sender.send(packet.data(), packet.size());
      } else {
        ok = sender.send(d.payload.data, d.payload.size);
      }
      if (ok) ++sent;
      else ++failed;
    }
  }
  secure_wipe(key, sizeof key);
  if (!quiet)
    std::fprintf(stderr, "sent %llu datagrams to %s in %.2f s (%llu failed, %llu signed)\n", static_cast<unsigned long long>(sent),
                 to.c_str(), static_cast<double>(port::monotonic_ns() - start) / 1e9, static_cast<unsigned long long>(failed),
                 static_cast<unsigned long long>(signed_packets));
  return failed ? kExitInput : kExitOk;
}

}  // namespace hesai::cli
