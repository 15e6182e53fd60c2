// The live signature session of 'hesai listen --sensor' with a secret: started, watched, restarted
// when lost, and stopped (QT128C2X manual 4.9.3: the key from the shared secret and both randoms;
// "in case of a reboot, start a session again").
//
// PTC 1.0 is plaintext and unauthenticated: anyone on the LAN can stop the session (0x2F) or start
// another under a key we do not know (0x2E). So the session is strict, and watched:
// - a packet may be accepted unsigned only if the kernel received it before the session's key
//   was agreed (cmd_listen feeds those with pre_session); every later one must carry a valid
//   signature, or it is rejected (unsigned_rejected, signature_invalid);
// - the unit's signing state is polled (0x2D) every poll interval;
// - packets that arrive with no valid signature for longer than the grace mean the session is
//   lost (stopped, replaced, or the unit rebooted);
// - a lost session is started again, with new randoms and so a new key (session_restarts); when
//   two restarts in a row fail (the session cannot be started, or still no valid signature comes
//   within the grace), watch() says why and the run ends with exit status 2.
#pragma once

#include <cstdint>
#include <string>

#include "hesai_port/net/ptc_client.h"
#include "hesai_port/pipeline/pipeline.h"
#include "options.h"

namespace hesai::cli {

struct SessionWatchOptions {
  std::int64_t poll_ns = 1000000000;   ///< --session-poll: 0x2D every this long
  std::int64_t grace_ns = 1000000000;  ///< --signature-grace: packets with no valid signature this long
};

class LiveSession {
 public:
  /// `secret` is kept (for restarts) until the session is destroyed, then wiped.
  LiveSession(port::PtcClient& client, std::string secret, Pipeline& pipeline, SessionWatchOptions options);
  /// Stops the session (0x2F) if it runs, and wipes the secret.
  ~LiveSession();
  LiveSession(const LiveSession&) = delete;
  LiveSession& operator=(const LiveSession&) = delete;

  /// Starts the first session and hands its key to the pipeline. Exit status, with a message.
  int start(std::string& error);
  /// CLOCK_REALTIME just after the first session's answer was read: a datagram the kernel received
  /// (SO_TIMESTAMPNS) at or before this time was sent before the session.
  std::int64_t agreed_realtime_ns() const { return agreed_realtime_ns_; }
  /// Called as packets are processed (monotonic `now_ns`): polls the signing state when due, and
  /// restarts a lost session. kExitOk, or kExitInput with the cause when two restarts in a row
  /// failed.
  int watch(std::int64_t now_ns, std::string& error);
  /// Ends the session on the unit (0x2F), if one runs; a failure is a warning.
  void stop();
  std::uint64_t restarts() const { return restarts_; }

 private:
  // 0x2E with new randoms; the key to the pipeline. Exit status.
  int begin();
  int restart(const std::string& why, std::int64_t now_ns, std::string& error);

  port::PtcClient& client_;
  std::string secret_;
  Pipeline& pipeline_;
  SessionWatchOptions options_;
  bool running_ = false;         // a session was started and not stopped by us
  std::int64_t agreed_realtime_ns_ = 0;
  std::int64_t next_poll_ns_ = 0;
  std::uint64_t valid_seen_ = 0;  // signature_valid when last watched
  std::uint64_t bad_seen_ = 0;    // signature_invalid + unsigned_rejected when last watched
  std::int64_t bad_since_ns_ = 0; // first packet without a valid signature since the last valid one; 0: none
  bool confirmed_ = false;        // a valid signature arrived since the last (re)start
  std::uint64_t restarts_ = 0;
  int failed_in_a_row_ = 0;       // restarts that brought no valid signature, or could not start
  bool counted_ = false;          // the last restart could not start (already in failed_in_a_row_)
  bool poll_failing_ = false;     // the last 0x2D went unanswered (warned once)
};

}  // namespace hesai::cli
