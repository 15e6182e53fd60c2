#include "live_session.h"

#include <cstdio>
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

int LiveSession::begin() {
  std::uint8_t key[32];
  const int st = session_start(client_, secret_, key);
  client_.close();  // the unit serves one connection at a time: others may need it
  if (st != kExitOk) return st;
  running_ = true;
  pipeline_.start_session(key);
  secure_wipe(key, sizeof key);
  return kExitOk;
}

int LiveSession::start(std::string& error) {
  if (const int st = begin(); st != kExitOk) {
    error = "no signature session (see above)";
    return st;
  }
  agreed_realtime_ns_ = port::realtime_ns();
  const std::int64_t now = port::monotonic_ns();
  next_poll_ns_ = now + options_.poll_ns;
  const Stats& s = pipeline_.stats();
  valid_seen_ = s.signature_valid;
  bad_seen_ = s.signature_invalid + s.unsigned_rejected;
  return kExitOk;
}

int LiveSession::watch(std::int64_t now_ns, std::string& error) {
  if (!running_) return kExitOk;
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
  } else if (now_ns >= next_poll_ns_) {
    next_poll_ns_ = now_ns + options_.poll_ns;
    std::vector<std::uint8_t> r;
    const port::PtcResult res = client_.request(ptc::Command::signature_state, {}, r);
    client_.close();
    bool on = false;
    if (!res.ok() || ptc::parse_signature_state(ByteView{r.data(), r.size()}, on) != Error::ok) {
      if (!poll_failing_)
        std::fprintf(stderr, "hesai listen: warning: the signing state could not be read (%s)\n",
                     res.ok() ? "its answer does not fit its layout" : res.message.c_str());
      poll_failing_ = true;  // the grace still watches the packets
    } else {
      poll_failing_ = false;
      if (!on) why = "the unit says it signs no packets (0x2D)";
    }
  }
  return why.empty() ? kExitOk : restart(why, now_ns, error);
}

int LiveSession::restart(const std::string& why, std::int64_t now_ns, std::string& error) {
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
  counted_ = begin() != kExitOk;
  if (counted_ && ++failed_in_a_row_ >= 2) {
    error = "the signature session failed after " + std::to_string(restarts_) +
            " restarts in a row: it could not be started again (see above)";
    return kExitInput;
  }
  bad_since_ns_ = 0;
  const Stats& s = pipeline_.stats();
  valid_seen_ = s.signature_valid;
  bad_seen_ = s.signature_invalid + s.unsigned_rejected;
  next_poll_ns_ = now_ns + options_.poll_ns;
  return kExitOk;
}

void LiveSession::stop() {
  if (!running_) return;
  running_ = false;
  std::vector<std::uint8_t> r;
  const port::PtcResult res = client_.request(ptc::Command::signature_stop, {}, r);
  client_.close();
  if (!res.ok()) std::fprintf(stderr, "hesai listen: warning: the session was not stopped: %s\n", res.message.c_str());
  else std::fprintf(stderr, "signature session stopped\n");
}

}  // namespace hesai::cli
