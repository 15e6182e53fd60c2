// The settings file of 'hesai sensor apply' and the key file of 'sensor signature start', end to
// end through the program (issue #44, finding 6): a FIFO is refused, not waited on; a NUL inside a
// number is not a digit and does not cut the message; numbers follow JSON's grammar (RFC 8259
// section 6: no leading zeros, no '+', digits after '.' and after the exponent); what the file
// holds reaches the terminal escaped; a key path that cannot be written starts no session.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "sensor_support.h"
#include "udp_support.h"

namespace {

using namespace hesai_test::sensor;

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string write_file(const std::string& name, const std::string& bytes) {
  const std::string path = temp_path(name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// `hesai ARGS`, killed after 10 s (a program that waits on a FIFO would otherwise hang the test).
Ran run_bounded(const std::string& args) { return run(args, "timeout -s KILL 10"); }

// The offset of the first byte a terminal would act on (below 0x20 but the line feed, or DEL), or
// npos. The text is not printed on failure: it would reach the terminal running the tests.
std::size_t first_control_byte(const std::string& text) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const unsigned char b = static_cast<unsigned char>(text[i]);
    if ((b < 0x20 && b != '\n') || b == 0x7F) return i;
  }
  return std::string::npos;
}

// `sensor apply` of a file to a port nobody listens on: a file refused is exit 1, before any
// connection (a connection attempt would be exit 2).
std::string apply_to_nobody() {
  static const int closed = hesai_test::free_udp_port();
  return "sensor apply 127.0.0.1 --ptc-port " + std::to_string(closed) + " --timeout 2 ";
}

TEST(SettingsFile, AFifoIsRefusedNotWaitedOn) {
  const std::string fifo = temp_path("settings.fifo");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  // No writer: opening it to read would wait for one.
  Ran r = run_bounded(apply_to_nobody() + fifo);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_LT(r.seconds, 5.0);
  EXPECT_TRUE(has(r.err, "cannot read '" + fifo + "': it is a FIFO, not a regular file (nothing written)")) << r.err;
  // A writer that never writes: reading would wait for its bytes.
  const int writer = open(fifo.c_str(), O_RDWR | O_NONBLOCK);
  ASSERT_GE(writer, 0);
  r = run_bounded(apply_to_nobody() + fifo);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_LT(r.seconds, 5.0);
  EXPECT_TRUE(has(r.err, "it is a FIFO")) << r.err;
  close(writer);
  std::remove(fifo.c_str());
  // A character device is no settings file either.
  r = run_bounded(apply_to_nobody() + "/dev/zero");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_TRUE(has(r.err, "cannot read '/dev/zero': it is a device, not a regular file")) << r.err;
}

TEST(SettingsFile, ANulInsideANumberIsNotADigit) {
  const std::string file = write_file("nul.json", std::string("{\"rpm\": 12\0" "00}\n", 15));
  const Ran r = run_bounded(apply_to_nobody() + file);
  EXPECT_EQ(r.status, 1) << r.err;
  // The NUL is named, escaped, and the message goes on to its end.
  EXPECT_TRUE(has(r.err, file + ": line 1: not JSON: expected ',' or '}', got '\\x00' (nothing written)\n")) << r.err;
  EXPECT_EQ(r.err.find('\0'), std::string::npos);
  std::remove(file.c_str());
}

TEST(SettingsFile, NumbersFollowJsonsGrammar) {
  struct Case {
    const char* json;
    const char* says;
  };
  // Not JSON (RFC 8259 section 6): exit 1 naming the number.
  for (const Case& c : {Case{"{\"rpm\": 01200}", "line 1: not JSON: a number with a leading zero: '01'"},
                        Case{"{\"sync_angle\": 007}", "line 1: not JSON: a number with a leading zero: '00'"},
                        Case{"{\"sync_angle\": -01}", "line 1: not JSON: a number with a leading zero: '-01'"},
                        Case{"{\"rpm\": 1.}", "line 1: not JSON: expected a digit after '.'"},
                        Case{"{\"rpm\": 6e}", "line 1: not JSON: expected a digit in the exponent"},
                        Case{"{\"rpm\": 6e+}", "line 1: not JSON: expected a digit in the exponent"},
                        Case{"{\"rpm\": -}", "line 1: not JSON: expected a digit after '-'"},
                        Case{"{\"rpm\": +600}", "line 1: not JSON: expected a value, got '+'"},
                        Case{"{\"rpm\": 6-00}", "line 1: not JSON: expected ',' or '}', got '-'"},
                        Case{"{\"rpm\": 600e1e1}", "line 1: not JSON: expected ',' or '}', got 'e'"}}) {
    SCOPED_TRACE(c.json);
    const std::string file = write_file("number.json", c.json);
    const Ran r = run_bounded(apply_to_nobody() + file);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_TRUE(has(r.err, c.says)) << r.err;
    std::remove(file.c_str());
  }
  // JSON, but no whole number of the key's range: refused as a value (exit 1), not as JSON.
  for (const Case& c : {Case{"{\"rpm\": 600.0}", "rpm: '600.0' is not a number of revolutions per minute"},
                        Case{"{\"rpm\": 6e2}", "rpm: '6e2' is not a number of revolutions per minute"},
                        Case{"{\"sync_angle\": -0}", "sync_angle: '-0' is not allowed"},
                        Case{"{\"sync_angle\": 0.5E+1}", "sync_angle: '0.5E+1' is not allowed"}}) {
    SCOPED_TRACE(c.json);
    const std::string file = write_file("number.json", c.json);
    const Ran r = run_bounded(apply_to_nobody() + file);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_TRUE(has(r.err, c.says)) << r.err;
    EXPECT_FALSE(has(r.err, "not JSON")) << r.err;
    std::remove(file.c_str());
  }
}

// Keys and values of the file reach stderr escaped (issue #44, finding 3).
TEST(SettingsFile, WhatTheFileHoldsIsEscapedOnTheTerminal) {
  struct Case {
    std::string json;
    const char* says;
  };
  for (const Case& c : {Case{"{\"\x7f\xff" "colour\": 1}", "unknown key '\\x7f\\xffcolour'"},
                        Case{"{\"return_mode\": \"\x7f\xc2\x9b" "31m\"}", "return_mode: '\\x7f\\xc2\\x9b31m' is not allowed"},
                        Case{"{\"rpm\": \x1b[2J}", "expected a value, got '\\x1b'"},
                        Case{"{\"rpm\": 600}\x07", "expected the end of the file after '}', got '\\x07'"},
                        Case{"{\"standby\": \"on\x1b\"}", "expected the closing '\"' on the same line, got '\\x1b'"}}) {
    SCOPED_TRACE(c.says);
    const std::string file = write_file("escaped.json", c.json);
    const Ran r = run_bounded(apply_to_nobody() + file);
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(first_control_byte(r.err), std::string::npos);
    EXPECT_TRUE(has(r.err, c.says)) << first_control_byte(r.err);
    std::remove(file.c_str());
  }
}

// 'signature start' with a key path that cannot be written started the session, then failed to
// write its key: the unit signed under a key nobody held. The path is now checked first.
TEST(SensorSignature, AKeyPathThatCannotBeWrittenStartsNoSession) {
  const std::string secret = write_file("secret", "sensor-secret-42\n");
  chmod(secret.c_str(), 0600);
  StandIn s("qt128c2x_dual.pcap", "127.0.0.1", "--to 127.0.0.1:9 --rate 0.05 --loop 100 --quiet --secret-file " + secret);
  ASSERT_NE(s.port(), 0) << s.stderr_text();
  const std::string at = " 127.0.0.1 --ptc-port " + std::to_string(s.port()) + " --timeout 3";
  ASSERT_EQ(run("sensor signature status" + at).out, "signature off\n");
  const std::string no_folder = temp_path("no_such_folder") + "/session.key";
  const Ran r = run("sensor signature start" + at + " --secret-file " + secret + " --session-key-out " + no_folder);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(has(r.err, "cannot write '" + no_folder + "'")) << r.err;
  EXPECT_TRUE(has(r.err, "No such file or directory")) << r.err;
  EXPECT_TRUE(has(r.err, "no session started")) << r.err;
  EXPECT_EQ(run("sensor signature status" + at).out, "signature off\n");
  // A path that can be written: the session starts (and is stopped here).
  const std::string key = temp_path("session.key");
  EXPECT_EQ(run("sensor signature start" + at + " --secret-file " + secret + " --session-key-out " + key).status, 0);
  EXPECT_EQ(run("sensor signature status" + at).out, "signature on\n");
  EXPECT_EQ(run("sensor signature stop" + at).status, 0);
  std::remove(key.c_str());
  std::remove(secret.c_str());
}

}  // namespace
