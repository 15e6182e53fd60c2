// The program's MCAP output (decode and listen --format mcap), checked by the structural parser
// of tests/mcap_check.h against the CSV of the same capture; usage errors.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "hesai_port/formats/pointcloud2.h"
#include "mcap_check.h"
#include "test_support.h"
#include "udp_support.h"

using namespace hesai;
using namespace hesai_test;

namespace {


TEST(McapCli, OneMessagePerFrameOfTheCsv) {
  const std::string csv = temp_path("hesai_test_cli_mcap.csv"), mcap = temp_path("hesai_test_cli.mcap");
  const std::string capture = hesai_test::data_path("pandar_xt32.pcap");
  ASSERT_EQ(std::system((cli() + " decode " + capture + " --quiet --format csv --out " + csv).c_str()), 0);
  ASSERT_EQ(std::system((cli() + " decode " + capture + " --quiet --format mcap --topic /lidar --frame-id xt32 --out " +
                         mcap).c_str()),
            0);
  // Rows per frame, in the CSV's order.
  std::map<std::uint64_t, std::uint64_t> rows;
  {
    const std::vector<std::uint8_t> text = hesai_test::read_file(csv);
    std::size_t line = 0;
    for (std::size_t i = 0; i < text.size(); i = line + 1) {
      line = i;
      while (line < text.size() && text[line] != '\n') ++line;
      if (i == 0) continue;  // the header line
      ++rows[std::stoull(std::string(text.begin() + static_cast<std::ptrdiff_t>(i), text.begin() + static_cast<std::ptrdiff_t>(line)))];
    }
  }
  ASSERT_GT(rows.size(), 1u);
  const std::vector<std::uint8_t> b = hesai_test::read_file(mcap);
  const Parsed p = check_mcap(b);
  EXPECT_EQ(p.profile, "ros2");
  ASSERT_EQ(p.messages.size(), rows.size());
  std::uint64_t total = 0;
  std::uint64_t previous_log_time = 0;
  for (const auto& [t, data] : p.messages) {
    ASSERT_GE(data.size(), 4u + 32);
    const std::vector<std::uint8_t> head = port::pointcloud2_head(0, "xt32", 0);
    const std::uint64_t width = le(data, 4 + 24, 4);  // after "xt32" + NUL (5, padded to 8)
    EXPECT_EQ(data.size(), head.size() + 32 * width + 1);
    EXPECT_EQ(le(data, 4 + 8, 4), 5u);
    EXPECT_EQ(0, std::memcmp(data.data() + 4 + 12, "xt32", 5));
    // log_time: the receive time of the datagram that closed the frame (compare.py checks it
    // against the capture's times), never going back.
    EXPECT_GE(t, previous_log_time);
    previous_log_time = t;
    total += width;
  }
  std::uint64_t csv_total = 0;
  for (const auto& [f, n] : rows) csv_total += n;
  EXPECT_EQ(total, csv_total);
  // Schema and channel in the summary: the names and encodings of the ros2 profile.
  for (const Record& r : p.summary) {
    std::size_t at = r.body + 2;
    if (r.op == 0x03) {
      EXPECT_EQ(str_at(b, at), "sensor_msgs/msg/PointCloud2");
      EXPECT_EQ(str_at(b, at), "ros2msg");
      EXPECT_EQ(str_at(b, at), port::pointcloud2_definition());
    } else if (r.op == 0x04) {
      at += 2;
      EXPECT_EQ(str_at(b, at), "/lidar");
      EXPECT_EQ(str_at(b, at), "cdr");
    }
  }
  std::remove(csv.c_str());
  std::remove(mcap.c_str());
}

int run_status(const std::string& args) {
  const int st = std::system((cli() + " " + args + " >/dev/null 2>&1").c_str());
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

TEST(McapCli, UsageErrors) {
  const std::string capture = hesai_test::data_path("pandar_xt16.pcap");
  EXPECT_EQ(run_status("decode " + capture + " --format mcap"), 1);                       // no --out
  EXPECT_EQ(run_status("decode " + capture + " --format mcap --out -"), 1);               // stdout
  EXPECT_EQ(run_status("decode " + capture + " --format mcap --per-frame --out " + temp_path("d")), 1);
  // A pipe: popen gives the program one as its stdout.
  FILE* p = popen((cli() + " decode " + capture + " --format mcap --out /dev/stdout 2>/dev/null").c_str(), "r");
  ASSERT_NE(p, nullptr);
  char buf[4096];
  while (std::fread(buf, 1, sizeof buf, p) > 0) {
  }
  const int st = pclose(p);
  EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 1);
  EXPECT_EQ(run_status("decode " + capture + " --format mcap --out /nonexistent/dir/x.mcap"), 2);
  EXPECT_EQ(run_status("decode " + capture + " --format mcap --topic"), 1);               // no value
}

// --topic must be a ROS 2 topic name once {sensor} is filled in (rcl's rules), and --frame-id must
// not be empty: exit 1, naming the rule, before anything is written. A relative name is recorded
// fully qualified.
TEST(McapCli, TopicsAreRos2NamesAndFrameIdsAreNotEmpty) {
  const std::string capture = hesai_test::data_path("pandar_xt16.pcap");
  const std::string out = temp_path("hesai_test_topics.mcap");
  const struct {
    const char* topic;
    const char* why;
  } bad[] = {{"'bad topic'", "' ' is not allowed"}, {"/a//b", "'//'"}, {"/lidar/", "end with '/'"},
             {"9lives", "start with a digit"},      {"/a/9b", "start with a digit"},
             {"/a__b", "'__'"},                    {"'~/points'", "'~'"},
             {"/{robot}/points", "only the {sensor}"}, {"''", "cannot be empty"}};
  for (const auto& c : bad) {
    SCOPED_TRACE(c.topic);
    std::remove(out.c_str());
    const CmdResult r = run_cli("decode " + capture + " --quiet --format mcap --topic " + c.topic + " --out " + out);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("is not a ROS 2 topic name"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.why), std::string::npos) << r.err;
    EXPECT_FALSE(std::ifstream(out)) << "a file was written";
  }
  for (const char* frame_id : {"''", "'{sensor}'"}) {
    const CmdResult r = run_cli("decode " + capture + " --quiet --format mcap --frame-id " + frame_id + " --out " + out);
    EXPECT_EQ(r.status, 1 + (std::string(frame_id) == "'{sensor}'" ? -1 : 0)) << frame_id << ": " << r.err;
  }
  ASSERT_EQ(run_cli("decode " + capture + " --quiet --format mcap --topic lidar/top --frame-id top --out " + out).status, 0);
  const std::vector<std::uint8_t> b = hesai_test::read_file(out);
  const Parsed p = check_mcap(b);
  std::vector<std::string> topics;
  for (const Record& r : p.summary) {
    if (r.op != 0x04) continue;
    std::size_t at = r.body + 4;
    topics.push_back(str_at(b, at));
  }
  EXPECT_EQ(topics, std::vector<std::string>{"/lidar/top"});
  std::remove(out.c_str());
}

// The rosbag2 metadata record, as rosbag2's MCAP plugin writes it: named "rosbag2", ROS_DISTRO
// from --ros-distro (default humble), indexed in the summary (check_mcap checks the index).
TEST(McapCli, Rosbag2MetadataNamesTheDistribution) {
  const std::string capture = hesai_test::data_path("pandar_xt16.pcap");
  const std::string out = temp_path("hesai_test_distro.mcap");
  for (const char* distro : {"", "jazzy"}) {
    SCOPED_TRACE(distro);
    const std::string option = *distro ? std::string(" --ros-distro ") + distro : "";
    ASSERT_EQ(run_cli("decode " + capture + " --quiet --format mcap" + option + " --out " + out).status, 0);
    const Parsed p = check_mcap(hesai_test::read_file(out));
    ASSERT_EQ(p.metadata.size(), 1u);
    ASSERT_EQ(p.metadata.count("rosbag2"), 1u);
    EXPECT_EQ(p.metadata.at("rosbag2"), (std::map<std::string, std::string>{{"ROS_DISTRO", *distro ? distro : "humble"}}));
  }
  EXPECT_EQ(run_cli("decode " + capture + " --quiet --format mcap --ros-distro 'hum ble' --out " + out).status, 1);
  std::remove(out.c_str());
}

// listen --format mcap on a replay of the XT16 capture writes the same messages as decode.
TEST(McapCli, ListenWritesWhatDecodeWrites) {
  const std::string capture = hesai_test::data_path("pandar_xt16.pcap");
  const std::string decoded = temp_path("hesai_test_decode_xt16.mcap"), live = temp_path("hesai_test_listen_xt16.mcap");
  // One frame id for both: the live sensor is 127.0.0.1 and the port replay sends from, which
  // would name another (hesai_ip_127_0_0_1).
  ASSERT_EQ(run_status("decode " + capture + " --quiet --format mcap --frame-id xt16 --out " + decoded), 0);
  const int port = hesai_test::free_udp_port();
  ASSERT_NE(port, 0);
  const std::string listen = cli() + " listen --bind 127.0.0.1 --port " + std::to_string(port) +
                             " --gps-port 0 --count 1626 --seconds 30 --quiet --format mcap --frame-id xt16 --out " + live +
                             " >/dev/null 2>&1";
  FILE* l = popen(listen.c_str(), "r");
  ASSERT_NE(l, nullptr);
  EXPECT_TRUE(hesai_test::wait_for_listener(port));
  EXPECT_EQ(run_status("replay " + capture + " --to 127.0.0.1:" + std::to_string(port) + " --rate 1 --quiet"), 0);
  EXPECT_EQ(WEXITSTATUS(pclose(l)), 0);
  const Parsed a = check_mcap(hesai_test::read_file(decoded)), b = check_mcap(hesai_test::read_file(live));
  ASSERT_EQ(a.messages.size(), 5u);  // the CSV's frames 1..5
  ASSERT_EQ(b.messages.size(), a.messages.size());
  // The same messages; their log times are each run's receive times (the capture's, the kernel's).
  for (std::size_t i = 0; i < a.messages.size(); ++i) EXPECT_TRUE(a.messages[i].second == b.messages[i].second) << i;
  std::remove(decoded.c_str());
  std::remove(live.c_str());
}

// --returns distinct (issue #32): in every output the points number exactly `points` -
// `duplicate_returns`, both counted here from the capture's bytes: the units with a distance of at
// least the smallest kept (1; 2 on the QT128C2X), and the dual-return pairs (blocks 2i, 2i + 1)
// whose two units carry the same distance (>= that) and reflectivity. Layouts typed in from the
// manuals: Pandar40P blocks of 124 bytes, units of 3 from byte 4 of a block; Pandar64 blocks of 194
// from byte 8, units of 3 after the azimuth; QT128C2X (flags 0x1D) blocks of 514 from byte 12,
// units of 4 after the azimuth.
TEST(McapCli, ReturnsDistinctInEveryFormat) {
  const struct {
    const char* file;
    std::size_t first, block, unit, units, blocks;
    std::uint16_t smallest;
  } captures[] = {{"pandar40p_dual.pcap", 4, 124, 3, 40, 10, 1},
                  {"pandar64_dual.pcap", 10, 194, 3, 64, 6, 1},
                  {"qt128c2x_dual.pcap", 14, 514, 4, 128, 2, 2}};
  for (const auto& c : captures) {
    SCOPED_TRACE(c.file);
    std::uint64_t points = 0, repeated = 0;
    for (const auto& q : pcap_payloads(c.file)) {
      for (std::size_t b = 0; b < c.blocks; ++b)
        for (std::size_t u = 0; u < c.units; ++u) {
          const std::size_t a0 = c.first + b * c.block + u * c.unit;
          const std::uint16_t d0 = static_cast<std::uint16_t>(q[a0] | q[a0 + 1] << 8);
          points += d0 >= c.smallest;
          if (b % 2 == 1) continue;
          const std::size_t a1 = a0 + c.block;
          repeated += d0 >= c.smallest && q[a1] == q[a0] && q[a1 + 1] == q[a0 + 1] && q[a1 + 2] == q[a0 + 2];
        }
    }
    ASSERT_GT(repeated, 0u);
    const std::uint64_t distinct = points - repeated;
    const std::string capture = hesai_test::data_path(c.file);
    const std::string base = temp_path("hesai_test_distinct");
    // stats: points counts every point, duplicate_returns the repeated ones, with either switch.
    for (const char* returns : {"all", "distinct"}) {
      std::FILE* f = popen((cli() + " stats " + capture + " --json --returns " + returns).c_str(), "r");
      ASSERT_NE(f, nullptr);
      std::string out;
      char buf[4096];
      for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) out.append(buf, n);
      pclose(f);
      EXPECT_NE(out.find("\"points\":" + std::to_string(points) + ","), std::string::npos) << out;
      EXPECT_NE(out.find("\"duplicate_returns\":" + std::to_string(repeated) + ","), std::string::npos) << out;
    }
    ASSERT_EQ(run_status("decode " + capture + " --quiet --returns distinct --format csv --out " + base + ".csv"), 0);
    std::uint64_t rows = 0;
    for (std::uint8_t ch : hesai_test::read_file(base + ".csv")) rows += ch == '\n';
    EXPECT_EQ(rows - 1, distinct) << "csv";
    for (const char* format : {"pcd", "ply"}) {
      const std::string out = base + "." + format;
      ASSERT_EQ(run_status("decode " + capture + " --quiet --returns distinct --format " + format + " --out " + out), 0);
      const std::string text = read_text(out);
      const std::string key = std::string(format) == "pcd" ? "\nPOINTS " : "\nelement vertex ";
      const std::size_t at = text.find(key);
      ASSERT_NE(at, std::string::npos) << format;
      EXPECT_EQ(std::stoull(text.substr(at + key.size(), 20)), distinct) << format;
      std::remove(out.c_str());
    }
    ASSERT_EQ(run_status("decode " + capture + " --quiet --returns distinct --format mcap --topic /lidar --frame-id xt32 --out " +
                         base + ".mcap"), 0);
    const Parsed p = check_mcap(hesai_test::read_file(base + ".mcap"));
    std::uint64_t total = 0;
    for (const auto& [t, data] : p.messages) total += le(data, 4 + 24, 4);  // width, after "xt32" + NUL (as above)
    EXPECT_EQ(total, distinct) << "mcap";
    std::remove((base + ".csv").c_str());
    std::remove((base + ".mcap").c_str());
  }
}

}  // namespace
