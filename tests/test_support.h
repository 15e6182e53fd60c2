// Test-only helpers: read the bundled captures and calibration files without the port's code,
// so that golden tests do not depend on the code they check.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "hesai/bytes.h"
#include "hesai/point.h"

namespace hesai_test {

/// A whole file as text ("" when it cannot be read).
inline std::string read_text(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

#if defined(HESAI_CLI_PATH)
/// The hesai program, started through the emulator in cross builds (qemu-user).
inline std::string cli() {
#if defined(HESAI_CLI_EMULATOR)
  return std::string(HESAI_CLI_EMULATOR) + " " + HESAI_CLI_PATH;
#else
  return HESAI_CLI_PATH;
#endif
}

/// What a run of the program gave: its exit status (-1: it did not exit normally), its stdout and
/// stderr, its wall time, and its own peak resident set (with run_cli's `peak_rss`, natively).
struct CmdResult {
  int status = -1;
  std::string out;
  std::string err;
  double seconds = 0;
  long max_rss_kib = 0;
};

/// A temporary file of this process's, created empty ("" when it cannot be).
inline std::string temp_file(const char* what) {
  std::string path = std::string("/tmp/hesai_test_") + what + "_XXXXXX";
  const int fd = mkstemp(&path[0]);
  if (fd < 0) return "";
  close(fd);
  return path;
}

/// Runs the program with `args` (shell words) and `env` ("NAME=value ...", or empty) as its only
/// key variables: HESAI_SESSION_KEY and HESAI_SECRET of the test's own environment are removed.
/// stdout is a pipe the test reads to its end, stderr a file. With
/// `peak_rss`, natively, through tests/tools/peak_rss.c, so that max_rss_kib is the program's own
/// peak and not this test process's resident set at the fork; otherwise (and under an emulator)
/// wait4's figure. The one way every test runs the program.
inline CmdResult run_cli(const std::string& args, const std::string& env = "", bool peak_rss = false) {
  CmdResult r;
  const std::string err = temp_file("stderr");
  int pipe_fds[2];
  if (err.empty() || pipe2(pipe_fds, O_CLOEXEC) != 0) return r;
  std::string peak_file, peak;
#if defined(HESAI_PEAK_RSS_PATH) && !defined(HESAI_CLI_EMULATOR)
  if (peak_rss) {
    peak_file = temp_file("peak_rss");
    peak = std::string(HESAI_PEAK_RSS_PATH) + " " + peak_file + " ";
  }
#else
  (void)peak_rss;
#endif
  const std::string cmd = "exec env -u HESAI_SESSION_KEY -u HESAI_SECRET " + env + " " + peak + cli() + " " + args + " 2>" + err;
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(pipe_fds[1], 1);  // stdout a pipe, as a shell's `hesai ... | ...` has it
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  close(pipe_fds[1]);
  char buf[65536];
  for (ssize_t n; (n = read(pipe_fds[0], buf, sizeof buf)) != 0;) {
    if (n > 0) r.out.append(buf, static_cast<std::size_t>(n));
    else if (errno != EINTR) break;
  }
  close(pipe_fds[0]);
  int st = 0;
  rusage u{};
  if (pid > 0 && wait4(pid, &st, 0, &u) == pid) {
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    r.max_rss_kib = u.ru_maxrss;
    if (!peak_file.empty()) r.max_rss_kib = std::atol(read_text(peak_file).c_str());
  }
  if (!peak_file.empty()) std::remove(peak_file.c_str());
  r.err = read_text(err);
  std::remove(err.c_str());
  return r;
}
#endif

/// Whether two Points hold the same bits in every field. Their tail padding is not compared: a
/// decode stores the fields, and what the padding holds is whatever the memory held (clang's
/// builds leave it, GCC's happened to write it).
inline bool same_point_bits(const hesai::Point& a, const hesai::Point& b) {
  static_assert(offsetof(hesai::Point, time_ns) == 24 && offsetof(hesai::Point, intensity) == 32 &&
                    offsetof(hesai::Point, block) == 36,
                "no padding before the last field");
  return std::memcmp(&a, &b, offsetof(hesai::Point, block) + sizeof a.block) == 0;
}
inline bool same_point_bits(const hesai::Point* a, const hesai::Point* b, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i)
    if (!same_point_bits(a[i], b[i])) return false;
  return true;
}

inline std::string data_path(const std::string& name) { return std::string(HESAI_DATA_DIR) + "/" + name; }

/// The bytes of a file; a file that cannot be opened is a test failure (and gives no bytes).
inline std::vector<std::uint8_t> read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) ADD_FAILURE() << "cannot open " << path;
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

/// UDP payloads of a classic little-endian pcap of Ethernet/IPv4/UDP frames (the bundled
/// captures: 24-byte file header, 16-byte record headers, 42 bytes of frame headers).
inline std::vector<std::vector<std::uint8_t>> pcap_payloads(const std::string& name) {
  const std::vector<std::uint8_t> file = read_file(data_path(name));
  std::vector<std::vector<std::uint8_t>> out;
  std::size_t off = 24;
  while (off + 16 <= file.size()) {
    const std::uint32_t incl = hesai::load_le32(&file[off + 8]);
    off += 16;
    if (incl < 42 || off + incl > file.size()) break;
    out.emplace_back(file.begin() + static_cast<long>(off + 42), file.begin() + static_cast<long>(off + incl));
    off += incl;
  }
  return out;
}

inline hesai::ByteView view(const std::vector<std::uint8_t>& v) { return {v.data(), v.size()}; }

/// Seconds since the epoch of a UTC date-time, from the C library (an independent reference).
inline std::int64_t timegm_utc(int year, int month, int day, int hour, int minute, int second) {
  std::tm t{};
  t.tm_year = year - 1900;
  t.tm_mon = month - 1;
  t.tm_mday = day;
  t.tm_hour = hour;
  t.tm_min = minute;
  t.tm_sec = second;
  return static_cast<std::int64_t>(timegm(&t));
}

/// Rows of a simple CSV file: numbers after the first non-numeric (header) rows.
struct CsvTable {
  std::vector<std::vector<double>> rows;
};
inline CsvTable read_numeric_csv(const std::string& name) {
  std::ifstream f(data_path(name));
  if (!f) ADD_FAILURE() << "cannot open " << data_path(name);
  CsvTable t;
  std::string line;
  while (std::getline(f, line)) {
    std::vector<double> row;
    std::stringstream ss(line);
    std::string cell;
    bool numeric = true;
    while (std::getline(ss, cell, ',')) {
      if (cell.empty() || cell == "\r") continue;
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      if (end == cell.c_str()) {
        numeric = false;
        break;
      }
      row.push_back(v);
    }
    if (numeric && !row.empty()) t.rows.push_back(row);
  }
  return t;
}

/// A unit's calibration as the tests' own reader (strtod) sees it, not the library's parser.
struct ReferenceCalibration {
  std::vector<double> elevation, azimuth;  ///< degrees, by channel - 1
  std::vector<double> fire1, fire2;        ///< firing time offset per loop, us (0 if not firing)
};

/// Reads an angle file (`channel,elevation,azimuth` rows) and a firetime file: `channel,time`
/// rows (Pandar40P/64, the same time in both loops) or `loop1 channel,time,loop2 channel,time`
/// rows (QT128, channel 0 for no entry).
inline ReferenceCalibration read_reference_calibration(const std::string& angles, const std::string& firetimes,
                                                       std::size_t channels) {
  ReferenceCalibration ref;
  ref.elevation.assign(channels, 0);
  ref.azimuth.assign(channels, 0);
  ref.fire1.assign(channels, 0);
  ref.fire2.assign(channels, 0);
  for (const auto& row : read_numeric_csv(angles).rows) {
    if (row.size() < 3 || row[0] < 1) continue;
    const std::size_t ch = static_cast<std::size_t>(row[0]) - 1;
    ref.elevation.at(ch) = row[1];
    ref.azimuth.at(ch) = row[2];
  }
  for (const auto& row : read_numeric_csv(firetimes).rows) {
    if (row.size() >= 4) {
      if (row[0] >= 1) ref.fire1.at(static_cast<std::size_t>(row[0]) - 1) = row[1];
      if (row[2] >= 1) ref.fire2.at(static_cast<std::size_t>(row[2]) - 1) = row[3];
    } else if (row.size() == 2 && row[0] >= 1) {
      ref.fire1.at(static_cast<std::size_t>(row[0]) - 1) = row[1];
      ref.fire2.at(static_cast<std::size_t>(row[0]) - 1) = row[1];
    }
  }
  return ref;
}

}  // namespace hesai_test
