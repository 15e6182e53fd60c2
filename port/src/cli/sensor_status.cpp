// What reads a unit's status (PTC 0x09) around a change: 'hesai sensor reboot' (with --wait, the
// uptime before and after) and the time-source check of 'listen --sensor'.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "hesai/ptc.h"
#include "hesai/ptc_settings.h"
#include "hesai_port/base/clock.h"
#include "sensor.h"

namespace hesai::cli {

using port::PtcClient;
using port::PtcResult;
using Bytes = std::vector<std::uint8_t>;

namespace {

// The unit's uptime from its status (0x09); false, having said why, when it cannot be had.
bool ask_uptime(PtcClient& client, Model model, std::uint32_t& uptime_s, bool quiet) {
  Bytes r;
  const PtcResult result = client.request(ptc::Command::status, {}, r);
  if (!result.ok()) {
    if (!quiet) std::fprintf(stderr, "hesai sensor: %s\n", result.message.c_str());
    return false;
  }
  ptc::Status status;
  if (const Error e = ptc::parse_status(ByteView{r.data(), r.size()}, model, status); e != Error::ok) {
    if (!quiet) payload_error(client, "status", e, r.size());
    return false;
  }
  uptime_s = status.uptime_s;
  return true;
}

}  // namespace

int sensor_reboot(PtcClient& client, double wait_s) {
  // With --wait, the uptime before: a unit that restarted reports less (or drops the connection
  // on its way down).
  Model model = Model::unknown;
  std::uint32_t uptime_before = 0;
  if (wait_s > 0 && (!ask_model(client, model) || !ask_uptime(client, model, uptime_before, false))) {
    std::fprintf(stderr, "hesai sensor: reboot not sent\n");
    return kExitInput;
  }
  Bytes r;
  if (!ask(client, ptc::Command::reboot, {}, r)) return kExitInput;
  client.close();
  if (!(wait_s > 0)) {
    std::fprintf(stderr, "reboot requested\n");
    return kExitOk;
  }
  // The unit goes down some time after its acknowledgement: the first poll waits a second.
  const std::int64_t start = port::monotonic_ns();
  const std::int64_t deadline = start + static_cast<std::int64_t>(wait_s * 1e9);
  std::int64_t next = std::min(start + 1000000000, deadline);  // a wait of a second or less: one poll at its end
  bool dropped = false;      // a poll found the unit down (refused, closed, silent): it went down
  bool answered = false;     // a poll was answered, without a sign of a restart
  std::uint32_t uptime = 0;  // the last answer's
  while (next <= deadline) {
    port::sleep_until_ns(next);
    if (ask_uptime(client, model, uptime, true)) {
      if (dropped || uptime < uptime_before) {
        std::fprintf(stderr, "%s:%u answers again after %.1f s (%s)\n", client.host().c_str(), client.port(),
                     static_cast<double>(port::monotonic_ns() - start) / 1e9,
                     dropped ? "it was down" : "its uptime went down");
        return kExitOk;
      }
      answered = true;  // not down yet, or not restarting: asked again until the wait runs out
    } else {
      dropped = true;
      client.close();
    }
    next = port::monotonic_ns() + 250000000;
  }
  if (answered && !dropped)
    std::fprintf(stderr,
                 "hesai sensor: %s:%u acknowledged the reboot but did not restart within %.1f s: it kept answering and "
                 "its uptime did not go down (%u s, %u s before the reboot)\n",
                 client.host().c_str(), client.port(), wait_s, uptime, uptime_before);
  else
    std::fprintf(stderr, "hesai sensor: %s:%u did not answer within %.1f s of its reboot\n", client.host().c_str(),
                 client.port(), wait_s);
  return kExitInput;
}

int check_time_source(PtcClient& client, Model model, bool require_sync, std::string& ptp_status, std::string& time_source,
                      std::string& error) {
  Bytes r;
  ptc::Status status;
  if (const PtcResult res = client.request(ptc::Command::status, {}, r); !res.ok()) {
    error = res.message;
    return kExitInput;
  }
  if (const Error e = ptc::parse_status(ByteView{r.data(), r.size()}, model, status); e != Error::ok) {
    error = client.host() + ":" + std::to_string(client.port()) + ": the status answer (" + std::to_string(r.size()) +
            " bytes) does not fit its layout: " + error_name(e);
    return kExitInput;
  }
  ptc::Config config;
  if (const PtcResult res = client.request(ptc::Command::config, {}, r); !res.ok()) {
    error = res.message;
    return kExitInput;
  }
  if (const Error e = ptc::parse_config(ByteView{r.data(), r.size()}, config); e != Error::ok) {
    error = client.host() + ":" + std::to_string(client.port()) + ": the configuration answer (" +
            std::to_string(r.size()) + " bytes) does not fit its layout: " + error_name(e);
    return kExitInput;
  }
  const ptc::TimeSource source = ptc::time_source(config.clock_source, status);
  ptp_status = ptc::ptp_status_name(status.ptp_status);
  time_source = ptc::time_source_name(source);
  std::fprintf(stderr, "clock source %s, PTP %s, GPS PPS %s, GPRMC %s: time source %s\n",
               ptc::clock_source_name(config.clock_source), ptp_status.c_str(),
               status.gps_pps_lock == 1 ? "locked" : "not locked", status.gprmc_status == 1 ? "valid" : "not valid",
               time_source.c_str());
  if (require_sync && source == ptc::TimeSource::free_run) {
    error = client.host() + ":" + std::to_string(client.port()) +
            " runs free (its packet times count from a virtual or last synchronised time): --require-sync, nothing "
            "recorded";
    return kExitInput;
  }
  return kExitOk;
}

}  // namespace hesai::cli
