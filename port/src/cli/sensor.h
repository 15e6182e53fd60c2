// Talking to a sensor over PTC: the 'hesai sensor' command, and what 'hesai listen --sensor'
// fetches from the unit before it decodes (calibration, firing times, channel configuration, a
// signature session).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "hesai/model.h"
#include "hesai_port/net/ptc_client.h"
#include "options.h"
#include "pipeline.h"

namespace hesai::cli {

/// hesai sensor COMMAND HOST [--ptc-port N] [--timeout SECONDS] [--json] ...
int cmd_sensor(Args& args);

/// listen --sensor: the unit's PTC link.
class SensorLink {
 public:
  SensorLink(const std::string& host, std::uint16_t port, int timeout_ms) : client_(host, port, timeout_ms) {}
  /// The unit at `ipv4` (in_addr.s_addr), resolved from `host` by the caller: the address its
  /// datagrams are filtered by is the one PTC talks to.
  SensorLink(const std::string& host, std::uint32_t ipv4, std::uint16_t port, int timeout_ms)
      : client_(host, ipv4, port, timeout_ms) {}
  ~SensorLink();

  /// Asks the unit its model (inventory), then downloads what the pipeline has no file for: the
  /// calibration (required), the firing times and the QT128 channel configuration (where the unit
  /// serves them). Says on stderr what it fetched and whether it fits the model. Returns an exit
  /// status (kExitInput with a message when the unit cannot be reached or refuses the calibration).
  int fetch(const DecodeOptions& options, Pipeline& pipeline, std::string& error);
  /// Starts a signature session with `secret` and hands its key to the pipeline (QT128C2X only:
  /// other models sign nothing, and get a note). Returns an exit status.
  int start_session(const std::string& secret, Pipeline& pipeline, std::string& error);
  /// Ends the session, if one was started (a failure is a warning: the unit may be gone).
  void stop_session();
  Model model() const { return model_; }

 private:
  port::PtcClient client_;
  Model model_ = Model::unknown;
  bool session_ = false;
};

}  // namespace hesai::cli
