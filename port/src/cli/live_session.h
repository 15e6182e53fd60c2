// The live signature session of 'hesai listen --sensor' with a secret: started, watched, restarted
// when lost, and stopped (QT128C2X manual 4.9.3: the key from the shared secret and both randoms;
// "in case of a reboot, start a session again").
//
// PTC 1.0 is plaintext and unauthenticated: anyone on the LAN can stop the session (0x2F) or start
// another under a key we do not know (0x2E). So the session is strict, and watched:
// - a packet may be accepted unsigned only if the kernel received it before the session's key
//   was agreed (cmd_listen feeds those with pre_session); every later one must carry a valid
//   signature, or it is rejected (unsigned_rejected, signature_invalid);
// - the unit's signing state is polled (0x2D) every poll interval, counted from the end of the
//   previous poll; a poll that gets no whole answer within the PTC deadline counts
//   (poll_timeouts) and, as any poll that fails, leaves the watching to the grace;
// - packets that arrive with no valid signature for longer than the grace mean the session is
//   lost (stopped, replaced, or the unit rebooted);
// - a lost session is started again, with new randoms and so a new key (session_restarts); when
//   two restarts in a row fail (the session cannot be started, or still no valid signature comes
//   within the grace), watch() says why and the run ends with exit status 2.
//
// Reception never waits on PTC. start() is blocking (it runs before reception begins); after it,
// the watched session's PTC exchanges (the polls and the restarts' 0x2E) run on a worker thread of
// the session, one at a time over the client, each within the client's deadline. watch(), called
// on the receive loop, never blocks on PTC: it reads the worker's latest results under a mutex,
// asks it for a restart, and hands a restart's new key to the pipeline itself (the Pipeline is
// the receive loop's alone). The key passes through one buffer of the session, wiped once taken
// (and at stop()). While a restart is under way, packets are still taken, under the old key, and
// neither the grace nor the polls are judged. stop() ends the worker (a request in flight ends
// within 100 ms: the client's stop flag is the session's from start() on), joins it, and then
// sends 0x2F, which runs to its own deadline.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

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
  /// Stops the session (stop()), and wipes the secret.
  ~LiveSession();
  LiveSession(const LiveSession&) = delete;
  LiveSession& operator=(const LiveSession&) = delete;

  /// Starts the first session (blocking) and hands its key to the pipeline; then starts the
  /// worker that polls. Exit status, with a message.
  int start(std::string& error);
  /// CLOCK_REALTIME just after the first session's answer was read: a datagram the kernel received
  /// (SO_TIMESTAMPNS) at or before this time was sent before the session.
  std::int64_t agreed_realtime_ns() const { return agreed_realtime_ns_; }
  /// Called as packets are processed (monotonic `now_ns`), on the thread that owns the pipeline;
  /// never waits on PTC. Takes the worker's latest poll and restart results, watches the grace,
  /// and asks for a restart of a lost session. kExitOk, or kExitInput with the cause when two
  /// restarts in a row failed.
  int watch(std::int64_t now_ns, std::string& error);
  /// Ends the worker (interrupting its request in flight) and then the session on the unit
  /// (0x2F), if one runs; a failure is a warning.
  void stop();
  std::uint64_t restarts() const { return restarts_; }
  /// Polls (0x2D) that got no whole answer within the PTC deadline.
  std::uint64_t poll_timeouts() const { return poll_timeouts_.load(); }

 private:
  // What the worker last learnt from a poll.
  enum class Poll { none, signing, not_signing, failed };

  // 0x2E with new randoms (on the calling thread). Exit status; the key in `key` on success.
  int begin(std::uint8_t key[32]);
  // Asks the worker for a new session (counted in failed_in_a_row_ as restart() always was).
  int restart(const std::string& why, std::string& error);
  // Takes the worker's restart result: kExitOk, or kExitInput when two failed in a row.
  int finish_restart(bool started, std::string& error);
  void work();  // the worker: polls when due, restarts when asked

  port::PtcClient& client_;
  std::string secret_;
  Pipeline& pipeline_;
  SessionWatchOptions options_;
  bool running_ = false;         // a session was started and not stopped by us
  std::int64_t agreed_realtime_ns_ = 0;
  std::uint64_t valid_seen_ = 0;  // signature_valid when last watched
  std::uint64_t bad_seen_ = 0;    // signature_invalid + unsigned_rejected when last watched
  std::int64_t bad_since_ns_ = 0; // first packet without a valid signature since the last valid one; 0: none
  bool confirmed_ = false;        // a valid signature arrived since the last (re)start
  std::uint64_t restarts_ = 0;
  int failed_in_a_row_ = 0;       // restarts that brought no valid signature, or could not start
  bool counted_ = false;          // the last restart could not start (already in failed_in_a_row_)
  bool poll_failing_ = false;     // the last 0x2D went unanswered (warned once)
  bool restarting_ = false;       // a restart was asked of the worker and its result not taken

  // Shared with the worker, under mutex_ (poll_timeouts_ and stop_flag_ are atomics of their own).
  std::thread worker_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool quit_ = false;              // stop(): the worker ends
  bool restart_asked_ = false;     // watch() → worker: start a new session
  bool restart_done_ = false;      // worker → watch(): the restart ended (restart_started_ says how)
  bool restart_started_ = false;
  std::uint8_t new_key_[32] = {};  // the restarted session's key until watch() takes it (then wiped)
  Poll poll_ = Poll::none;         // worker → watch(): the latest poll, taken (none) by watch()
  std::string poll_error_;         // why it failed
  std::atomic<std::uint64_t> poll_timeouts_{0};
  std::atomic<bool> stop_flag_{false};  // the client's stop flag from start() on: up in stop()
};

}  // namespace hesai::cli
