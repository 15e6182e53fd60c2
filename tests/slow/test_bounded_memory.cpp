// Peak memory of the hesai program on a capture of more than 1 GiB, made here from the bundled
// QT128C2X packets and deleted after: reading it (stats) and decoding it to CSV, one PCD file, one
// PLY file and one bird's-eye PNG must each stay under 256 MiB of peak resident memory, as the
// kernel reports it for the child (wait4's rusage: ru_maxrss counts mapped file pages too). The
// time of each run gives the throughput table of the README; a plain read() is the baseline.
//
// Label "slow" (ctest -L slow). Needs the capture's size free in the temporary directory. The
// outputs but the PNG go to /dev/null, so that the disk's speed does not count; it is seekable,
// so the PCD/PLY header is rewritten there as in a file. Native unsanitized builds only.
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
constexpr std::uint64_t kCaptureBytes = std::uint64_t{1} << 30;  // at least this much

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

// Runs `args` with stdout to `out_path`, stderr to /dev/null; waits for it with wait4, whose
// rusage is this child's alone.
Child spawn(const std::vector<std::string>& args, const std::string& out_path) {
  Child c;
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = hesai_test::start_process(args, out_path);
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

TEST(BoundedMemory, DecodesAOneGibCaptureInEveryFormatUnder256MiB) {
  // The capture: the bundled file's header, then its records again and again.
  const std::vector<std::uint8_t> one = hesai_test::read_file(hesai_test::data_path("qt128c2x_dual.pcap"));
  ASSERT_GT(one.size(), 24u);
  const std::size_t body = one.size() - 24;
  const std::uint64_t copies = (kCaptureBytes + body - 1) / body;
  const std::uint64_t size = 24 + copies * body;
  std::string dir = ::testing::TempDir() + "hesai_slow_XXXXXX";
  ASSERT_NE(mkdtemp(&dir[0]), nullptr);
  struct statvfs fs {};
  ASSERT_EQ(statvfs(dir.c_str(), &fs), 0);
  const std::uint64_t free_bytes = std::uint64_t{fs.f_bavail} * fs.f_frsize;
  ASSERT_GT(free_bytes, size + (std::uint64_t{256} << 20))
      << "this test writes a " << size / 1048576 << " MiB capture into " << dir << ": free space there first";
  const std::string capture = dir + "/big.pcap";
  {
    std::FILE* f = std::fopen(capture.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    bool ok = std::fwrite(one.data(), 1, one.size(), f) == one.size();
    for (std::uint64_t i = 1; ok && i < copies; ++i) ok = std::fwrite(one.data() + 24, 1, body, f) == body;
    ok = std::fclose(f) == 0 && ok;
    ASSERT_TRUE(ok) << "cannot write " << capture;
  }

  // Baseline: read() of the whole file in 1 MiB blocks (from the page cache, as the runs below).
  double read_seconds = 0, read_cpu = 0;
  {
    std::vector<char> buf(1 << 20);
    rusage before{}, after{};
    getrusage(RUSAGE_SELF, &before);
    const auto start = std::chrono::steady_clock::now();
    const int fd = ::open(capture.c_str(), O_RDONLY);
    ASSERT_GE(fd, 0);
    std::uint64_t total = 0;
    for (ssize_t n; (n = ::read(fd, buf.data(), buf.size())) > 0;) total += static_cast<std::uint64_t>(n);
    ::close(fd);
    read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    getrusage(RUSAGE_SELF, &after);
    read_cpu = cpu_seconds(after) - cpu_seconds(before);
    ASSERT_EQ(total, size);
  }

  const std::string json = dir + "/stats.json";
  struct Case {
    const char* name;
    std::vector<std::string> args;
    std::string out;
  };
  const std::vector<Case> cases = {
      {"stats", {HESAI_CLI_PATH, "stats", capture, "--json", "--quiet"}, json},
      {"decode csv", {HESAI_CLI_PATH, "decode", capture, "--quiet", "--out", "-"}, "/dev/null"},
      {"decode pcd", {HESAI_CLI_PATH, "decode", capture, "--quiet", "--format", "pcd", "--out", "/dev/null"}, "/dev/null"},
      {"decode ply", {HESAI_CLI_PATH, "decode", capture, "--quiet", "--format", "ply", "--out", "/dev/null"}, "/dev/null"},
      {"decode png", {HESAI_CLI_PATH, "decode", capture, "--quiet", "--format", "png", "--out", dir + "/one.png"}, "/dev/null"},
  };
  const double mb = static_cast<double>(size) / 1e6;
  std::printf("%.0f MB capture (%llu copies of qt128c2x_dual.pcap)\n", mb, static_cast<unsigned long long>(copies));
  // Throughput per CPU second (user + system): what one core gives, whatever else the machine runs.
  std::printf("| %-10s | %6s | %6s | %11s | %15s | %12s |\n", "run", "wall s", "CPU s", "MB/s (CPU)", "points/s (CPU)",
              "peak RSS MiB");
  std::printf("| %-10s | %6.2f | %6.2f | %11.0f | %15s | %12s |\n", "read()", read_seconds, read_cpu, mb / read_cpu, "", "");
  long long points = -1;
  for (const Case& c : cases) {
    const Child r = spawn(c.args, c.out);
    EXPECT_EQ(r.exit_status, 0) << c.name;
    EXPECT_GT(r.max_rss_kb, 0) << c.name;
    EXPECT_LT(r.max_rss_kb, kMaxRssKb) << c.name << ": peak RSS " << r.max_rss_kb / 1024 << " MiB";
    if (c.out == json) {
      const std::vector<std::uint8_t> text = hesai_test::read_file(json);
      points = json_points(std::string(text.begin(), text.end()));
    }
    std::printf("| %-10s | %6.2f | %6.2f | %11.0f | %15.3g | %12.1f |\n", c.name, r.seconds, r.cpu_seconds,
                mb / r.cpu_seconds, static_cast<double>(points) / r.cpu_seconds, static_cast<double>(r.max_rss_kb) / 1024.0);
    ::testing::Test::RecordProperty(std::string(c.name) + " peak RSS kB", std::to_string(r.max_rss_kb));
  }
  // Every packet decodes: 337 108 points per copy (test_golden.cpp counts them in the bundled file).
  EXPECT_EQ(points, static_cast<long long>(copies) * 337108);
  std::remove(json.c_str());
  std::remove((dir + "/one.png").c_str());
  std::remove(capture.c_str());
  ::rmdir(dir.c_str());
}

}  // namespace
