// Changing a sensor over PTC (issue #33), end to end on the loopback against the stand-in
// ('hesai replay --serve-ptc'): 'sensor set', 'apply', 'config' by name, 'reboot --wait', and the
// time source of 'listen --sensor'.
//
// Expectations: the values the test asks for, read back through 'sensor config --json' (the
// stand-in keeps what the set commands write, hesai_port/net/ptc_server.h); the allowed values of
// each model as nebula and the manuals give them (hesai/ptc_settings.h); the stand-in's test
// options (--refuse-set, --ignore-set, --config-bytes, --reboot-seconds, --cut-after-set, docs/TESTING.md) make
// the misbehaving unit.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "hesai/ptc_settings.h"
#include "hesai_port/net/ptc_client.h"
#include "sensor_support.h"
#include "udp_support.h"

namespace {

using namespace hesai_test::sensor;

const std::string kQtAngles = data_path("calibration/qt128c2x_unit_a_angles.csv");
const std::string kP64Angles = data_path("calibration/pandar64_unit_a_angles.csv");

// A stand-in that lives for the whole test (the capture played a hundred times, slowly).
std::string standin_options(const std::string& extra = "") {
  return "--to 127.0.0.1:9 --rate 0.05 --loop 100 --quiet " + extra;
}

std::string at(const StandIn& s) { return " 127.0.0.1 --ptc-port " + std::to_string(s.port()) + " --timeout 3"; }

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

// The text of a JSON string value: "key":"value".
std::string json_text(const std::string& json, const std::string& key) {
  const std::size_t start = json.find("\"" + key + "\":\"");
  if (start == std::string::npos) return "<absent>";
  const std::size_t from = start + key.size() + 4;
  return json.substr(from, json.find('"', from) - from);
}

// Each key set on a QT128C2X (which has every key and all six return modes), read back by
// 'sensor config --json' in the configuration's own units.
TEST(SensorSet, EachKeyIsWrittenAndReadBack) {
  StandIn s("qt128c2x_dual.pcap", "127.0.0.1", standin_options());
  ASSERT_NE(s.port(), 0) << s.stderr_text();
  const Ran set = run("sensor set" + at(s) +
                      " rpm=1200 return_mode=first_strongest standby=on sync_angle=90 destination=127.0.0.5:2370,10111 "
                      "fov=30.5-330");
  ASSERT_EQ(set.status, 0) << set.err;
  EXPECT_TRUE(has(set.out, "-> 1200\n")) << set.out;
  EXPECT_TRUE(has(set.out, "return_mode: last -> first_strongest\n")) << set.out;
  EXPECT_TRUE(has(set.out, "standby: off -> on\n")) << set.out;
  EXPECT_TRUE(has(set.out, "sync_angle: off -> 90\n")) << set.out;
  EXPECT_TRUE(has(set.out, "destination: 127.0.0.1:2368,10110 -> 127.0.0.5:2370,10111\n")) << set.out;
  EXPECT_TRUE(has(set.out, "fov: 0.0-0.0 -> 30.5-330.0\n")) << set.out;
  const Ran config = run("sensor config" + at(s) + " --json");
  ASSERT_EQ(config.status, 0) << config.err;
  EXPECT_EQ(json_number(config.out, "spin_rate_rpm"), 1200);
  EXPECT_EQ(json_number(config.out, "return_mode"), 5);  // nebula: 5 first + strongest
  EXPECT_EQ(json_text(config.out, "return_mode_name"), "first_strongest");
  EXPECT_EQ(json_number(config.out, "standby_mode"), 1);
  EXPECT_EQ(json_text(config.out, "standby_mode_name"), "standby");
  EXPECT_EQ(json_number(config.out, "sync"), 1);
  EXPECT_EQ(json_number(config.out, "sync_angle"), 9000);  // 0.01 degree
  EXPECT_EQ(json_text(config.out, "destination_ip"), "127.0.0.5");
  EXPECT_EQ(json_number(config.out, "destination_port"), 2370);
  EXPECT_EQ(json_number(config.out, "gps_port"), 10111);
  EXPECT_EQ(json_number(config.out, "start_angle"), 305);  // 0.1 degree
  EXPECT_EQ(json_number(config.out, "stop_angle"), 3300);
  // In standby the motor stops: the status says so.
  EXPECT_EQ(json_number(run("sensor status" + at(s) + " --json").out, "motor_speed_rpm"), 0);

  // The sync switched off; a destination without a GPS port keeps the unit's.
  const Ran again = run("sensor set" + at(s) + " sync_angle=off destination=127.0.0.6:2371 standby=off");
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_TRUE(has(again.out, "sync_angle: 90 -> off\n")) << again.out;
  const Ran after = run("sensor config" + at(s) + " --json");
  EXPECT_EQ(json_number(after.out, "sync"), 0);
  EXPECT_EQ(json_text(after.out, "destination_ip"), "127.0.0.6");
  EXPECT_EQ(json_number(after.out, "destination_port"), 2371);
  EXPECT_EQ(json_number(after.out, "gps_port"), 10111);
  EXPECT_EQ(json_number(after.out, "standby_mode"), 0);
}

// 'sensor config' names the coded fields; --json keeps every earlier key with its raw code and adds
// one <field>_name key for each coded field.
TEST(SensorConfig, NamesBesideTheCodes) {
  StandIn s("pandar64_dual.pcap", "127.0.0.1", standin_options("--ptp-state locked"));
  ASSERT_NE(s.port(), 0) << s.stderr_text();
  const Ran json = run("sensor config" + at(s) + " --json");
  ASSERT_EQ(json.status, 0) << json.err;
  // Exactly the earlier keys, each coded field followed by its name.
  std::vector<std::string> keys;
  // Each "name": with a name of a-z and '_' (no std::regex: GCC 12 at -O1 with the sanitizers
  // warns inside <regex>, and warnings are errors).
  for (std::size_t q = json.out.find('"'); q != std::string::npos; q = json.out.find('"', q + 1)) {
    const std::size_t end = json.out.find('"', q + 1);
    if (end == std::string::npos) break;
    const std::string name = json.out.substr(q + 1, end - q - 1);
    const bool is_key = end + 1 < json.out.size() && json.out[end + 1] == ':' && !name.empty() &&
                        name.find_first_not_of("abcdefghijklmnopqrstuvwxyz_") == std::string::npos;
    if (is_key) keys.push_back(name);
    q = end;
  }
  EXPECT_EQ(keys, (std::vector<std::string>{
                      "ip", "mask", "gateway", "destination_ip", "destination_port", "gps_port", "spin_rate_rpm", "sync",
                      "sync_angle", "start_angle", "stop_angle", "clock_source", "clock_source_name", "udp_sequence",
                      "udp_sequence_name", "trigger_method", "trigger_method_name", "return_mode", "return_mode_name",
                      "standby_mode", "standby_mode_name", "motor_status", "motor_status_name", "vlan_flag",
                      "vlan_flag_name", "vlan_id", "clock_data_format", "noise_filtering", "reflectivity_mapping",
                      "reflectivity_mapping_name"}));
  // The stand-in: clock source PTP (1) with a PTP state, UDP sequence on, the rest 0.
  EXPECT_EQ(json_number(json.out, "clock_source"), 1);
  EXPECT_EQ(json_text(json.out, "clock_source_name"), "PTP");
  EXPECT_EQ(json_text(json.out, "udp_sequence_name"), "on");
  EXPECT_EQ(json_text(json.out, "trigger_method_name"), "time-based");
  EXPECT_EQ(json_text(json.out, "return_mode_name"), "last");
  EXPECT_EQ(json_text(json.out, "standby_mode_name"), "in operation");
  EXPECT_EQ(json_text(json.out, "motor_status_name"), "clockwise");
  EXPECT_EQ(json_text(json.out, "vlan_flag_name"), "off");
  EXPECT_EQ(json_text(json.out, "reflectivity_mapping_name"), "linear");
  const Ran text = run("sensor config" + at(s));
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_TRUE(has(text.out, "clock_source          PTP\n")) << text.out;
  EXPECT_TRUE(has(text.out, "return_mode           last\n")) << text.out;
  EXPECT_TRUE(has(text.out, "standby_mode          in operation\n")) << text.out;
  EXPECT_TRUE(has(text.out, "reflectivity_mapping  linear\n")) << text.out;
  EXPECT_TRUE(has(text.out, "sync                  off\n")) << text.out;
  EXPECT_TRUE(has(text.out, "motor_status          clockwise\n")) << text.out;
  const Ran status = run("sensor status" + at(s) + " --json");
  EXPECT_TRUE(has(status.out, "\"ptp_status\":\"locked\"")) << status.out;
}

// Values outside the model's set: exit 1 naming the allowed values, nothing written.
TEST(SensorSet, BadValuesNameWhatTheModelAllows) {
  StandIn s("pandar64_dual.pcap", "127.0.0.1", standin_options());
  ASSERT_NE(s.port(), 0) << s.stderr_text();
  const std::string before = run("sensor config" + at(s) + " --json").out;
  struct Case {
    const char* pair;
    const char* says;
  };
  for (const Case& c : {Case{"rpm=900", "allowed: 600, 1200"},  // Pandar64 manual, chapter 4
                        Case{"return_mode=first", "allowed: last, strongest, last_strongest"},  // nebula, Pandar64
                        Case{"standby=maybe", "allowed: on, off"},
                        Case{"sync_angle=360", "0 to 359"},
                        Case{"destination=127.0.0.1", "IP:PORT"},
                        Case{"destination=127.0.0.1:0", "IP:PORT"},
                        Case{"fov=10-20", "takes no FOV"},
                        Case{"colour=red", "KEY one of rpm"},
                        Case{"rpm", "KEY one of rpm"}}) {
    SCOPED_TRACE(c.pair);
    // With a valid value of another key first: that one is not written either.
    const bool rpm = std::string(c.pair).rfind("rpm", 0) == 0;
    const Ran r = run(std::string("sensor set") + at(s) + (rpm ? " standby=on " : " rpm=1200 ") + c.pair);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_TRUE(has(r.err, c.says)) << r.err;
    EXPECT_TRUE(has(r.err, "nothing written")) << r.err;
  }
  EXPECT_EQ(run("sensor config" + at(s) + " --json").out, before);  // rpm=1200 and standby=on never went out
}

// A set command answered with a return code: exit 2 naming the key and the code; for the spin
// rate of a model nebula sets over HTTP, the message says so.
TEST(SensorSet, RefusedSetNamesTheKeyAndTheCode) {
  {
    StandIn s("pandar64_dual.pcap", "127.0.0.1", standin_options("--refuse-set 0x17:5"));
    ASSERT_NE(s.port(), 0) << s.stderr_text();
    const Ran r = run("sensor set" + at(s) + " rpm=1200");
    EXPECT_EQ(r.status, 2);
    EXPECT_TRUE(has(r.err, "refused rpm=1200: return code 5 ('unsupported command')")) << r.err;
    EXPECT_TRUE(has(r.err, "nebula sets the spin rate of the Pandar64 over the unit's HTTP API")) << r.err;
  }
  StandIn s("qt128c2x_dual.pcap", "127.0.0.1", standin_options("--refuse-set 0x17 --refuse-set 0x1E:3"));
  ASSERT_NE(s.port(), 0) << s.stderr_text();
  Ran r = run("sensor set" + at(s) + " rpm=1200");
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(has(r.err, "refused rpm=1200: return code 1 ('invalid input parameter')")) << r.err;
  EXPECT_FALSE(has(r.err, "HTTP")) << r.err;  // the QT128C2X takes its spin rate over PTC
  r = run("sensor set" + at(s) + " return_mode=last_first");
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(has(r.err, "refused return_mode=last_first: return code 3")) << r.err;
}

// Acknowledged but not applied: exit 2 naming the key, the value asked for and the value read.
TEST(SensorSet, AcknowledgedButNotAppliedIsCaughtOnReadBack) {
  StandIn s("qt128c2x_dual.pcap", "127.0.0.1", standin_options("--ignore-set 0x1C --ignore-set 0x18"));
  ASSERT_NE(s.port(), 0) << s.stderr_text();
  Ran r = run("sensor set" + at(s) + " standby=on");
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(has(r.err, "acknowledged standby=on but reads back standby=off")) << r.err;
  r = run("sensor set" + at(s) + " return_mode=first sync_angle=15");
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(has(r.out, "return_mode: last -> first\n")) << r.out;  // written in order until the one that did not take
  EXPECT_TRUE(has(r.err, "acknowledged sync_angle=15 but reads back sync_angle=off")) << r.err;
}

// A unit that applies a set and then closes the connection unanswered (--cut-after-set 2: after
// the second set command): the first key confirmed, the second sent and not confirmed, the third
// not sent, each said on stdout; the configuration read back on a new connection shows the second
// applied (the stand-in applied it: its state is what the test asked). Exit 2.
TEST(SensorSet, CutAfterASetSaysWhatWasConfirmedSentAndNotSent) {
  StandIn s("qt128c2x_dual.pcap", "127.0.0.1", standin_options("--cut-after-set 2"));
  ASSERT_NE(s.port(), 0) << s.stderr_text();
  const long long rpm = json_number(run("sensor config" + at(s) + " --json").out, "spin_rate_rpm");
  ASSERT_NE(rpm, 1200);
  const Ran r = run("sensor set" + at(s) + " rpm=1200 return_mode=first standby=on");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(has(r.err, "closed the connection")) << r.err;  // the cause, as before
  EXPECT_EQ(r.out, "rpm: " + std::to_string(rpm) + " -> 1200\n"
                   "confirmed: rpm=1200\n"
                   "not confirmed: return_mode=first (sent; state unknown)\n"
                   "not sent: standby=on\n"
                   "unit has: rpm=1200 (asked 1200)\n"
                   "unit has: return_mode=first (asked first)\n"
                   "unit has: standby=off (asked on)\n");
  const std::string config = run("sensor config" + at(s) + " --json").out;
  EXPECT_EQ(json_number(config, "spin_rate_rpm"), 1200);
  EXPECT_EQ(json_text(config, "return_mode_name"), "first");
  EXPECT_EQ(json_number(config, "standby_mode"), 0);  // never sent
}

// The same cut, and the unit then down for 5 s (--cut-after-set 2:5): the read-back fails too,
// and each key's value is "unknown".
TEST(SensorSet, CutAfterASetWithTheReadBackFailingSaysUnknown) {
  StandIn s("qt128c2x_dual.pcap", "127.0.0.1", standin_options("--cut-after-set 2:5"));
  ASSERT_NE(s.port(), 0) << s.stderr_text();
  const Ran r = run("sensor set" + at(s) + " standby=on sync_angle=45 return_mode=first");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.out, "standby: off -> on\n"
                   "confirmed: standby=on\n"
                   "not confirmed: sync_angle=45 (sent; state unknown)\n"
                   "not sent: return_mode=first\n"
                   "unit has: standby=unknown (asked on)\n"
                   "unit has: sync_angle=unknown (asked 45)\n"
                   "unit has: return_mode=unknown (asked first)\n");
  EXPECT_TRUE(has(r.err, "cannot read the configuration back")) << r.err;
  EXPECT_LT(r.seconds, 4.0);  // one read-back, not a wait for the unit
}

// apply with the cut after its second write: the same three states, after the differs and changed
// lines.
TEST(SensorApply, CutAfterASetSaysWhatWasConfirmedSentAndNotSent) {
  StandIn s("qt128c2x_dual.pcap", "127.0.0.1", standin_options("--cut-after-set 2"));
  ASSERT_NE(s.port(), 0) << s.stderr_text();
  const std::string file = write_file("cut.json", "{\"sync_angle\": 30, \"return_mode\": \"strongest\", "
                                                  "\"destination\": \"127.0.0.7:2368,10110\"}\n");
  const Ran r = run("sensor apply" + at(s) + " " + file);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(has(r.err, "closed the connection")) << r.err;
  EXPECT_EQ(r.out, "differs: sync_angle off -> 30\n"
                   "differs: return_mode last -> strongest\n"
                   "differs: destination 127.0.0.1:2368,10110 -> 127.0.0.7:2368,10110\n"
                   "changed: sync_angle off -> 30\n"
                   "confirmed: sync_angle=30\n"
                   "not confirmed: return_mode=strongest (sent; state unknown)\n"
                   "not sent: destination=127.0.0.7:2368,10110\n"
                   "unit has: sync_angle=30 (asked 30)\n"
                   "unit has: return_mode=strongest (asked strongest)\n"
                   "unit has: destination=127.0.0.1:2368,10110 (asked 127.0.0.7:2368,10110)\n");
  const std::string config = run("sensor config" + at(s) + " --json").out;
  EXPECT_EQ(json_text(config, "return_mode_name"), "strongest");
  EXPECT_EQ(json_text(config, "destination_ip"), "127.0.0.1");
  std::remove(file.c_str());
}

// A configuration answer cut short (30 of its 38 required bytes): ptc_payload_length, exit 2,
// before anything is written.
TEST(SensorSet, TruncatedConfigurationAnswer) {
  StandIn s("qt128c2x_dual.pcap", "127.0.0.1", standin_options("--config-bytes 30 --refuse-set 0x17"));
  ASSERT_NE(s.port(), 0) << s.stderr_text();
  const std::string file = write_file("truncated.json", "{\"rpm\": 1200}\n");
  for (const std::string& args : {"sensor config" + at(s), "sensor set" + at(s) + " rpm=1200", "sensor apply" + at(s) + " " + file}) {
    SCOPED_TRACE(args);
    const Ran r = run(args);
    EXPECT_EQ(r.status, 2);
    EXPECT_TRUE(has(r.err, "the configuration answer (30 bytes) does not fit its layout: ptc_payload_length")) << r.err;
    EXPECT_FALSE(has(r.err, "refused")) << r.err;  // the set was never sent
  }
  std::remove(file.c_str());
}

// apply: prints what differs, writes only that (the stand-in refuses the standby and destination
// commands: writing either would fail), reads back, says what it changed; --dry-run writes
// nothing; a second apply has nothing to do.
TEST(SensorApply, WritesOnlyWhatDiffersThenHasNothingToDo) {
  StandIn s("qt128c2x_dual.pcap", "127.0.0.1", standin_options("--refuse-set 0x1C --refuse-set 0x20"));
  ASSERT_NE(s.port(), 0) << s.stderr_text();
  const std::string file = write_file("apply.json",
                                      "{\n  \"rpm\": 1200,\n  \"return_mode\": \"strongest\",\n  \"standby\": \"off\",\n"
                                      "  \"sync_angle\": 30,\n  \"destination\": \"127.0.0.1:2368,10110\"\n}\n");
  const std::string before = run("sensor config" + at(s) + " --json").out;
  const long long rpm = json_number(before, "spin_rate_rpm");
  ASSERT_NE(rpm, 1200) << before;
  const std::string differs = "differs: rpm " + std::to_string(rpm) +
                              " -> 1200\ndiffers: return_mode last -> strongest\ndiffers: sync_angle off -> 30\n";

  const Ran dry = run("sensor apply" + at(s) + " " + file + " --dry-run");
  ASSERT_EQ(dry.status, 0) << dry.err;
  EXPECT_EQ(dry.out, differs + "dry run: nothing written\n");
  EXPECT_EQ(run("sensor config" + at(s) + " --json").out, before);

  const Ran apply = run("sensor apply" + at(s) + " " + file);
  ASSERT_EQ(apply.status, 0) << apply.err;
  EXPECT_EQ(apply.out, differs + "changed: rpm " + std::to_string(rpm) +
                           " -> 1200\nchanged: return_mode last -> strongest\nchanged: sync_angle off -> 30\n");
  const std::string after = run("sensor config" + at(s) + " --json").out;
  EXPECT_EQ(json_number(after, "spin_rate_rpm"), 1200);
  EXPECT_EQ(json_number(after, "return_mode"), 1);
  EXPECT_EQ(json_number(after, "sync_angle"), 3000);

  const Ran again = run("sensor apply" + at(s) + " " + file);
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(again.out, "nothing to change: the unit has every setting of " + file + "\n");
  std::remove(file.c_str());
}

// Each key alone, on a QT128C2X stand-in: --dry-run says what differs and changes nothing, apply
// changes it (read back by 'sensor config --json' in the configuration's units), a second apply
// has nothing to do.
TEST(SensorApply, EachKeyDryRunApplyAndAgain) {
  StandIn s("qt128c2x_dual.pcap", "127.0.0.1", standin_options());
  ASSERT_NE(s.port(), 0) << s.stderr_text();
  const long long rpm = json_number(run("sensor config" + at(s) + " --json").out, "spin_rate_rpm");
  ASSERT_NE(rpm, 1200);
  struct Case {
    const char* json;         // the file's one key
    std::string line;         // "KEY BEFORE -> AFTER"
    const char* config_key;   // what the configuration then reports
    long long config_value;
  };
  const Case cases[] = {
      {"\"rpm\": 1200", "rpm " + std::to_string(rpm) + " -> 1200", "spin_rate_rpm", 1200},
      {"\"return_mode\": \"last_first\"", "return_mode last -> last_first", "return_mode", 4},
      {"\"standby\": \"on\"", "standby off -> on", "standby_mode", 1},
      {"\"sync_angle\": 359", "sync_angle off -> 359", "sync_angle", 35900},
      {"\"destination\": \"127.0.0.9:2400,10200\"", "destination 127.0.0.1:2368,10110 -> 127.0.0.9:2400,10200",
       "destination_port", 2400},
      {"\"fov\": \"0.5-359.9\"", "fov 0.0-0.0 -> 0.5-359.9", "stop_angle", 3599},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.json);
    const std::string file = write_file("one_key.json", std::string("{") + c.json + "}\n");
    const std::string before = run("sensor config" + at(s) + " --json").out;
    const Ran dry = run("sensor apply" + at(s) + " " + file + " --dry-run");
    EXPECT_EQ(dry.status, 0) << dry.err;
    EXPECT_EQ(dry.out, "differs: " + c.line + "\ndry run: nothing written\n");
    EXPECT_EQ(run("sensor config" + at(s) + " --json").out, before);
    const Ran apply = run("sensor apply" + at(s) + " " + file);
    EXPECT_EQ(apply.status, 0) << apply.err;
    EXPECT_EQ(apply.out, "differs: " + c.line + "\nchanged: " + c.line + "\n");
    EXPECT_EQ(json_number(run("sensor config" + at(s) + " --json").out, c.config_key), c.config_value);
    const Ran again = run("sensor apply" + at(s) + " " + file);
    EXPECT_EQ(again.status, 0) << again.err;
    EXPECT_EQ(again.out, "nothing to change: the unit has every setting of " + file + "\n");
    std::remove(file.c_str());
  }
}

// A file that is not JSON, an unknown key, a value of the wrong type: exit 1 naming the line or
// the key, before anything is sent (no unit listens on the port: a connection would be exit 2).
TEST(SensorApply, BadFilesNameTheLineOrKeyBeforeAnythingIsSent) {
  const int closed = hesai_test::free_udp_port();  // a free port number; nothing listens on its TCP twin either
  ASSERT_NE(closed, 0);
  struct Case {
    const char* name;
    const char* text;
    const char* says;
  };
  for (const Case& c : {Case{"missing_brace", "{\n  \"rpm\": 600\n", "line 3: not JSON: expected ',' or '}'"},
                        Case{"not_json", "rpm = 600\n", "line 1: not JSON: expected '{'"},
                        Case{"unknown_key", "{\n  \"rpm\": 600,\n  \"colour\": \"red\"\n}\n", "line 3: unknown key 'colour'"},
                        Case{"rpm_string", "{\"rpm\": \"600\"}", "key 'rpm' takes a number, got a string"},
                        Case{"standby_bool", "{\n\"standby\": true}", "key 'standby' takes a string, got a boolean"},
                        Case{"mode_number", "{\"return_mode\": 2}", "key 'return_mode' takes a string, got a number"},
                        Case{"twice", "{\"rpm\": 600,\n \"rpm\": 1200}", "line 2: key 'rpm' given twice"},
                        Case{"trailing", "{\"rpm\": 600} x", "expected the end of the file"},
                        Case{"bad_value", "{\"sync_angle\": \"north\"}", "sync_angle: 'north' is not allowed"}}) {
    SCOPED_TRACE(c.name);
    const std::string file = write_file(c.name, c.text);
    const Ran r = run("sensor apply 127.0.0.1 --ptc-port " + std::to_string(closed) + " --timeout 2 " + file);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_TRUE(has(r.err, c.says)) << r.err;
    std::remove(file.c_str());
  }
  const std::string to = "sensor apply 127.0.0.1 --ptc-port " + std::to_string(closed) + " --timeout 2 ";
  const Ran missing = run(to + temp_path("absent.json"));
  EXPECT_EQ(missing.status, 1);
  EXPECT_TRUE(has(missing.err, "cannot read")) << missing.err;
  const Ran folder = run(to + "/tmp");
  EXPECT_EQ(folder.status, 1);
  EXPECT_TRUE(has(folder.err, "cannot read '/tmp': Is a directory")) << folder.err;
  const std::string empty = write_file("empty.json", "");
  const Ran none = run(to + empty);
  EXPECT_EQ(none.status, 1);
  EXPECT_TRUE(has(none.err, "line 1: not JSON: expected '{', got the end of the file")) << none.err;
  const std::string big = write_file("big.json", "{\"rpm\": 600" + std::string(70000, ' ') + "}");
  const Ran large = run(to + big);
  EXPECT_EQ(large.status, 1);
  EXPECT_TRUE(has(large.err, "larger than 65536 bytes")) << large.err;
  std::remove(empty.c_str());
  std::remove(big.c_str());
}

// reboot --wait: 0x10, then the inventory until the unit answers again. The stand-in is down for
// --reboot-seconds after it acknowledges.
TEST(SensorReboot, WaitsUntilTheUnitAnswersAgain) {
  {
    StandIn s("pandar64_dual.pcap", "127.0.0.1", standin_options("--reboot-seconds 1.5"));
    ASSERT_NE(s.port(), 0) << s.stderr_text();
    const Ran r = run("sensor reboot" + at(s) + " --wait 10");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(has(r.err, "answers again after")) << r.err;
    EXPECT_GE(r.seconds, 1.5);  // not before the unit was back
    EXPECT_LT(r.seconds, 4.0);
  }
  StandIn s("pandar64_dual.pcap", "127.0.0.1", standin_options("--reboot-seconds 5"));
  ASSERT_NE(s.port(), 0) << s.stderr_text();
  // Without --wait: 0x10 only; the unit is then down.
  const Ran now = run("sensor reboot" + at(s));
  EXPECT_EQ(now.status, 0) << now.err;
  EXPECT_TRUE(has(now.err, "reboot requested")) << now.err;
  EXPECT_EQ(run("sensor info" + at(s)).status, 2);
  const Ran r = run("sensor reboot" + at(s) + " --wait 2");
  EXPECT_EQ(r.status, 2);  // the uptime asked before the 0x10 finds the unit down
  EXPECT_TRUE(has(r.err, "reboot not sent")) << r.err;
  usleep(5200000);  // up again
  const Ran late = run("sensor reboot" + at(s) + " --wait 2");
  EXPECT_EQ(late.status, 2);
  EXPECT_TRUE(has(late.err, "did not answer within 2.0 s of its reboot")) << late.err;
  EXPECT_LT(late.seconds, 3.5);  // the wait; a unit that closes connections costs no timeout
  EXPECT_EQ(run("sensor reboot" + at(s) + " --wait 0").status, 1);  // usage
}

// reboot --wait asks for a sign that the unit restarted: it went down (a poll unanswered), or its
// uptime (0x09) went down. A unit that acknowledges 0x10 and goes on as before (--reboot-seconds
// never) is exit 2 at the end of the wait; one back within 0.2 s, before the first poll, is told
// by its uptime (the stand-in's counts anew from the restart).
TEST(SensorReboot, ARestartIsCheckedNotAssumed) {
  {
    StandIn s("pandar64_dual.pcap", "127.0.0.1", standin_options("--reboot-seconds never"));
    ASSERT_NE(s.port(), 0) << s.stderr_text();
    const Ran r = run("sensor reboot" + at(s) + " --wait 2");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_TRUE(has(r.err, "acknowledged the reboot but did not restart within 2.0 s")) << r.err;
    EXPECT_FALSE(has(r.err, "answers again")) << r.err;
    EXPECT_LT(r.seconds, 3.5);
  }
  StandIn s("pandar64_dual.pcap", "127.0.0.1", standin_options("--reboot-seconds 0.2"));
  ASSERT_NE(s.port(), 0) << s.stderr_text();
  usleep(2200000);  // an uptime of 2 s before the reboot
  const Ran r = run("sensor reboot" + at(s) + " --wait 5");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(has(r.err, "s (its uptime went down)")) << r.err;
}

// listen --sensor: the status and clock source first; --require-sync ends a run on a free-running
// unit before anything is recorded; --json gains ptp_status and time_source.
TEST(SensorTime, ListenSaysTheTimeSourceAndRequireSyncRefusesAFreeRunningUnit) {
  for (const bool locked : {false, true}) {
    SCOPED_TRACE(locked ? "locked" : "free run");
    const int port = hesai_test::free_udp_port();
    ASSERT_NE(port, 0);
    StandIn s("pandar64_dual.pcap", "127.0.0.3",
              "--to 127.0.0.1:" + std::to_string(port) + " --rate 0.05 --loop 100 --quiet --calibration " + kP64Angles +
                  (locked ? " --ptp-state locked" : ""));
    ASSERT_NE(s.port(), 0) << s.stderr_text();
    const std::string listen = "listen --bind 127.0.0.1 --port " + std::to_string(port) +
                               " --gps-port 0 --sensor 127.0.0.3 --ptc-port " + std::to_string(s.port()) +
                               " --count 20 --seconds 30 --json --quiet";
    const Ran strict = run(listen + " --require-sync");
    if (locked) {
      EXPECT_EQ(strict.status, 0) << strict.err;
      EXPECT_EQ(json_number(strict.out, "packets"), 20) << strict.out;
      EXPECT_EQ(json_text(strict.out, "ptp_status"), "locked") << strict.out;
      EXPECT_EQ(json_text(strict.out, "time_source"), "ptp") << strict.out;
      EXPECT_TRUE(has(strict.err, "clock source PTP, PTP locked")) << strict.err;
    } else {
      EXPECT_EQ(strict.status, 2);
      EXPECT_EQ(strict.out, "");  // nothing recorded, no summary
      EXPECT_TRUE(has(strict.err, "runs free")) << strict.err;
      EXPECT_FALSE(has(strict.err, "calibration:")) << strict.err;  // ended before the download
      const Ran loose = run(listen);
      EXPECT_EQ(loose.status, 0) << loose.err;
      EXPECT_EQ(json_text(loose.out, "ptp_status"), "free run") << loose.out;
      EXPECT_EQ(json_text(loose.out, "time_source"), "free_run") << loose.out;
    }
  }
  EXPECT_EQ(run("listen --port 0 --require-sync --count 1").status, 1);  // goes with --sensor
}

// The stand-in's options refuse bad values (exit 1) and go with --serve-ptc.
TEST(SensorStandIn, OptionsAreChecked) {
  const std::string replay = "replay " + data_path("pandar64_dual.pcap") + " --to 127.0.0.1:9 --quiet ";
  for (const char* bad : {"--serve-ptc 127.0.0.1:0 --ptp-state synced", "--serve-ptc 127.0.0.1:0 --refuse-set 0x1FF",
                          "--serve-ptc 127.0.0.1:0 --refuse-set 0x17:0", "--serve-ptc 127.0.0.1:0 --ignore-set x",
                          "--serve-ptc 127.0.0.1:0 --config-bytes 48", "--serve-ptc 127.0.0.1:0 --reboot-seconds -1",
                          "--serve-ptc 127.0.0.1:0 --reboot-seconds always",
                          "--serve-ptc 127.0.0.1:0 --cut-after-set 0", "--serve-ptc 127.0.0.1:0 --cut-after-set 2:x",
                          "--cut-after-set 1",
                          "--ptp-state locked", "--refuse-set 0x17"}) {
    SCOPED_TRACE(bad);
    const Ran r = run(replay + bad);
    EXPECT_EQ(r.status, 1) << r.err;
  }
}

// The stand-in's other answers, asked by the client directly: 0x06 with the PTP status query
// (nebula HesaiPtpDiagStatus) in the state --ptp-state gives, another query refused; a set payload
// of the wrong size refused with 'invalid input parameter' and nothing changed; 0x23 the FOV set.
TEST(SensorStandIn, PtpDiagnosticsFovAndMalformedSets) {
  StandIn s("qt128c2x_dual.pcap", "127.0.0.1", standin_options("--ptp-state tracking"));
  ASSERT_NE(s.port(), 0) << s.stderr_text();
  hesai::port::PtcClient client("127.0.0.1", static_cast<std::uint16_t>(s.port()), 3000);
  namespace ptc = hesai::ptc;
  std::vector<std::uint8_t> r;
  const std::uint8_t status_query[1] = {0x01}, port_query[1] = {0x02};
  ASSERT_TRUE(client.request(ptc::Command::ptp_diagnostics, hesai::ByteView{status_query, 1}, r).ok());
  ptc::PtpDiagStatus diag;
  ASSERT_EQ(ptc::parse_ptp_diag_status(hesai::ByteView{r.data(), r.size()}, diag), hesai::Error::ok);
  EXPECT_EQ(diag.ptp_state, 1);  // tracking
  hesai::port::PtcResult res = client.request(ptc::Command::ptp_diagnostics, hesai::ByteView{port_query, 1}, r);
  EXPECT_EQ(res.outcome, hesai::port::PtcOutcome::sensor_error);
  EXPECT_EQ(res.return_code, 1);

  const std::string before = run("sensor config" + at(s) + " --json").out;
  const std::uint8_t three[3] = {0x04, 0xB0, 0x00};  // 0x17 takes two bytes
  res = client.request(ptc::Command::set_spin_rate, hesai::ByteView{three, 3}, r);
  EXPECT_EQ(res.outcome, hesai::port::PtcOutcome::sensor_error);
  EXPECT_EQ(res.return_code, 1);
  EXPECT_EQ(run("sensor config" + at(s) + " --json").out, before);

  ASSERT_EQ(run("sensor set" + at(s) + " fov=45-315.5").status, 0);
  ASSERT_TRUE(client.request(ptc::Command::get_fov, {}, r).ok());
  ptc::Fov fov;
  ASSERT_EQ(ptc::parse_fov(hesai::ByteView{r.data(), r.size()}, fov), hesai::Error::ok);
  EXPECT_EQ(fov.method, 0);
  EXPECT_EQ(fov.start, 450);
  EXPECT_EQ(fov.end, 3155);
  EXPECT_TRUE(has(run("sensor status" + at(s) + " --json").out, "\"ptp_status\":\"tracking\""));
}

}  // namespace
