// A stand-in sensor's PTC service, for tests and for users without hardware (hesai replay
// --serve-ptc): it answers the commands of hesai/ptc.h from files and the capture's model, and runs
// signature sessions as QT128C2X manual 4.9.3 describes them (the key from the shared secret and
// both randoms, hesai_session_key()).
//
// Answers: 0x05/0xA9/0xA8 the files byte for byte ('unsupported command' without one); 0x07 an
// inventory in the model's layout (serial StandInContent::serial, "STANDIN" by default, MAC 02:00:00:00:00:01, versions "standin");
// 0x08 the configuration it keeps (47 bytes: IP 127.0.0.1, mask 255.0.0.0, destination
// 127.0.0.1:2368, GPS port 10110, the capture's spin rate (600 when unknown), UDP sequence on,
// clock source GPS, or PTP when a PTP state was given, everything else 0); the set commands
// 0x17, 0x1E, 0x1C, 0x18 (the angle kept in 0.01 degree), 0x20 and 0x22 change it (a payload of
// another size: 'invalid input parameter'), 0x23 reports its FOV; 0x09 a status with the model's
// temperature count (each 25.00 C), the uptime since open() or the last reboot, the motor speed set by
// set_motor_speed() (0 in standby) and the PTP state of StandInContent; 0x06 with query 1 the PTP
// status (offset 0, the state, the uptime in ms); 0x10 is acknowledged, then for
// StandInContent::reboot_ms the unit is down: every connection, open or new, is closed unanswered
// (over TLS too). For tests, StandInContent can make a set command answer a return code
// (refuse) or be acknowledged and not applied (ignore), cut the configuration short, and handle
// its N-th set command (applied, refused or ignored as the others) then close that connection
// without an answer, and be down for a while after (cut_after_set, cut_down_ms). 0x2E with
// a 32-byte client random: a fresh lidar random (from /dev/urandom), 'unsupported command' without
// a secret, 'invalid input parameter' for another payload size; 0x2D the session state; 0x2F ends
// the session. Any other command: 'unsupported command'. For tests, StandInContent can make the
// port go silent once a session has started (silent_after_session: the answer to that 0x2E is
// sent; from then on connections are still accepted and requests read, and none is answered, as a
// unit whose PTC service hangs while its TCP stack runs: a client connects at once and waits out
// its whole deadline for the answer).
//
// Limits, so that no client can hold the service (or hesai replay) for long:
// - up to kMaxConnections (8) connections are served at once, by one thread that polls them all
//   (a further client waits in the listen backlog until one closes); each gets its answers in
//   order, one request at a time;
// - a connection is closed when its client closes it, sends a header without the magic or a
//   payload over 4 KiB, stays silent for kIdleMs (10 s) between requests, has not taken an answer
//   within kSendMs (2 s) of its being ready (a client that sends and never reads), has been open
//   for kConnectionMs (60 s), or after kMaxRequests (1000) answers;
// - every wait is a poll of at most 100 ms that looks at the stop flag: run() returns within about
//   100 ms of stop(), whatever the clients do.
//
// With use_tls(), PTCS: connections are served one at a time, each starting with a TLS 1.3
// handshake with the context's certificate (and, with its client CA, a client certificate required
// and verified: mTLS). The same limits hold, but every wait on a client (the handshake, a request's
// payload, an answer not taken) lasts at most kSendMs (2 s): run() returns within 2 s of stop().
// A failed handshake is said on stderr ("stand-in: TLS handshake: ...") and the connection closed.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "hesai/model.h"
#include "hesai/ptc_settings.h"

namespace hesai::port {

class TlsContext;

struct StandInContent {
  Model model = Model::unknown;
  std::string calibration, firetimes, channel_config;  ///< file bytes; empty: not served
  std::string secret;                                  ///< shared secret; empty: no signature sessions
  int ptp_state = -1;            ///< 0 free run .. 3 frozen: clock source PTP; -1: clock source GPS, unlocked
  int reboot_ms = 1500;          ///< how long the unit is down after 0x10 (its uptime then counts anew);
                                 ///< -1: 0x10 is acknowledged and nothing happens (a unit that does not restart)
  std::array<std::uint8_t, 256> refuse{};  ///< a non-zero entry: the set command of that code answers it
  std::array<bool, 256> ignore{};          ///< true: the set command of that code is acknowledged, not applied
  std::size_t config_bytes = 47;           ///< bytes of the configuration answer (fewer: cut short)
  std::string serial = "STANDIN";          ///< the inventory's serial (bytes as they are, cut to its 18 bytes)
  bool silent_after_session = false;       ///< once a session started: requests read, none answered
  std::uint32_t cut_after_set = 0;  ///< non-zero: the set command of that rank (1: the first) is handled, then
                                    ///< its connection closed unanswered; 0: never
  int cut_down_ms = 0;              ///< after that cut, how long the unit is down (as after 0x10)
};

class PtcServer {
 public:
  PtcServer() = default;
  ~PtcServer();
  PtcServer(const PtcServer&) = delete;
  PtcServer& operator=(const PtcServer&) = delete;

  /// Listens on `address` (IPv4 dotted quad) and `port` (0: any free port). False with a message.
  bool open(const std::string& address, std::uint16_t port, StandInContent content, std::string& error);
  std::uint16_t port() const { return port_; }
  /// PTCS from now on, with a server context (TlsContext::server); null: plain TCP.
  void use_tls(std::shared_ptr<TlsContext> tls) { tls_ = std::move(tls); }

  /// Serves connections until stop() is called (from another thread).
  void run();
  void stop() { stop_ = true; }

  /// While a session runs: copies its key and returns true.
  bool session_key(std::uint8_t key[32]) const;
  /// Sessions started so far.
  std::uint64_t sessions_started() const { return sessions_started_; }
  /// For tests: called on the server's thread when the first 0x2E arrives, before its key is
  /// agreed and its answer sent (replay --unsigned-before-session). Call before run().
  void on_first_session(std::function<void()> f) { on_first_session_ = std::move(f); }
  /// The motor speed the status reports, and the spin rate of the configuration (600 for 0);
  /// call before run().
  void set_motor_speed(std::uint16_t rpm) {
    motor_rpm_ = rpm;
    settings_.rpm = rpm != 0 ? rpm : 600;
  }

 private:
  static constexpr std::size_t kMaxConnections = 8;
  static constexpr int kIdleMs = 10000;
  static constexpr int kSendMs = 2000;
  static constexpr int kConnectionMs = 60000;
  static constexpr std::uint32_t kMaxRequests = 1000;

  struct Connection;
  /// Reads what `c` sent and answers one whole request; false when the connection must close.
  bool on_readable(Connection& c);
  /// Sends what is pending to `c`; false when the connection must close.
  bool on_writable(Connection& c);
  /// Answers the first whole request in `c`'s input, if any; false on a framing error.
  bool answer_pending(Connection& c);
  /// PTCS: the connections one at a time (serve_tls), within the limits above.
  void run_tls();
  void serve_tls(int fd);
  std::vector<std::uint8_t> answer(std::uint8_t command, const std::vector<std::uint8_t>& request, std::uint8_t& code);

  /// The configuration answer, from settings_.
  std::vector<std::uint8_t> config_answer() const;
  /// True while the unit is down after a reboot.
  bool rebooting() const;
  /// True once silent_after_session holds and a session has started: no request is answered.
  bool silent() const { return content_.silent_after_session && sessions_started_ > 0; }

  int fd_ = -1;
  std::uint16_t port_ = 0;
  ptc::Settings settings_;        // what 0x08 reports; set commands change it
  std::uint16_t sync_centi_ = 0;  // the sync angle in 0.01 degree
  std::atomic<std::int64_t> down_until_ns_{0};
  std::uint32_t sets_seen_ = 0;  // set commands answered so far (cut_after_set)
  bool cut_ = false;             // answer(): close this connection, do not send the answer
  std::shared_ptr<TlsContext> tls_;
  std::function<void()> on_first_session_;
  StandInContent content_;
  std::int64_t opened_ns_ = 0;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint16_t> motor_rpm_{0};
  std::atomic<std::uint64_t> sessions_started_{0};
  mutable std::mutex session_mutex_;
  bool session_on_ = false;
  std::array<std::uint8_t, 32> key_{};
};

}  // namespace hesai::port
