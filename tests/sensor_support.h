// What the tests of 'hesai sensor' share (test_sensor.cpp, test_sensor_set.cpp, test_ptcs.cpp): the program
// run with its output captured, and a stand-in sensor ('hesai replay --serve-ptc') in the
// background on the loopback.
#pragma once

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "test_support.h"

namespace hesai_test::sensor {

using hesai_test::cli;
using hesai_test::data_path;
using hesai_test::read_text;

inline std::string temp_path(const std::string& name) { return "/tmp/hesai_sensor_test_" + std::to_string(getpid()) + "_" + name; }

using Ran = CmdResult;

// Runs `hesai ARGS` (run_cli) with the program's own peak resident set measured.
inline Ran run(const std::string& args, const std::string& env = "") { return run_cli(args, env, true); }

// The integer after "key": in a flat JSON object; -1 when absent.
inline long long json_number(const std::string& json, const std::string& key) {
  const std::size_t at = json.find("\"" + key + "\":");
  if (at == std::string::npos) return -1;
  return std::stoll(json.substr(at + key.size() + 3));
}

// A stand-in sensor: 'hesai replay CAPTURE --serve-ptc ADDR:0 ...' in the background; the PTC
// port it chose is read from its stderr.
class StandIn {
 public:
  StandIn(const std::string& capture, const std::string& address, const std::string& options) : address_(address) {
    err_ = temp_path("standin_" + std::to_string(++count_));
    const std::string cmd = "exec env -u HESAI_SECRET " + cli() + " replay " + data_path(capture) + " --serve-ptc " + address +
                            ":0 " + options + " 2>" + err_;
    pid_ = fork();
    if (pid_ == 0) {
      execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    for (int i = 0; i < 200 && port_ == 0; ++i) {
      const std::string text = read_text(err_);
      const std::size_t at = text.find("serving PTC on " + address + ":");
      if (at != std::string::npos && text.find('\n', at) != std::string::npos)
        port_ = std::stoi(text.substr(at + 16 + address.size()));
      else usleep(25000);
    }
  }
  ~StandIn() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      waitpid(pid_, nullptr, 0);
    }
    std::remove(err_.c_str());
  }
  int port() const { return port_; }
  /// The stand-in as a sensor command names it: " ADDRESS --ptc-port PORT".
  std::string at() const { return " " + address_ + " --ptc-port " + std::to_string(port_); }
  std::string stderr_text() const { return read_text(err_); }
  /// Sends SIGINT and waits (at most 10 s) for the program to end: the seconds it took, -1 when it
  /// did not end (it is then killed).
  double interrupt() {
    const auto t0 = std::chrono::steady_clock::now();
    kill(pid_, SIGINT);
    double seconds = -1;
    for (int i = 0; i < 10000; ++i) {
      if (waitpid(pid_, nullptr, WNOHANG) == pid_) {
        seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        pid_ = -1;
        return seconds;
      }
      usleep(1000);
    }
    return seconds;  // the destructor kills it
  }

 private:
  static inline int count_ = 0;
  pid_t pid_ = -1;
  int port_ = 0;
  std::string address_;
  std::string err_;
};

}  // namespace hesai_test::sensor
