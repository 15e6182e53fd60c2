#include "live_session.h"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>

#include "hesai/ct.h"
#include "hesai/ptc.h"
#include "hesai_port/base/clock.h"
#include "options.h"
#include "sensor.h"

namespace hesai::cli {

LiveSession::LiveSession(port::PtcClient& client, std::string secret, Pipeline& pipeline, SessionWatchOptions options)
    : client_(client), secret_(std::move(secret)), pipeline_(pipeline), options_(options) {}

LiveSession::~LiveSession() {
  stop();
  if (!secret_.empty()) secure_wipe(&secret_[0], secret_.size());
}

int LiveSession::begin(std::uint8_t key[32]) {
  const int st = session_start(client_, secret_, key);
  client_.close();  // the unit serves one connection at a time: others may need it
  if (st != kExitOk) secure_wipe(key, 32);  // whatever a failed derivation left
  return st;
}

int LiveSession::start(std::string& error) {
  std::uint8_t key[32];
  if (const int st = begin(key); st != kExitOk) {
    error = "no signature session (see above)";
    return st;
  }
  running_ = true;
  pipeline_.start_session(key);
  secure_wipe(key, sizeof key);
  agreed_realtime_ns_ = port::realtime_ns();
  const Stats& s = pipeline_.stats();
  valid_seen_ = s.signature_valid;
  bad_seen_ = s.signature_invalid + s.unsigned_rejected;
  // From here on the worker speaks PTC; stop() ends its request in flight by this flag.
  client_.set_stop(&stop_flag_);
  worker_ = std::thread([this] { work(); });
  return kExitOk;
}

void LiveSession::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  std::int64_t next_poll = port::monotonic_ns() + options_.poll_ns;
  while (!quit_) {
    if (restart_asked_) {
      restart_asked_ = false;
      lock.unlock();
      std::uint8_t key[32];
      const bool started = begin(key) == kExitOk;
      lock.lock();
      if (started) std::memcpy(new_key_, key, sizeof key);
      secure_wipe(key, sizeof key);
      restart_started_ = started;
      restart_done_ = true;
      next_poll = port::monotonic_ns() + options_.poll_ns;
      continue;
    }
    const std::int64_t now = port::monotonic_ns();
    if (now < next_poll) {
      wake_.wait_for(lock, std::chrono::nanoseconds(next_poll - now));
      continue;
    }
    lock.unlock();
    std::vector<std::uint8_t> r;
    bool on = false;
    const port::PtcResult res = client_.request(ptc::Command::signature_state, {}, r);
    client_.close();
    const bool fits = res.ok() && ptc::parse_signature_state(ByteView{r.data(), r.size()}, on) == Error::ok;
    lock.lock();
    // The next poll is counted from the end of this one: a unit that does not answer is asked
    // once per interval and deadline, never back to back.
    next_poll = port::monotonic_ns() + options_.poll_ns;
    if (quit_) break;  // interrupted by stop(): nothing to say
    if (res.outcome == port::PtcOutcome::timeout) ++poll_timeouts_;
    if (restart_asked_) continue;  // asked before a restart: says nothing of the new session
    poll_ = !fits ? Poll::failed : on ? Poll::signing : Poll::not_signing;
    poll_error_ = res.ok() ? "its answer does not fit its layout" : res.message;
  }
}

int LiveSession::watch(std::int64_t now_ns, std::string& error) {
  if (!running_) return kExitOk;
  Poll poll = Poll::none;
  std::string poll_error;
  bool restarted = false, started = false;
  std::uint8_t key[32] = {};
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (restart_done_) {
      restart_done_ = false;
      restarted = true;
      started = restart_started_;
      std::memcpy(key, new_key_, sizeof key);
      secure_wipe(new_key_, sizeof new_key_);
    } else if (!restarting_) {
      poll = poll_;
      poll_ = Poll::none;
      poll_error.swap(poll_error_);
    }
  }
  if (restarted) {
    if (started) pipeline_.start_session(key);  // the pipeline is this thread's: the key is handed over here
    secure_wipe(key, sizeof key);
    return finish_restart(started, error);
  }
  if (restarting_) return kExitOk;  // the worker's 0x2E ends within its deadline

  const Stats& s = pipeline_.stats();
  const std::uint64_t bad = s.signature_invalid + s.unsigned_rejected;
  if (s.signature_valid != valid_seen_) {
    valid_seen_ = s.signature_valid;
    bad_since_ns_ = 0;
    if (!confirmed_) failed_in_a_row_ = 0;
    confirmed_ = true;
  } else if (bad != bad_seen_ && bad_since_ns_ == 0) {
    bad_since_ns_ = now_ns;
  }
  bad_seen_ = bad;

  std::string why;
  if (bad_since_ns_ != 0 && now_ns - bad_since_ns_ > options_.grace_ns) {
    char text[96];
    std::snprintf(text, sizeof text, "no valid signature for %.1f s while packets arrived",
                  static_cast<double>(now_ns - bad_since_ns_) / 1e9);
    why = text;
  } else if (poll == Poll::failed) {
    if (!poll_failing_)
      std::fprintf(stderr, "hesai listen: warning: the signing state could not be read (%s)\n", poll_error.c_str());
    poll_failing_ = true;  // the grace still watches the packets
  } else if (poll != Poll::none) {
    poll_failing_ = false;
    if (poll == Poll::not_signing) why = "the unit says it signs no packets (0x2D)";
  }
  return why.empty() ? kExitOk : restart(why, error);
}

int LiveSession::restart(const std::string& why, std::string& error) {
  // The last restart brought no valid signature (unless it failed to start, counted then).
  if (restarts_ > 0 && !confirmed_ && !counted_) ++failed_in_a_row_;
  if (failed_in_a_row_ >= 2) {
    error = "the signature session failed after " + std::to_string(restarts_) + " restarts in a row: " + why;
    return kExitInput;
  }
  ++restarts_;
  std::fprintf(stderr, "hesai listen: signature session lost (%s); starting a new one (restart %llu)\n", why.c_str(),
               static_cast<unsigned long long>(restarts_));
  confirmed_ = false;
  restarting_ = true;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    restart_asked_ = true;
    poll_ = Poll::none;  // what a poll said of the lost session
  }
  wake_.notify_one();
  return kExitOk;
}

int LiveSession::finish_restart(bool started, std::string& error) {
  restarting_ = false;
  counted_ = !started;
  if (counted_ && ++failed_in_a_row_ >= 2) {
    error = "the signature session failed after " + std::to_string(restarts_) +
            " restarts in a row: it could not be started again (see above)";
    return kExitInput;
  }
  bad_since_ns_ = 0;
  const Stats& s = pipeline_.stats();
  valid_seen_ = s.signature_valid;
  bad_seen_ = s.signature_invalid + s.unsigned_rejected;
  return kExitOk;
}

void LiveSession::stop() {
  if (worker_.joinable()) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      quit_ = true;
    }
    // A request in flight ends within 100 ms. One the worker starts in the instant between its
    // look at quit_ and the client's look at this flag runs to its deadline.
    stop_flag_ = true;
    wake_.notify_all();
    worker_.join();
  }
  secure_wipe(new_key_, sizeof new_key_);  // a restart's key never taken
  if (!running_) return;
  running_ = false;
  // Started with the flag up: this request runs to its own deadline (the clean-up reaches the unit).
  std::vector<std::uint8_t> r;
  const port::PtcResult res = client_.request(ptc::Command::signature_stop, {}, r);
  client_.close();
  if (!res.ok()) std::fprintf(stderr, "hesai listen: warning: the session was not stopped: %s\n", res.message.c_str());
  else std::fprintf(stderr, "signature session stopped\n");
}

}  // namespace hesai::cli
