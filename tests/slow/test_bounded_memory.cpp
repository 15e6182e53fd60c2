// Peak memory of the hesai program on captures made here from the bundled QT128C2X packets and
// deleted after, of 256 MiB and then, the same file grown, of more than 1 GiB: reading each (stats)
// and decoding it to CSV, one PCD file, one PLY file and one bird's-eye PNG must each stay under
// 256 MiB of peak resident memory, as the kernel reports it for the child (wait4's rusage:
// ru_maxrss counts mapped file pages too), and each run's peak on the large capture must lie
// within 8 MiB of its peak on the small one: memory that grew with the input (a leak, a mapping
// not released, points kept) would show as 4 x the capture's growth between the two. The time of
// each run on the large capture gives the throughput table of the README; a plain read() is the
// baseline.
//
// Every run must also give every point: stats' "points" and each decode's summary line ("... P
// points written", on stderr) must equal the copies times the bundled capture's 337 108 points
// (tests/test_golden.cpp counts them from the raw bytes).
//
// Label "slow" (ctest -L slow). Needs the large capture's size free in the temporary directory.
// The outputs but the PNG go to /dev/null, so that the disk's speed does not count; it is
// seekable, so the PCD/PLY header is rewritten there as in a file. Native unsanitized builds only.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "process.h"
#include "test_support.h"

namespace {

constexpr long kMaxRssKb = 256 * 1024;
constexpr long kMaxGrowthKb = 8 * 1024;  // peak RSS, large capture against small
constexpr std::uint64_t kSmallBytes = std::uint64_t{1} << 28;  // at least this much: 256 MiB
constexpr std::uint64_t kLargeBytes = std::uint64_t{1} << 30;  // 1 GiB

struct Child {
  int exit_status = -1;
  double seconds = 0;      // wall clock
  double cpu_seconds = 0;  // user + system
  long max_rss_kb = 0;  // ru_maxrss of the child, kilobytes
};

double cpu_seconds(const rusage& ru) {
  return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) / 1e6;
}

// Runs `args` with stdout to `out_path`, stderr to `err_path`; waits for it with wait4, whose
// rusage is this child's alone.
Child spawn(const std::vector<std::string>& args, const std::string& out_path, const std::string& err_path) {
  Child c;
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = hesai_test::start_process(args, out_path, err_path);
  if (pid == 0) return c;
  int status = 0;
  rusage ru{};
  if (wait4(pid, &status, 0, &ru) != pid) return c;
  c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  c.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  c.max_rss_kb = ru.ru_maxrss;
  c.cpu_seconds = cpu_seconds(ru);
  return c;
}

// The number after "points": in stats --json output.
long long json_points(const std::string& json) {
  const std::size_t at = json.find("\"points\":");
  return at == std::string::npos ? -1 : std::stoll(json.substr(at + 9));
}

// P in the summary line "N packets, F frames, P points written to ..." of hesai decode; -1 when absent.
long long summary_points(const std::string& text) {
  const std::size_t end = text.find(" points written");
  if (end == std::string::npos) return -1;
  const std::size_t start = text.rfind(", ", end);
  return start == std::string::npos ? -1 : std::stoll(text.substr(start + 2, end - start - 2));
}

// Appends copies of the bundled capture's records to `path` (its header first when `copies_now`
// is 0) until it holds `copies` of them.
bool grow_capture(const std::string& path, const std::vector<std::uint8_t>& one, std::uint64_t copies_now, std::uint64_t copies) {
  std::FILE* f = std::fopen(path.c_str(), copies_now == 0 ? "wb" : "ab");
  if (f == nullptr) return false;
  const std::size_t body = one.size() - 24;
  bool ok = true;
  if (copies_now == 0) {
    ok = std::fwrite(one.data(), 1, one.size(), f) == one.size();
    copies_now = 1;
  }
  for (std::uint64_t i = copies_now; ok && i < copies; ++i) ok = std::fwrite(one.data() + 24, 1, body, f) == body;
  return std::fclose(f) == 0 && ok;
}

TEST(BoundedMemory, PeakMemoryUnder256MiBAndTheSameAt256MiBAnd1GiB) {
  // The captures: the bundled file's header, then its records again and again. Without --quiet
  // each decode prints its summary line (stderr is not a terminal: no progress line); the CSV to
  // a named file (/dev/null) for it, as to stdout it prints none.
  const std::vector<std::uint8_t> one = hesai_test::read_file(hesai_test::data_path("qt128c2x_dual.pcap"));
  ASSERT_GT(one.size(), 24u);
  const std::size_t body = one.size() - 24;
  const std::uint64_t small_copies = (kSmallBytes + body - 1) / body;
  const std::uint64_t large_copies = (kLargeBytes + body - 1) / body;
  const std::uint64_t large_size = 24 + large_copies * body;
  std::string dir = ::testing::TempDir() + "hesai_slow_XXXXXX";
  ASSERT_NE(mkdtemp(&dir[0]), nullptr);
  struct statvfs fs {};
  ASSERT_EQ(statvfs(dir.c_str(), &fs), 0);
  const std::uint64_t free_bytes = std::uint64_t{fs.f_bavail} * fs.f_frsize;
  ASSERT_GT(free_bytes, large_size + (std::uint64_t{256} << 20))
      << "this test writes a " << large_size / 1048576 << " MiB capture into " << dir << ": free space there first";
  const std::string capture = dir + "/big.pcap";
  const std::string json = dir + "/stats.json";
  const std::string summary = dir + "/stderr.txt";
  struct Case {
    const char* name;
    std::vector<std::string> args;
    std::string out;
  };
  const std::vector<Case> cases = {
      {"stats", {HESAI_CLI_PATH, "stats", capture, "--json", "--quiet"}, json},
      {"decode csv", {HESAI_CLI_PATH, "decode", capture, "--out", "/dev/null"}, "/dev/null"},
      {"decode pcd", {HESAI_CLI_PATH, "decode", capture, "--format", "pcd", "--out", "/dev/null"}, "/dev/null"},
      {"decode ply", {HESAI_CLI_PATH, "decode", capture, "--format", "ply", "--out", "/dev/null"}, "/dev/null"},
      {"decode png", {HESAI_CLI_PATH, "decode", capture, "--format", "png", "--out", dir + "/one.png"}, "/dev/null"},
  };
  std::vector<long> small_rss_kb;

  for (const std::uint64_t copies : {small_copies, large_copies}) {
    const bool large = copies == large_copies;
    ASSERT_TRUE(grow_capture(capture, one, large ? small_copies : 0, copies)) << "cannot write " << capture;
    const std::uint64_t size = 24 + copies * body;
    const double mb = static_cast<double>(size) / 1e6;
    std::printf("%.0f MB capture (%llu copies of qt128c2x_dual.pcap)\n", mb, static_cast<unsigned long long>(copies));

    // Throughput per CPU second (user + system): what one core gives, whatever else the machine runs.
    std::printf("| %-10s | %6s | %6s | %11s | %15s | %12s |\n", "run", "wall s", "CPU s", "MB/s (CPU)", "points/s (CPU)",
                "peak RSS MiB");
    if (large) {
      // Baseline: read() of the whole file in 1 MiB blocks (from the page cache, as the runs below).
      std::vector<char> buf(1 << 20);
      rusage before{}, after{};
      getrusage(RUSAGE_SELF, &before);
      const auto start = std::chrono::steady_clock::now();
      const int fd = ::open(capture.c_str(), O_RDONLY);
      ASSERT_GE(fd, 0);
      std::uint64_t total = 0;
      for (ssize_t n; (n = ::read(fd, buf.data(), buf.size())) > 0;) total += static_cast<std::uint64_t>(n);
      ::close(fd);
      const double read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      getrusage(RUSAGE_SELF, &after);
      const double read_cpu = cpu_seconds(after) - cpu_seconds(before);
      ASSERT_EQ(total, size);
      std::printf("| %-10s | %6.2f | %6.2f | %11.0f | %15s | %12s |\n", "read()", read_seconds, read_cpu, mb / read_cpu, "", "");
    }
    long long points = -1;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const Case& c = cases[i];
      const Child r = spawn(c.args, c.out, summary);
      EXPECT_EQ(r.exit_status, 0) << c.name;
      EXPECT_GT(r.max_rss_kb, 0) << c.name;
      EXPECT_LT(r.max_rss_kb, kMaxRssKb) << c.name << ": peak RSS " << r.max_rss_kb / 1024 << " MiB";
      if (!large) {
        small_rss_kb.push_back(r.max_rss_kb);
      } else {
        const long growth = r.max_rss_kb - small_rss_kb[i];
        EXPECT_LT(growth < 0 ? -growth : growth, kMaxGrowthKb)
            << c.name << ": peak RSS " << small_rss_kb[i] << " kB on " << small_copies << " copies, " << r.max_rss_kb
            << " kB on " << large_copies;
      }
      // Every packet decodes: 337 108 points per copy (test_golden.cpp counts them in the bundled file).
      const std::vector<std::uint8_t> err = hesai_test::read_file(summary);
      if (c.out == json) {
        const std::vector<std::uint8_t> text = hesai_test::read_file(json);
        points = json_points(std::string(text.begin(), text.end()));
        EXPECT_EQ(points, static_cast<long long>(copies) * 337108) << c.name;
      } else {
        EXPECT_EQ(summary_points(std::string(err.begin(), err.end())), static_cast<long long>(copies) * 337108)
            << c.name << ": " << std::string(err.begin(), err.end());
      }
      std::printf("| %-10s | %6.2f | %6.2f | %11.0f | %15.3g | %12.1f |\n", c.name, r.seconds, r.cpu_seconds,
                  mb / r.cpu_seconds, static_cast<double>(points) / r.cpu_seconds, static_cast<double>(r.max_rss_kb) / 1024.0);
      ::testing::Test::RecordProperty(std::string(c.name) + (large ? " 1 GiB" : " 256 MiB") + " peak RSS kB",
                                      std::to_string(r.max_rss_kb));
    }
  }
  std::remove(json.c_str());
  std::remove(summary.c_str());
  std::remove((dir + "/one.png").c_str());
  std::remove(capture.c_str());
  ::rmdir(dir.c_str());
}

}  // namespace
