// Changing a sensor: 'hesai sensor config' by name, 'set' and 'apply' (a JSON file); 'reboot' and
// the time-source check are in sensor_status.cpp. The payloads, the allowed values and the names
// are the core's (hesai/ptc_settings.h); this file parses what the user gives, talks, and prints.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

#include "hesai/ptc.h"
#include "hesai/ptc_settings.h"
#include "hesai_port/base/text.h"
#include "sensor.h"
#include "settings_file.h"

namespace hesai::cli {
namespace {

using port::PtcClient;
using port::PtcResult;
using ptc::Setting;
using ptc::Settings;
using Bytes = std::vector<std::uint8_t>;


bool all_digits(const std::string& s, std::size_t max_digits) {
  if (s.empty() || s.size() > max_digits) return false;
  for (const char c : s)
    if (c < '0' || c > '9') return false;
  return true;
}

// Degrees with at most one decimal, 0 to 360, in tenths.
bool parse_tenths(const std::string& s, std::uint16_t& tenths) {
  const std::size_t dot = s.find('.');
  const std::string whole = s.substr(0, dot);
  const std::string frac = dot == std::string::npos ? "0" : s.substr(dot + 1);
  if (!all_digits(whole, 3) || !all_digits(frac, 1)) return false;
  const unsigned v = static_cast<unsigned>(std::stoul(whole)) * 10 + static_cast<unsigned>(frac[0] - '0');
  if (v > ptc::kMaxFovTenths) return false;
  tenths = static_cast<std::uint16_t>(v);
  return true;
}

bool parse_ipv4(const std::string& s, std::uint8_t out[4]) {
  std::size_t at = 0;
  for (int i = 0; i < 4; ++i) {
    const std::size_t end = i < 3 ? s.find('.', at) : s.size();
    if (end == std::string::npos) return false;
    const std::string part = s.substr(at, end - at);
    if (!all_digits(part, 3) || std::stoul(part) > 255) return false;
    out[i] = static_cast<std::uint8_t>(std::stoul(part));
    at = end + 1;
  }
  return true;
}

bool parse_port(const std::string& s, std::uint16_t& port) {
  if (!all_digits(s, 5) || std::stoul(s) == 0 || std::stoul(s) > 65535) return false;
  port = static_cast<std::uint16_t>(std::stoul(s));
  return true;
}

std::string tenths_text(std::uint16_t v) { return std::to_string(v / 10) + "." + std::to_string(v % 10); }

// A setting's value as the user writes it.
std::string value_text(Setting s, Model model, const Settings& v) {
  switch (s) {
    case Setting::rpm: return std::to_string(v.rpm);
    case Setting::return_mode: {
      const char* name = ptc::return_mode_name(model, v.return_mode);
      return name != nullptr ? name : "code " + std::to_string(v.return_mode);
    }
    case Setting::standby: return v.standby == 0 ? "off" : v.standby == 1 ? "on" : "code " + std::to_string(v.standby);
    case Setting::sync_angle: return v.sync == 0 ? "off" : std::to_string(v.sync_angle);
    case Setting::destination:
      return ipv4_text(v.destination_ip) + ":" + std::to_string(v.destination_port) + "," + std::to_string(v.gps_port);
    case Setting::fov: return tenths_text(v.fov_start) + "-" + tenths_text(v.fov_end);
  }
  return "";
}

// What `model` allows for `s`, for the refusal.
std::string allowed_text(Setting s, Model model) {
  switch (s) {
    case Setting::rpm: {
      std::uint16_t rates[ptc::kMaxSpinRates];
      const std::size_t n = ptc::allowed_spin_rates(model, rates);
      std::string t;
      for (std::size_t i = 0; i < n; ++i) t += (i ? ", " : "") + std::to_string(rates[i]);
      return t;
    }
    case Setting::return_mode: {
      std::string t;
      for (std::uint8_t c = 0; c < ptc::kReturnModeNames; ++c)
        if (const char* name = ptc::return_mode_name(model, c)) t += (t.empty() ? "" : ", ") + std::string(name);
      return t;
    }
    case Setting::standby: return "on, off";
    case Setting::sync_angle: return "0 to 359 (whole degrees), off";
    case Setting::destination: return "IP:PORT or IP:PORT,GPS_PORT (ports 1 to 65535)";
    case Setting::fov: return "START-END, each 0 to 360 degrees in steps of 0.1";
  }
  return "";
}

// Reads `w.text` into `v` for `model` (`current`: the GPS port when none is given). False with
// `error` naming the key, the value and what the model allows. `form_only`: before the model is
// known, only the form (a number of rpm, any FOV).
bool parse_value(const Wanted& w, Model model, const Settings& current, Settings& v, std::string& error,
                 bool form_only = false) {
  const std::string& t = w.text;
  bool ok = false;
  if (form_only && (w.setting == Setting::fov || w.setting == Setting::rpm)) {
    ok = w.setting == Setting::fov || all_digits(t, 5);
    if (!ok) error = "rpm: '" + port::terminal_text(t) + "' is not a number of revolutions per minute";
    return ok;
  }
  switch (w.setting) {
    case Setting::rpm: {
      std::uint16_t rates[ptc::kMaxSpinRates];
      const std::size_t n = ptc::allowed_spin_rates(model, rates);
      for (std::size_t i = 0; i < n && !ok; ++i) ok = all_digits(t, 5) && std::stoul(t) == rates[i];
      if (ok) v.rpm = static_cast<std::uint16_t>(std::stoul(t));
      break;
    }
    case Setting::return_mode: ok = ptc::return_mode_code(model, t.data(), t.size(), v.return_mode); break;
    case Setting::standby:
      ok = t == "on" || t == "off";
      v.standby = t == "on" ? 1 : 0;
      break;
    case Setting::sync_angle:
      if (t == "off") {
        ok = true;
        v.sync = 0;
        v.sync_angle = 0;
      } else if (all_digits(t, 3) && std::stoul(t) <= ptc::kMaxSyncAngle) {
        ok = true;
        v.sync = 1;
        v.sync_angle = static_cast<std::uint16_t>(std::stoul(t));
      }
      break;
    case Setting::destination: {
      const std::size_t colon = t.find(':'), comma = t.find(',');
      v.gps_port = current.gps_port;
      ok = colon != std::string::npos && parse_ipv4(t.substr(0, colon), v.destination_ip) &&
           parse_port(t.substr(colon + 1, comma == std::string::npos ? std::string::npos : comma - colon - 1),
                      v.destination_port) &&
           (comma == std::string::npos || parse_port(t.substr(comma + 1), v.gps_port));
      break;
    }
    case Setting::fov: {
      if (!ptc::fov_supported(model)) {
        error = std::string("fov: the ") + model_name(model) + " takes no FOV over PTC (nebula sets none)";
        return false;
      }
      const std::size_t dash = t.find('-');
      ok = dash != std::string::npos && parse_tenths(t.substr(0, dash), v.fov_start) &&
           parse_tenths(t.substr(dash + 1), v.fov_end);
      break;
    }
  }
  if (!ok)
    error = std::string(ptc::setting_name(w.setting)) + ": '" + port::terminal_text(t) + "' is not allowed" +
            (model != Model::unknown ? std::string(" on the ") + model_name(model) : std::string()) +
            "; allowed: " + allowed_text(w.setting, model);
  return ok;
}

// Reads the configuration into `out`. Exit status (kExitInput after saying why).
int read_settings(PtcClient& client, Settings& out) {
  Bytes r;
  if (!ask(client, ptc::Command::config, {}, r)) return kExitInput;
  ptc::Config c;
  if (const Error e = ptc::parse_config(ByteView{r.data(), r.size()}, c); e != Error::ok)
    return payload_error(client, "configuration", e, r.size());
  ptc::settings_from_config(c, out);
  return kExitOk;
}

// What became of one setting of a change.
enum class Written {
  confirmed,    // acknowledged and read back
  refused,      // answered with a return code: not applied
  not_applied,  // acknowledged, read back with another value
  no_answer,    // sent, not answered (the connection closed, a timeout): state unknown
  not_read,     // acknowledged, the read-back failed: state unknown
  not_sent,     // the connection could not be made: not sent
};

// Writes setting `s` (its value in `value`), then reads the configuration back into `now`. Says why
// on stderr for anything but `confirmed`.
Written write_setting(PtcClient& client, Model model, Setting s, const Settings& value, Settings& now) {
  std::uint8_t payload[ptc::kMaxSetPayloadBytes];
  std::size_t size = 0;
  ptc::encode_setting(s, value, payload, size);
  Bytes r;
  const PtcResult result = client.request(ptc::set_command(s), ByteView{payload, size}, r);
  if (result.outcome == port::PtcOutcome::sensor_error) {
    std::fprintf(stderr, "hesai sensor: %s:%u refused %s=%s: return code %u ('%s')%s\n", client.host().c_str(),
                 client.port(), ptc::setting_name(s), value_text(s, model, value).c_str(), result.return_code,
                 ptc::return_code_name(result.return_code),
                 s == Setting::rpm && ptc::spin_rate_over_http(model)
                     ? (std::string("; nebula sets the spin rate of the ") +
                        (model == Model::unknown ? std::string("models it does not list") : model_name(model)) +
                        " over the unit's HTTP API, not PTC (not done here)")
                           .c_str()
                     : "");
    return Written::refused;
  }
  if (!result.ok()) {
    std::fprintf(stderr, "hesai sensor: %s\n", result.message.c_str());
    return result.outcome == port::PtcOutcome::unreachable ? Written::not_sent : Written::no_answer;
  }
  if (read_settings(client, now) != kExitOk) return Written::not_read;
  if (!ptc::same_setting(s, value, now)) {
    std::fprintf(stderr, "hesai sensor: %s:%u acknowledged %s=%s but reads back %s=%s\n", client.host().c_str(),
                 client.port(), ptc::setting_name(s), value_text(s, model, value).c_str(), ptc::setting_name(s),
                 value_text(s, model, now).c_str());
    return Written::not_applied;
  }
  return Written::confirmed;
}

// Writes `keys` in order, each read back; prints each one confirmed as "KEY: BEFORE -> AFTER"
// (`set`) or "changed: KEY BEFORE -> AFTER" (`apply`). On the first that is not confirmed it stops
// and says, on stdout, what became of every key (confirmed; refused; not applied; not confirmed:
// sent, state unknown; not sent), then reads the configuration once more, on a new connection,
// and prints what the unit has for each key ("unknown" when that read fails too). Exit status:
// kExitOk, or kExitInput after such a stop.
int write_all(PtcClient& client, Model model, const std::vector<Setting>& keys, Settings current,
              const Settings& target, bool apply) {
  std::size_t failed = 0;
  Written outcome = Written::confirmed;
  for (; failed < keys.size(); ++failed) {
    const Setting s = keys[failed];
    Settings now;
    outcome = write_setting(client, model, s, target, now);
    if (outcome != Written::confirmed) break;
    std::printf(apply ? "changed: %s %s -> %s\n" : "%s: %s -> %s\n", ptc::setting_name(s),
                value_text(s, model, current).c_str(), value_text(s, model, now).c_str());
    current = now;
  }
  if (failed == keys.size()) return kExitOk;
  const auto asked = [&](Setting s) { return std::string(ptc::setting_name(s)) + "=" + value_text(s, model, target); };
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::string key = asked(keys[i]);
    const Written w = i < failed ? Written::confirmed : i > failed ? Written::not_sent : outcome;
    switch (w) {
      case Written::confirmed: std::printf("confirmed: %s\n", key.c_str()); break;
      case Written::refused: std::printf("refused: %s\n", key.c_str()); break;
      case Written::not_applied: std::printf("not applied: %s (acknowledged; reads back otherwise)\n", key.c_str()); break;
      case Written::no_answer: std::printf("not confirmed: %s (sent; state unknown)\n", key.c_str()); break;
      case Written::not_read: std::printf("not confirmed: %s (acknowledged, not read back; state unknown)\n", key.c_str()); break;
      case Written::not_sent: std::printf("not sent: %s\n", key.c_str()); break;
    }
  }
  // What the unit has now, on a connection of its own (the last one may be dead or out of step).
  client.close();
  Settings now;
  const bool known = read_settings(client, now) == kExitOk;
  if (!known)
    std::fprintf(stderr, "hesai sensor: %s:%u: cannot read the configuration back: what the unit has is unknown\n",
                 client.host().c_str(), client.port());
  for (const Setting s : keys)
    std::printf("unit has: %s=%s (asked %s)\n", ptc::setting_name(s), known ? value_text(s, model, now).c_str() : "unknown",
                value_text(s, model, target).c_str());
  return kExitInput;
}

// The unit's model and settings, and every wanted value checked against the model (kExitUsage
// naming the allowed values) before anything is written.
int prepare(PtcClient& client, const std::vector<Wanted>& wanted, Model& model, Settings& current, Settings& target) {
  if (!ask_model(client, model)) return kExitInput;
  if (const int st = read_settings(client, current); st != kExitOk) return st;
  target = current;
  for (const Wanted& w : wanted) {
    std::string error;
    if (!parse_value(w, model, current, target, error)) {
      std::fprintf(stderr, "hesai sensor: %s (nothing written)\n", error.c_str());
      return kExitUsage;
    }
  }
  return kExitOk;
}

}  // namespace

int sensor_config(PtcClient& client, bool json) {
  Model model = Model::unknown;
  if (!ask_model(client, model)) return kExitInput;
  Bytes r;
  if (!ask(client, ptc::Command::config, {}, r)) return kExitInput;
  ptc::Config c;
  if (const Error e = ptc::parse_config(ByteView{r.data(), r.size()}, c); e != Error::ok)
    return payload_error(client, "configuration", e, r.size());
  const char* return_mode = ptc::return_mode_name(model, c.return_mode);
  struct Field {
    const char* key;
    std::string value;        // JSON: the raw value
    const char* name;         // a coded field's name; null for the others
    bool present = true;      // the three model bytes: false when absent
  };
  const Field fields[] = {
      {"ip", "\"" + ipv4_text(c.ip) + "\"", nullptr},
      {"mask", "\"" + ipv4_text(c.mask) + "\"", nullptr},
      {"gateway", "\"" + ipv4_text(c.gateway) + "\"", nullptr},
      {"destination_ip", "\"" + ipv4_text(c.destination_ip) + "\"", nullptr},
      {"destination_port", std::to_string(c.destination_port), nullptr},
      {"gps_port", std::to_string(c.gps_port), nullptr},
      {"spin_rate_rpm", std::to_string(c.spin_rate_rpm), nullptr},
      {"sync", std::to_string(c.sync), nullptr},
      {"sync_angle", std::to_string(c.sync_angle), nullptr},
      {"start_angle", std::to_string(c.start_angle), nullptr},
      {"stop_angle", std::to_string(c.stop_angle), nullptr},
      {"clock_source", std::to_string(c.clock_source), ptc::clock_source_name(c.clock_source)},
      {"udp_sequence", std::to_string(c.udp_sequence), ptc::on_off_name(c.udp_sequence)},
      {"trigger_method", std::to_string(c.trigger_method), ptc::trigger_method_name(c.trigger_method)},
      {"return_mode", std::to_string(c.return_mode), return_mode != nullptr ? return_mode : "unknown"},
      {"standby_mode", std::to_string(c.standby_mode), ptc::standby_name(c.standby_mode)},
      {"motor_status", std::to_string(c.motor_status), ptc::motor_direction_name(c.motor_status)},
      {"vlan_flag", std::to_string(c.vlan_flag), ptc::on_off_name(c.vlan_flag)},
      {"vlan_id", std::to_string(c.vlan_id), nullptr},
      {"clock_data_format", c.has_extra ? std::to_string(c.clock_data_format) : "null", nullptr, c.has_extra},
      {"noise_filtering", c.has_extra ? std::to_string(c.noise_filtering) : "null", nullptr, c.has_extra},
      {"reflectivity_mapping", c.has_extra ? std::to_string(c.reflectivity_mapping) : "null",
       ptc::reflectivity_mapping_name(c.reflectivity_mapping), c.has_extra},
  };
  std::string out = json ? "{" : "";
  for (const Field& f : fields) {
    const std::string key = f.key;
    if (json) {
      out += (out.size() > 1 ? ",\"" : "\"") + key + "\":" + f.value;
      if (f.name != nullptr) out += ",\"" + key + "_name\":" + (f.present ? json_string(f.name) : "null");
      continue;
    }
    // Text: the name in place of the code, the angles in degrees.
    std::string value = f.name != nullptr ? (f.present ? std::string(f.name) : "absent") : f.value;
    if (key == "sync") value = ptc::on_off_name(c.sync);
    if (value.size() >= 2 && value.front() == '"') value = value.substr(1, value.size() - 2);
    if (key == "sync_angle") value = std::to_string(c.sync_angle / 100) + "." + (c.sync_angle % 100 < 10 ? "0" : "") +
                                     std::to_string(c.sync_angle % 100) + " deg";
    if (key == "start_angle" || key == "stop_angle")
      value = tenths_text(key == "start_angle" ? c.start_angle : c.stop_angle) + " deg";
    out += key + std::string(22 - key.size(), ' ') + value + "\n";
  }
  std::printf("%s%s", out.c_str(), json ? "}\n" : "");
  return kExitOk;
}

int sensor_set(PtcClient& client, const std::vector<std::string>& pairs) {
  std::vector<Wanted> wanted;
  for (const std::string& p : pairs) {
    const std::size_t eq = p.find('=');
    Setting s;
    if (eq == std::string::npos || !ptc::setting_from_name(p.data(), eq, s)) {
      std::fprintf(stderr, "hesai sensor: set takes KEY=VALUE with KEY one of rpm, return_mode, standby, sync_angle, "
                           "destination, fov; got '%s' (nothing written)\n", port::terminal_text(p).c_str());
      return kExitUsage;
    }
    for (const Wanted& w : wanted)
      if (w.setting == s) {
        std::fprintf(stderr, "hesai sensor: %s given twice (nothing written)\n", ptc::setting_name(s));
        return kExitUsage;
      }
    wanted.push_back({s, p.substr(eq + 1)});
  }
  // The form of every value first, before the unit is asked anything.
  Settings scratch;
  for (const Wanted& w : wanted) {
    std::string error;
    if (!parse_value(w, Model::unknown, scratch, scratch, error, true)) {
      std::fprintf(stderr, "hesai sensor: %s (nothing written)\n", error.c_str());
      return kExitUsage;
    }
  }
  Model model = Model::unknown;
  Settings current, target;
  if (const int st = prepare(client, wanted, model, current, target); st != kExitOk) return st;
  std::vector<Setting> keys;
  for (const Wanted& w : wanted) keys.push_back(w.setting);
  return write_all(client, model, keys, current, target, false);
}

int sensor_apply(PtcClient& client, const std::string& file, bool dry_run) {
  std::string bytes, error;
  if (!read_settings_file(file, bytes, error)) {
    std::fprintf(stderr, "hesai sensor: %s (nothing written)\n", error.c_str());
    return kExitUsage;
  }
  std::vector<Wanted> wanted;
  if (!read_settings_json(bytes, wanted, error)) {
    std::fprintf(stderr, "hesai sensor: %s: %s (nothing written)\n", file.c_str(), error.c_str());
    return kExitUsage;
  }
  Settings scratch;
  for (const Wanted& w : wanted) {
    if (!parse_value(w, Model::unknown, scratch, scratch, error, true)) {
      std::fprintf(stderr, "hesai sensor: %s: %s (nothing written)\n", file.c_str(), error.c_str());
      return kExitUsage;
    }
  }
  Model model = Model::unknown;
  Settings current, target;
  if (const int st = prepare(client, wanted, model, current, target); st != kExitOk) return st;
  std::vector<Setting> differ;
  for (const Wanted& w : wanted)
    if (!ptc::same_setting(w.setting, current, target)) {
      differ.push_back(w.setting);
      std::printf("differs: %s %s -> %s\n", ptc::setting_name(w.setting), value_text(w.setting, model, current).c_str(),
                  value_text(w.setting, model, target).c_str());
    }
  if (differ.empty()) {
    std::printf("nothing to change: the unit has every setting of %s\n", file.c_str());
    return kExitOk;
  }
  if (dry_run) {
    std::printf("dry run: nothing written\n");
    return kExitOk;
  }
  return write_all(client, model, differ, current, target, true);
}

}  // namespace hesai::cli
