// What the tests of 'hesai sensor' share (test_sensor.cpp, test_sensor_set.cpp): the program
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

struct Ran {
  int status = -1;
  std::string out, err;
  double seconds = 0;
  long max_rss_kib = 0;  // the program's own peak resident set
};

// Runs `hesai ARGS` (shell words) with the key variables of the test's own environment removed.
// Natively through tests/tools/peak_rss.c, so that max_rss_kib is the program's own peak and not
// this test process's resident set at the fork; under an emulator, wait4's figure (which the
// memory bounds do not read there).
inline Ran run(const std::string& args, const std::string& env = "") {
  Ran r;
  const std::string out = temp_path("stdout"), err = temp_path("stderr");
#if defined(HESAI_CLI_EMULATOR)
  const std::string peak;
#else
  const std::string peak_file = temp_path("peak_rss");
  const std::string peak = std::string(HESAI_PEAK_RSS_PATH) + " " + peak_file + " ";
#endif
  const std::string cmd = "exec env -u HESAI_SESSION_KEY -u HESAI_SECRET " + env + " " + peak + cli() + " " + args + " >" +
                          out + " 2>" + err;
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int st = 0;
  rusage u{};
  if (pid < 0 || wait4(pid, &st, 0, &u) != pid) return r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.max_rss_kib = u.ru_maxrss;
#if !defined(HESAI_CLI_EMULATOR)
  r.max_rss_kib = std::atol(read_text(peak_file).c_str());
  std::remove(peak_file.c_str());
#endif
  r.out = read_text(out);
  r.err = read_text(err);
  std::remove(out.c_str());
  std::remove(err.c_str());
  return r;
}

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
  StandIn(const std::string& capture, const std::string& address, const std::string& options) {
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
  std::string err_;
};

}  // namespace hesai_test::sensor
