#include "sensor.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include "hesai/calibration.h"
#include "hesai/ct.h"
#include "hesai/hkdf.h"
#include "hesai/ptc.h"
#include "hesai/model.h"
#include "hesai_port/base/files.h"
#include "hesai_port/base/random.h"
#include "hesai_port/base/text.h"
#include "commands.h"

namespace hesai::cli {

using port::PtcClient;
using port::PtcResult;
using Bytes = std::vector<std::uint8_t>;

std::string json_string(const char* s) { return port::json_string(s); }

std::string ipv4_text(const std::uint8_t a[4]) {
  return std::to_string(a[0]) + "." + std::to_string(a[1]) + "." + std::to_string(a[2]) + "." + std::to_string(a[3]);
}

// Runs one request; on failure prints the client's message and returns false.
bool ask(PtcClient& client, ptc::Command command, ByteView payload, Bytes& response) {
  const PtcResult r = client.request(command, payload, response);
  if (r.ok()) return true;
  std::fprintf(stderr, "hesai sensor: %s\n", r.message.c_str());
  return false;
}

// A payload the codec refused: the message names the host, the command and the length.
int payload_error(const PtcClient& client, const char* what, Error e, std::size_t size) {
  std::fprintf(stderr, "hesai sensor: %s:%u: the %s answer (%zu bytes) does not fit its layout: %s\n",
               client.host().c_str(), client.port(), what, size, error_name(e));
  return kExitInput;
}

// Asks the unit its model (Model::unknown when its inventory names none we know). False after
// printing why the request failed.
bool ask_model(PtcClient& client, Model& model) {
  Bytes r;
  if (!ask(client, ptc::Command::inventory, {}, r)) return false;
  ptc::Inventory inv;
  model = ptc::parse_inventory(ByteView{r.data(), r.size()}, inv) == Error::ok ? inv.model : Model::unknown;
  return true;
}

namespace {

constexpr const char* kSensorUsage =
    "usage: hesai sensor COMMAND HOST [--ptc-port N] [--timeout SECONDS] [--json] [--tls --ca FILE ...]\n"
    "\n"
    "Talks to a sensor over PTC (Pandar TCP Commands), on plain TCP or, with --tls, over TLS (PTCS).\n"
    "\n"
    "commands:\n"
    "  info                    serial, manufacture date, MAC, versions, model (0x07)\n"
    "  config                  network, spin rate, return mode... (0x08), coded fields by name\n"
    "  status                  uptime, motor speed, temperatures, GPS and PTP state (0x09)\n"
    "  calibration --out FILE  the unit's angle-correction file, byte for byte (0x05)\n"
    "  firetimes --out FILE    the unit's firing-time file (0xA9)\n"
    "  channel-config --out FILE  the QT128's channel configuration (0xA8)\n"
    "  signature start --session-key-out FILE [--secret-file FILE]\n"
    "                          start a point-cloud signature session (0x2E); the session key (HKDF\n"
    "                          of the shared secret, from --secret-file or HESAI_SECRET, and both\n"
    "                          randoms) goes to FILE, mode 0600, for 'decode --session-key-file'\n"
    "                          (written to a new file and renamed; a link, folder or FIFO at FILE\n"
    "                          is refused)\n"
    "  signature status        whether the unit signs its packets (0x2D)\n"
    "  signature stop          end the session (0x2F)\n"
    "  set KEY=VALUE...        write settings, each read back (0x08): rpm=600|1200 (the model's\n"
    "                          rates), return_mode=last|strongest|last_strongest|first|last_first|\n"
    "                          first_strongest (the model's modes), standby=on|off,\n"
    "                          sync_angle=DEGREES|off, destination=IP:PORT[,GPS_PORT],\n"
    "                          fov=START-END (degrees, 0.1 steps; where the model has one)\n"
    "  apply FILE [--dry-run]  the settings of a JSON file ({\"rpm\": 600, \"return_mode\": \"last\"}):\n"
    "                          prints what differs, writes only that, reads it back; --dry-run\n"
    "                          writes nothing\n"
    "  reboot [--wait SECONDS] restart the unit (0x10); with --wait, until it answers again, restarted\n"
    "\n"
    "  --ptc-port N            PTC port (default 9347)\n"
    "  --timeout SECONDS       the deadline of each request, connecting included (default 3)\n"
    "  --json                  one JSON object (info: serial, manufacture_date, mac, software_version,\n"
    "                          hardware_version, control_firmware, sensor_firmware, model,\n"
    "                          product_model, lines; status: uptime_s, motor_speed_rpm, temperatures_c,\n"
    "                          gps_pps_locked, gprmc_valid, startups, operating_time (minutes),\n"
    "                          ptp_status)\n"
    "\n"
    "Exit status: 0 success, 1 usage (a bad KEY=VALUE, a value the model does not allow, a FILE\n"
    "that is not JSON or holds an unknown key or a value of the wrong type: nothing is written),\n"
    "2 an unreachable sensor, a timeout, a malformed answer, an error code from the sensor, a\n"
    "setting that reads back another value, a unit that does not answer within --wait, a TLS\n"
    "failure (named in the message).\n"
    "\n"
    "PTCS:\n";

// After the TLS options (options.cpp): how the serial is checked.
constexpr const char* kSerialPinHelp =
    "\n"
    "The serial check is exact: the unit's certificate names one serial, its serialNumber, or its\n"
    "CN where it has none, and that whole value must equal the serial (CN \"Hesai QT128 1234\" is\n"
    "not unit 1234). Without --expect-serial the certificate must name the serial the unit itself\n"
    "reports in its inventory: that binds the certificate to what the unit says, not to the unit\n"
    "you meant; any unit with a certificate of the CA passes. --expect-serial SN pins the unit.\n";

std::string mac_text(const std::uint8_t m[6]) {
  char text[18];
  std::snprintf(text, sizeof text, "%02x:%02x:%02x:%02x:%02x:%02x", m[0], m[1], m[2], m[3], m[4], m[5]);
  return text;
}


using port::terminal_text;

// The atomic writer of hesai_port/base/files.h, as an exit status and a message.
int write_file(const std::string& path, const Bytes& bytes, mode_t mode, std::string& error) {
  const port::Status s = port::write_file_atomic(path, bytes.data(), bytes.size(), mode);
  error = s.message();
  return exit_status(s);
}

// Whether a downloaded file parses for `model`; `text` says so ("fits the QT128C2X (128
// channels)") or why not. For an unknown model, whether it parses for some model we know (each
// channel count is tried).
bool file_fits(ptc::Command command, const Bytes& file, Model model, std::string& text) {
  const ByteView view{file.data(), file.size()};
  const auto parse = [&](std::size_t channels) {
    if (command == ptc::Command::calibration) {
      AngleCorrection a;
      return parse_angle_csv(view, channels, a);
    }
    if (command == ptc::Command::firetimes) {
      FiretimeCorrection f;
      return parse_firetime_csv(view, channels, f);
    }
    ChannelConfig c;
    return parse_channel_config_csv(view, c);
  };
  if (model == Model::unknown && command == ptc::Command::channel_config) {  // no channel count to try
    const ParseResult r = parse(0);
    text = r.error == Error::ok ? "model unknown; a valid channel configuration"
                                : std::string("model unknown; not a channel configuration: ") + error_name(r.error) +
                                      " at line " + std::to_string(r.line);
    return r.error == Error::ok;
  }
  if (model == Model::unknown) {
    std::string fitting;
    std::size_t channels = 0;
    for (std::size_t i = 1; i < kModelCount; ++i) {
      const Model m = static_cast<Model>(i);
      if (parse(channel_count(m)).error != Error::ok) continue;
      if (fitting.empty()) channels = channel_count(m);
      if (channel_count(m) == channels) fitting += (fitting.empty() ? "" : ", ") + std::string(model_name(m));
    }
    text = fitting.empty() ? "model unknown; it fits no model we know"
                           : "model unknown; fits the " + fitting + " (" + std::to_string(channels) + " channels)";
    return !fitting.empty();
  }
  const std::size_t channels = channel_count(model);
  const ParseResult r = parse(channels);
  if (r.error == Error::ok) {
    text = std::string("fits the ") + model_name(model) + " (" + std::to_string(channels) + " channels)";
    return true;
  }
  text = std::string("does not fit the ") + model_name(model) + ": " + error_name(r.error) + " at line " + std::to_string(r.line);
  return false;
}

std::string fit_text(ptc::Command command, const Bytes& file, Model model) {
  std::string text;
  (void)file_fits(command, file, model, text);
  return text;
}

int sensor_info(PtcClient& client, bool json) {
  Bytes r;
  if (!ask(client, ptc::Command::inventory, {}, r)) return kExitInput;
  ptc::Inventory inv;
  if (const Error e = ptc::parse_inventory(ByteView{r.data(), r.size()}, inv); e != Error::ok)
    return payload_error(client, "inventory", e, r.size());
  const std::string model = inv.has_model ? model_name(inv.model) : "unknown";
  if (json) {
    std::printf("{\"serial\":%s,\"manufacture_date\":%s,\"mac\":\"%s\",\"software_version\":%s,\"hardware_version\":%s,"
                "\"control_firmware\":%s,\"sensor_firmware\":%s,\"model\":\"%s\",\"product_model\":%d,\"lines\":%d}\n",
                json_string(inv.serial).c_str(), json_string(inv.manufacture_date).c_str(), mac_text(inv.mac).c_str(),
                json_string(inv.software_version).c_str(), json_string(inv.hardware_version).c_str(),
                json_string(inv.control_firmware).c_str(), json_string(inv.sensor_firmware).c_str(), model.c_str(),
                inv.has_model ? inv.product_model : -1, inv.has_model ? inv.lines : -1);
  } else {
    std::printf("serial            %s\nmanufacture date  %s\nMAC               %s\nsoftware          %s\n"
                "hardware          %s\ncontrol firmware  %s\nsensor firmware   %s\nmodel             %s",
                terminal_text(inv.serial).c_str(), terminal_text(inv.manufacture_date).c_str(), mac_text(inv.mac).c_str(),
                terminal_text(inv.software_version).c_str(), terminal_text(inv.hardware_version).c_str(),
                terminal_text(inv.control_firmware).c_str(), terminal_text(inv.sensor_firmware).c_str(), model.c_str());
    if (inv.has_model) std::printf(" (product model %u, %u lines)", inv.product_model, inv.lines);
    std::printf("\n");
  }
  return kExitOk;
}

int sensor_status(PtcClient& client, bool json) {
  // The count of temperatures depends on the model: the inventory says which it is.
  Model model = Model::unknown;
  if (!ask_model(client, model)) return kExitInput;
  Bytes r;
  if (!ask(client, ptc::Command::status, {}, r)) return kExitInput;
  ptc::Status s;
  if (const Error e = ptc::parse_status(ByteView{r.data(), r.size()}, model, s); e != Error::ok)
    return payload_error(client, "status", e, r.size());
  std::string temperatures;
  for (std::size_t i = 0; i < s.temperature_count; ++i) {
    char t[32];
    std::snprintf(t, sizeof t, "%s%.2f", i == 0 ? "" : json ? "," : " ", s.temperature_centi_c[i] / 100.0);
    temperatures += t;
  }
  if (json) {
    std::printf("{\"uptime_s\":%u,\"motor_speed_rpm\":%u,\"temperatures_c\":[%s],\"gps_pps_locked\":%s,"
                "\"gprmc_valid\":%s,\"startups\":%u,\"operating_time\":%u,\"ptp_status\":\"%s\",\"ptp_status_code\":%u,"
                "\"model\":\"%s\"}\n",
                s.uptime_s, s.motor_speed_rpm, temperatures.c_str(), s.gps_pps_lock == 1 ? "true" : "false",
                s.gprmc_status == 1 ? "true" : "false", s.startups, s.operating_time_min, ptc::ptp_status_name(s.ptp_status),
                s.ptp_status, model_name(model));
  } else {
    std::printf("uptime            %u s\nmotor speed       %u rpm\ntemperatures      %s C\nGPS PPS           %s\n"
                "GPRMC             %s\nstart-ups         %u\noperating time    %u min\nPTP               %s\n",
                s.uptime_s, s.motor_speed_rpm, temperatures.c_str(), s.gps_pps_lock == 1 ? "locked" : "not locked",
                s.gprmc_status == 1 ? "valid" : "not valid", s.startups, s.operating_time_min, ptc::ptp_status_name(s.ptp_status));
  }
  return kExitOk;
}

int sensor_file(PtcClient& client, ptc::Command command, const std::string& out_path) {
  Bytes r;
  if (!ask(client, command, {}, r)) return kExitInput;
  // The model, to check that the file parses for it (a failure to learn it is only a note: the
  // file must then parse for some model we know).
  Model model = Model::unknown;
  Bytes inv;
  ptc::Inventory parsed;
  if (client.request(ptc::Command::inventory, {}, inv).ok() &&
      ptc::parse_inventory(ByteView{inv.data(), inv.size()}, parsed) == Error::ok)
    model = parsed.model;
  // Checked before anything is written: a file that does not parse leaves nothing behind (and an
  // earlier file at the path as it was).
  std::string fit;
  if (!file_fits(command, r, model, fit)) {
    std::fprintf(stderr, "hesai sensor: %zu bytes from %s:%u not written to %s: %s\n", r.size(), client.host().c_str(),
                 client.port(), out_path.c_str(), fit.c_str());
    return kExitInput;
  }
  std::string error;
  if (const int st = write_file(out_path, r, 0644, error); st != kExitOk) {
    std::fprintf(stderr, "hesai sensor: %s\n", error.c_str());
    return st;
  }
  std::fprintf(stderr, "%zu bytes to %s; %s\n", r.size(), out_path.c_str(), fit.c_str());
  return kExitOk;
}

int sensor_signature(PtcClient& client, const std::string& action, const std::string& secret_file,
                     const std::string& key_out, bool json) {
  if (action == "start") {
    if (key_out.empty()) {
      std::fprintf(stderr, "hesai sensor: signature start needs --session-key-out FILE\n");
      return kExitUsage;
    }
    std::string secret, error;
    // Before a session starts that no file would hold: the key's path is checked and its
    // temporary file made (and removed at once: an interrupted request leaves none behind).
    {
      port::AtomicFile probe(key_out);  // removed again at the end of this block
      if (const port::Status s = probe.create(); !s.ok()) {
        std::fprintf(stderr, "hesai sensor: %s (no session started)\n", s.message().c_str());
        return kExitInput;
      }
    }
    if (const int st = read_secret(secret_file, secret, error); st != kExitOk) {
      std::fprintf(stderr, "hesai sensor: %s\n", error.c_str());
      return st;
    }
    std::uint8_t key[32] = {};
    const int st = session_start(client, secret, key);
    wipe_secret(secret);
    if (st != kExitOk) {
      secure_wipe(key, sizeof key);  // whatever a failed derivation left
      return st;
    }
    Bytes hex(65);
    for (std::size_t i = 0; i < 32; ++i) std::snprintf(reinterpret_cast<char*>(&hex[2 * i]), 3, "%02x", key[i]);
    hex[64] = '\n';
    secure_wipe(key, sizeof key);
    const int wst = write_file(key_out, hex, 0600, error);
    secure_wipe(hex.data(), hex.size());
    if (wst != kExitOk) {
      // The folder changed since the check: a session whose key nobody holds is stopped.
      Bytes r;
      const bool stopped = client.request(ptc::Command::signature_stop, {}, r).ok();
      std::fprintf(stderr, "hesai sensor: %s; %s\n", error.c_str(),
                   stopped ? "the session is stopped (no file holds its key)"
                           : "the session could not be stopped: run 'hesai sensor signature stop'");
      return wst;
    }
    if (json) std::printf("{\"session\":\"started\",\"session_key_file\":%s}\n", json_string(key_out.c_str()).c_str());
    else std::fprintf(stderr, "signature session started; session key written to %s (mode 0600)\n", key_out.c_str());
    return kExitOk;
  }
  Bytes r;
  const ptc::Command command = action == "status" ? ptc::Command::signature_state : ptc::Command::signature_stop;
  if (!ask(client, command, {}, r)) return kExitInput;
  if (action == "stop") {
    if (json) std::printf("{\"session\":\"stopped\"}\n");
    else std::fprintf(stderr, "signature session stopped\n");
    return kExitOk;
  }
  bool on = false;
  if (const Error e = ptc::parse_signature_state(ByteView{r.data(), r.size()}, on); e != Error::ok)
    return payload_error(client, "signature state", e, r.size());
  if (json) std::printf("{\"signing\":%s}\n", on ? "true" : "false");
  else std::printf("signature %s\n", on ? "on" : "off");
  return kExitOk;
}

}  // namespace

int session_start(PtcClient& client, const std::string& secret, std::uint8_t key[32]) {
  std::uint8_t client_random[ptc::kRandomBytes], lidar_random[ptc::kRandomBytes];
  if (!port::random_bytes(client_random, sizeof client_random)) {
    std::fprintf(stderr, "hesai sensor: cannot read /dev/urandom for the client random\n");
    return kExitInput;
  }
  Bytes r;
  if (!ask(client, ptc::Command::signature_start, ByteView{client_random, sizeof client_random}, r)) return kExitInput;
  if (const Error e = ptc::parse_session_start(ByteView{r.data(), r.size()}, lidar_random); e != Error::ok)
    return payload_error(client, "signature session start", e, r.size());
  const ByteView text{reinterpret_cast<const std::uint8_t*>(secret.data()), secret.size()};
  if (hesai_session_key(text, lidar_random, client_random, key) != Error::ok) return kExitUsage;  // length checked before
  return kExitOk;
}

int cmd_sensor(Args& args) {
  std::string command, action, host, out, secret_file, key_out, v;
  std::vector<std::string> operands;  // set: KEY=VALUE...; apply: FILE
  std::uint64_t port = ptc::kDefaultPort;
  float timeout_s = 3, wait_s = 0;
  bool json = false, dry_run = false;
  const auto usage = [](const std::string& message) {
    std::fprintf(stderr, "hesai sensor: %s\nRun 'hesai sensor --help' for usage.\n", message.c_str());
    return kExitUsage;
  };
  TlsOptions tls;
  std::string error;
  while (!args.empty()) {
    if (parse_tls_option(args, tls, error)) {
      if (!error.empty()) return usage(error);
      continue;
    }
    const std::string a = args.take();
    if (a == "--help" || a == "-h") {
      std::printf("%s%s%s", kSensorUsage, kTlsOptionsHelp, kSerialPinHelp);
      return kExitOk;
    }
    if (a == "--json") json = true;
    else if (a == "--ptc-port") {
      if (!args.value(a, v) || !parse_u64(v, port) || port == 0 || port > 65535) return usage("--ptc-port takes 1 to 65535");
    } else if (a == "--timeout") {
      if (!args.value(a, v) || !parse_float(v, timeout_s) || !(timeout_s > 0) || timeout_s > 3600)
        return usage("--timeout takes seconds above 0 (at most 3600)");
    } else if (a == "--wait") {
      if (!args.value(a, v) || !parse_float(v, wait_s) || !(wait_s > 0) || wait_s > 3600)
        return usage("--wait takes seconds above 0 (at most 3600)");
    } else if (a == "--dry-run") {
      dry_run = true;
    } else if (a == "--out") {
      if (!args.value(a, out)) return usage("--out needs a file");
    } else if (a == "--secret-file") {
      if (!args.value(a, secret_file)) return usage("--secret-file needs a file");
    } else if (a == "--session-key-out") {
      if (!args.value(a, key_out)) return usage("--session-key-out needs a file");
    } else if (a.rfind("--", 0) == 0) {
      return usage("unknown option " + a);
    } else if (command.empty()) {
      command = a;
    } else if (command == "signature" && action.empty()) {
      action = a;
    } else if (host.empty()) {
      host = a;
    } else if (command == "set" || command == "apply") {
      operands.push_back(a);
    } else {
      return usage("unexpected argument '" + a + "'");
    }
  }
  const bool file_command = command == "calibration" || command == "firetimes" || command == "channel-config";
  if (command.empty()) return usage("missing COMMAND");
  const bool settings_command = command == "set" || command == "apply" || command == "reboot";
  if (!file_command && !settings_command && command != "info" && command != "config" && command != "status" &&
      command != "signature")
    return usage("unknown command '" + command + "'");
  if (command == "set" && operands.empty() && !host.empty()) return usage("set needs KEY=VALUE...");
  if (command == "apply" && operands.size() != 1 && !host.empty()) return usage("apply takes one FILE");
  if (dry_run && command != "apply") return usage("--dry-run goes with apply");
  if (wait_s > 0 && command != "reboot") return usage("--wait goes with reboot");
  if (command == "signature" && action != "start" && action != "status" && action != "stop")
    return usage("signature takes start, status or stop");
  if (host.empty()) return usage("missing HOST");
  if (file_command && out.empty()) return usage(command + " needs --out FILE");

  std::shared_ptr<port::TlsContext> tls_context;
  if (const int st = finish_tls_options(tls, tls_context, error); st != kExitOk) {
    if (st == kExitUsage) return usage(error);
    std::fprintf(stderr, "hesai sensor: %s\n", error.c_str());
    return st;
  }
  PtcClient client(host, static_cast<std::uint16_t>(port), static_cast<int>(timeout_s * 1000));
  client.use_tls(tls_context);
  if (command == "info") return sensor_info(client, json);
  if (command == "config") return sensor_config(client, json);
  if (command == "set") return sensor_set(client, operands);
  if (command == "apply") return sensor_apply(client, operands[0], dry_run);
  if (command == "reboot") return sensor_reboot(client, wait_s);
  if (command == "status") return sensor_status(client, json);
  if (command == "signature") return sensor_signature(client, action, secret_file, key_out, json);
  const ptc::Command c = command == "calibration" ? ptc::Command::calibration
                         : command == "firetimes" ? ptc::Command::firetimes
                                                  : ptc::Command::channel_config;
  return sensor_file(client, c, out);
}

// ---- listen --sensor ----

int SensorLink::fetch(const DecodeOptions& options, Pipeline& pipeline, std::string& error, bool require_sync) {
  const std::string origin = client_.host() + ":" + std::to_string(client_.port());
  // Ctrl-C (or SIGTERM) ends the request in flight at once, here and in the session that follows
  // over this client; the requests made after it (the session's stop) still run.
  client_.set_stop(&g_stop);
  if (!ask_model(client_, model_)) {
    error = "cannot fetch the calibration from the sensor (see above)";
    return kExitInput;
  }
  std::fprintf(stderr, "sensor %s: %s\n", origin.c_str(), model_name(model_));
  if (const int st = check_time_source(client_, model_, require_sync, ptp_status_, time_source_, error); st != kExitOk)
    return st;
  Bytes files[3];
  const ptc::Command commands[3] = {ptc::Command::calibration, ptc::Command::firetimes, ptc::Command::channel_config};
  const bool given[3] = {!options.calibration_path.empty(), !options.firetimes_path.empty(),
                         !options.channel_config_path.empty() || model_ != Model::qt128c2x};
  for (std::size_t i = 0; i < 3; ++i) {
    const char* name = ptc::command_name(static_cast<std::uint8_t>(commands[i]));
    if (given[i]) continue;
    const PtcResult r = client_.request(commands[i], {}, files[i]);
    if (r.outcome == port::PtcOutcome::sensor_error && i != 0) {
      std::fprintf(stderr, "%s: not served (%s); the built-in tables apply\n", name, ptc::return_code_name(r.return_code));
      continue;
    }
    if (!r.ok()) {
      error = r.message;
      return kExitInput;
    }
    std::fprintf(stderr, "%s: %zu bytes, %s\n", name, files[i].size(), fit_text(commands[i], files[i], model_).c_str());
  }
  client_.close();  // the session, if any, opens its own connection
  const auto text = [](const Bytes& b) { return std::string(b.begin(), b.end()); };
  const port::Status s = pipeline.use_downloaded(origin, text(files[0]), text(files[1]), text(files[2]));
  error = s.message();
  return exit_status(s);
}

}  // namespace hesai::cli
