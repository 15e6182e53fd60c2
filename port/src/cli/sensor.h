// Talking to a sensor over PTC: the 'hesai sensor' command, and what 'hesai listen --sensor'
// fetches from the unit before it decodes (calibration, firing times, channel configuration, a
// signature session).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hesai/model.h"
#include "hesai_port/net/ptc_client.h"
#include "hesai_port/pipeline/pipeline.h"
#include "options.h"

namespace hesai::cli {

/// hesai sensor COMMAND HOST [--ptc-port N] [--timeout SECONDS] [--json] ...
int cmd_sensor(Args& args);

// ---- Shared by sensor.cpp and sensor_settings.cpp ----

/// `s` as a JSON string (quotes, backslash and bytes outside 0x20..0x7E escaped).
std::string json_string(const char* s);
/// "a.b.c.d".
std::string ipv4_text(const std::uint8_t a[4]);
/// Runs one request; on failure prints the client's message ("hesai sensor: ...") and returns false.
bool ask(port::PtcClient& client, ptc::Command command, ByteView payload, std::vector<std::uint8_t>& response);
/// A payload the codec refused: prints the host, the command and the length; kExitInput.
int payload_error(const port::PtcClient& client, const char* what, Error e, std::size_t size);
/// Asks the unit its model (Model::unknown when its inventory names none we know). False after
/// printing why the request failed.
bool ask_model(port::PtcClient& client, Model& model);

// ---- sensor_settings.cpp ----

/// sensor config: the configuration (0x08), coded fields by name (--json: the raw codes and a
/// `<field>_name` key for each coded field).
int sensor_config(port::PtcClient& client, bool json);
/// sensor set HOST KEY=VALUE...: each value checked against the model, written, read back.
int sensor_set(port::PtcClient& client, const std::vector<std::string>& pairs);
/// sensor apply HOST FILE [--dry-run]: the JSON file's settings, only those that differ.
int sensor_apply(port::PtcClient& client, const std::string& file, bool dry_run);
/// sensor reboot HOST [--wait SECONDS]: 0x10; with a wait, the status (0x09) asked before it and then
/// until the unit answers having restarted (a poll unanswered first, or its uptime gone down).
int sensor_reboot(port::PtcClient& client, double wait_s);

/// The unit's time source before a run (listen --sensor): the clock source (0x08) and the status
/// (0x09) of `model`, said on stderr. Exit status: kExitInput when a request fails, or when
/// `require_sync` and the unit runs free.
int check_time_source(port::PtcClient& client, Model model, bool require_sync, std::string& ptp_status,
                      std::string& time_source, std::string& error);

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
  /// First, after the model, the unit's time source (check_time_source: said on stderr; with
  /// `require_sync`, kExitInput for a unit that runs free, before anything is downloaded).
  int fetch(const DecodeOptions& options, Pipeline& pipeline, std::string& error, bool require_sync = false);
  Model model() const { return model_; }
  /// The status's PTP state by name ("free run", "locked", ...), and "ptp", "gps" or "free_run".
  const std::string& ptp_status() const { return ptp_status_; }
  const std::string& time_source() const { return time_source_; }
  /// The connection a signature session (LiveSession) runs over.
  port::PtcClient& client() { return client_; }

 private:
  port::PtcClient client_;
  Model model_ = Model::unknown;
  std::string ptp_status_, time_source_;
};

/// Starts a signature session with `secret` (0x2E with a fresh client random): the key derived
/// from the secret and both randoms in `key` (QT128C2X manual 4.9.3). Prints why on failure.
/// Exit status.
int session_start(port::PtcClient& client, const std::string& secret, std::uint8_t key[32]);

}  // namespace hesai::cli
