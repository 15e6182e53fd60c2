// Talking to a sensor over PTC: the 'hesai sensor' command, and what 'hesai listen --sensor'
// fetches from the unit before it decodes (calibration, firing times, channel configuration, a
// signature session).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
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
  /// `tls`: PTCS with this context (null: plain TCP).
  SensorLink(const std::string& host, std::uint16_t port, int timeout_ms, std::shared_ptr<port::TlsContext> tls = nullptr)
      : client_(host, port, timeout_ms) {
    client_.use_tls(std::move(tls));
  }
  /// The unit at `ipv4` (in_addr.s_addr), resolved from `host` by the caller: the address its
  /// datagrams are filtered by is the one PTC talks to.
  SensorLink(const std::string& host, std::uint32_t ipv4, std::uint16_t port, int timeout_ms,
             std::shared_ptr<port::TlsContext> tls = nullptr)
      : client_(host, ipv4, port, timeout_ms) {
    client_.use_tls(std::move(tls));
  }

  /// Asks the unit its model (inventory), then downloads what the pipeline has no file for: the
  /// calibration (required), the firing times and the QT128 channel configuration (where the unit
  /// serves them). Says on stderr what it fetched and whether it fits the model. Returns an exit
  /// status (kExitInput with a message when the unit cannot be reached or refuses the calibration).
  int fetch(const DecodeOptions& options, Pipeline& pipeline, std::string& error);
  Model model() const { return model_; }
  /// The connection a signature session (LiveSession) runs over.
  port::PtcClient& client() { return client_; }

 private:
  port::PtcClient client_;
  Model model_ = Model::unknown;
};

/// Starts a signature session with `secret` (0x2E with a fresh client random): the key derived
/// from the secret and both randoms in `key` (QT128C2X manual 4.9.3). Prints why on failure.
/// Exit status.
int session_start(port::PtcClient& client, const std::string& secret, std::uint8_t key[32]);

}  // namespace hesai::cli
