// Several sensors in one capture, kept apart in every output (issue #34): a capture made here
// from the bundled PandarXT16 and PandarXT32 captures, their datagrams interleaved one by one
// under one capture clock, the XT32's from another address (or another port). Each sensor's rows,
// frames, files and MCAP messages must be those of its own capture decoded alone; the two units'
// clocks differ by about 3 180 s, which no output may mix.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "mcap_check.h"
#include "test_support.h"

using namespace hesai_test;

namespace {

// One record of a classic little-endian pcap: its frame bytes (Ethernet, IPv4, UDP).
std::vector<std::vector<std::uint8_t>> pcap_frames(const std::string& name) {
  const std::vector<std::uint8_t> f = read_file(data_path(name));
  std::vector<std::vector<std::uint8_t>> out;
  for (std::size_t at = 24; at + 16 <= f.size();) {
    const auto incl = static_cast<std::size_t>(le(f, at + 8, 4));
    out.emplace_back(f.begin() + static_cast<std::ptrdiff_t>(at + 16),
                     f.begin() + static_cast<std::ptrdiff_t>(at + 16 + incl));
    at += 16 + incl;
  }
  return out;
}

// The frame's IPv4 source address set to `last_octet` in 192.168.1.x and its UDP source port to
// `port` (RFC 791 header checksum recomputed; the UDP checksum set to 0, "none", RFC 768).
void resend_from(std::vector<std::uint8_t>& frame, std::uint8_t last_octet, std::uint16_t port) {
  const std::size_t ip = 14, ihl = (frame[ip] & 0x0Fu) * 4u, udp = ip + ihl;
  frame[ip + 12] = 192;
  frame[ip + 13] = 168;
  frame[ip + 14] = 1;
  frame[ip + 15] = last_octet;
  frame[ip + 10] = frame[ip + 11] = 0;
  std::uint32_t sum = 0;
  for (std::size_t i = 0; i < ihl; i += 2) sum += static_cast<std::uint32_t>(frame[ip + i] << 8 | frame[ip + i + 1]);
  while (sum >> 16) sum = (sum & 0xFFFFu) + (sum >> 16);
  frame[ip + 10] = static_cast<std::uint8_t>(~sum >> 8);
  frame[ip + 11] = static_cast<std::uint8_t>(~sum);
  frame[udp] = static_cast<std::uint8_t>(port >> 8);
  frame[udp + 1] = static_cast<std::uint8_t>(port);
  frame[udp + 6] = frame[udp + 7] = 0;
}

// The XT16's records and the XT32's (sent from 192.168.1.`xt32_octet`:`xt32_port`), alternating,
// one capture clock: record i at 1 700 000 000 s + 100 us x i. Returns the path.
std::string two_sensor_capture(const std::string& path, std::uint8_t xt32_octet, std::uint16_t xt32_port) {
  const auto a = pcap_frames("pandar_xt16.pcap");
  auto b = pcap_frames("pandar_xt32.pcap");
  for (auto& f : b) resend_from(f, xt32_octet, xt32_port);
  std::vector<std::uint8_t> out = {0xD4, 0xC3, 0xB2, 0xA1, 2, 0, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                                   0xFF, 0xFF, 0, 0, 1, 0, 0, 0};  // microseconds, Ethernet
  std::uint64_t i = 0;
  auto put = [&](const std::vector<std::uint8_t>& frame) {
    const std::uint64_t us = i++ * 100;
    auto le32 = [&](std::uint64_t v) {
      for (int k = 0; k < 4; ++k) out.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
    };
    le32(1700000000 + us / 1000000);
    le32(us % 1000000);
    le32(frame.size());
    le32(frame.size());
    out.insert(out.end(), frame.begin(), frame.end());
  };
  for (std::size_t k = 0; k < std::max(a.size(), b.size()); ++k) {
    if (k < a.size()) put(a[k]);
    if (k < b.size()) put(b[k]);
  }
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(out.data()), static_cast<std::streamsize>(out.size()));
  return path;
}

// The lines of the program's CSV output, the header first. No field of it holds a comma or a
// quote, so a field is what lies between two commas. (Views into `text`, not a string a field:
// these are 650 000 rows, under qemu too.)
std::vector<std::string_view> csv_lines(const std::string& text) {
  std::vector<std::string_view> lines;
  for (std::size_t at = 0; at < text.size();) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    lines.emplace_back(text.data() + at, end - at);
    at = end + 1;
  }
  return lines;
}

// Field k (0-based) of a CSV line.
std::string_view field(std::string_view line, std::size_t k) {
  std::size_t at = 0;
  for (; k > 0; --k) at = line.find(',', at) + 1;
  return line.substr(at, line.find(',', at) - at);
}

// The last field: the sensor column.
std::string_view sensor_of(std::string_view line) { return line.substr(line.rfind(',') + 1); }

// A row without its packet column (1: the merged input numbers packets across both sensors) and
// its sensor column (13, the last): the other fields, each followed by a comma.
std::string without_packet_and_sensor(std::string_view line) {
  const std::size_t packet = line.find(',') + 1, after_packet = line.find(',', packet) + 1, sensor = line.rfind(',') + 1;
  std::string s(line.substr(0, packet));
  s.append(line.substr(after_packet, sensor - after_packet));
  return s;
}

class SensorsApart : public ::testing::Test {
 protected:
  void SetUp() override {
    // One directory per test: ctest runs them as processes side by side.
    dir_ = testing::TempDir() + "hesai_sensors_apart_" + std::to_string(getpid()) + "_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string dir_;
};

// The CSV's sensor column names each row's sender; each sensor's rows, in order, are its own
// capture's rows decoded alone (frame numbers, points and times the same).
TEST_F(SensorsApart, EachSensorsCsvRowsAreItsOwnCaptures) {
  const std::string merged = two_sensor_capture(dir_ + "/two.pcap", 202, 10000);
  const CmdResult r = run_cli("decode " + merged + " --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = csv_lines(r.out);
  ASSERT_GT(rows.size(), 1u);
  ASSERT_EQ(sensor_of(rows[0]), "sensor");
  ASSERT_EQ(field(rows[0], 1), "packet");
  std::map<std::string, std::vector<std::string>> by_sensor;
  for (std::size_t i = 1; i < rows.size(); ++i)
    by_sensor[std::string(sensor_of(rows[i]))].push_back(without_packet_and_sensor(rows[i]));
  ASSERT_EQ(by_sensor.size(), 2u);
  for (const auto& [capture, sensor] : {std::pair<std::string, std::string>{"pandar_xt16.pcap", "192.168.1.201:10000"},
                                        {"pandar_xt32.pcap", "192.168.1.202:10000"}}) {
    SCOPED_TRACE(capture);
    const CmdResult alone = run_cli("decode " + data_path(capture) + " --quiet");
    ASSERT_EQ(alone.status, 0);
    std::vector<std::string> want;
    const auto alone_rows = csv_lines(alone.out);
    for (std::size_t i = 1; i < alone_rows.size(); ++i) want.push_back(without_packet_and_sensor(alone_rows[i]));
    ASSERT_EQ(by_sensor[sensor].size(), want.size());
    EXPECT_TRUE(by_sensor[sensor] == want);
  }
  // The bundled counts (tests/test_xt.cpp): XT16 165 138 points, XT32 486 606.
  EXPECT_EQ(by_sensor["192.168.1.201:10000"].size(), 165138u);
  EXPECT_EQ(by_sensor["192.168.1.202:10000"].size(), 486606u);
}

// --per-frame: frame_<token>_<n> per sensor, the token "ip_" and the address with '_' for '.';
// two sensors at one address: the later one's token adds its port.
TEST_F(SensorsApart, PerFrameFilesAreNamedBySensor) {
  for (const bool same_address : {false, true}) {
    SCOPED_TRACE(same_address ? "one address, two ports" : "two addresses");
    const std::string merged = two_sensor_capture(dir_ + "/two.pcap", same_address ? 201 : 202, same_address ? 10001 : 10000);
    const std::string out = dir_ + (same_address ? "/ports" : "/addresses");
    const CmdResult r = run_cli("decode " + merged + " --quiet --per-frame --format pcd --out " + out);
    ASSERT_EQ(r.status, 0) << r.err;
    std::set<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(out)) names.insert(e.path().filename().string());
    std::set<std::string> want;
    // Five frames each (tests/test_cli.cpp: XT16 and XT32 rotations 0..4).
    for (int n = 1; n <= 5; ++n) {
      char number[32];
      std::snprintf(number, sizeof number, "_%06d.pcd", n);
      want.insert(std::string("frame_ip_192_168_1_201") + number);
      want.insert(std::string(same_address ? "frame_ip_192_168_1_201_10001" : "frame_ip_192_168_1_202") + number);
    }
    EXPECT_EQ(names, want);
  }
}

// CDR of a PointCloud2 (sensor_msgs, ROS 2): encapsulation (4), stamp sec and nanosec (8),
// frame_id (uint32 length with the NUL, then the bytes, padded to 4), height, width, ...; the
// points (32 bytes each) end one byte (is_dense) before the message's end.
struct Cloud {
  std::string frame_id;
  std::uint64_t stamp = 0, width = 0;
  std::uint32_t max_time_stamp = 0;  // the largest point offset from the stamp (bytes 28..31)
};
Cloud cloud(const std::vector<std::uint8_t>& m) {
  Cloud c;
  c.stamp = le(m, 4, 4) * 1000000000ull + le(m, 8, 4);
  const auto n = static_cast<std::size_t>(le(m, 12, 4));
  c.frame_id.assign(m.begin() + 16, m.begin() + 16 + static_cast<std::ptrdiff_t>(n - 1));
  const std::size_t after = 16 + (n + 3) / 4 * 4;
  c.width = le(m, after + 4, 4);
  const std::size_t points = m.size() - 1 - 32 * static_cast<std::size_t>(c.width);
  for (std::size_t i = 0; i < c.width; ++i)
    c.max_time_stamp = std::max(c.max_time_stamp, static_cast<std::uint32_t>(le(m, points + 32 * i + 28, 4)));
  return c;
}

// MCAP: one topic and frame_id per sensor; each topic's messages are that sensor's frames (the
// CSV's rows per frame, the stamp its earliest time_ns); no time_stamp overflows (a frame spans
// 0.1 s); the messages of both topics in log-time order in the file.
TEST_F(SensorsApart, McapHasATopicPerSensorInLogTimeOrder) {
  const std::string merged = two_sensor_capture(dir_ + "/two.pcap", 202, 10000);
  const std::string mcap = dir_ + "/two.mcap";
  ASSERT_EQ(run_cli("decode " + merged + " --quiet --format mcap --out " + mcap).status, 0);
  const CmdResult csv = run_cli("decode " + merged + " --quiet");
  ASSERT_EQ(csv.status, 0);
  // Rows and earliest time per (sensor, frame), from the CSV.
  std::map<std::pair<std::string, std::uint64_t>, std::pair<std::uint64_t, std::uint64_t>> frames;
  const auto rows = csv_lines(csv.out);
  ASSERT_EQ(field(rows[0], 0), "frame");
  ASSERT_EQ(field(rows[0], 12), "time_ns");
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto key = std::make_pair(std::string(sensor_of(rows[i])), std::stoull(std::string(field(rows[i], 0))));
    const std::uint64_t t = std::stoull(std::string(field(rows[i], 12)));
    auto [it, fresh] = frames.try_emplace(key, 0, t);
    ++it->second.first;
    it->second.second = std::min(it->second.second, t);
  }
  const std::vector<std::uint8_t> b = read_file(mcap);
  const Parsed p = check_mcap(b);
  std::map<std::uint16_t, std::string> topics;
  for (const Record& r : p.summary) {
    if (r.op != 0x04) continue;
    std::size_t at = r.body + 4;
    topics[static_cast<std::uint16_t>(le(b, r.body, 2))] = str_at(b, at);
  }
  std::set<std::string> topic_names;
  for (const auto& [id, t] : topics) topic_names.insert(t);
  EXPECT_EQ(topic_names, (std::set<std::string>{"/hesai/ip_192_168_1_201/points", "/hesai/ip_192_168_1_202/points"}));
  ASSERT_EQ(p.file_order.size(), frames.size());
  for (std::size_t i = 1; i < p.file_order.size(); ++i)
    EXPECT_GE(p.file_order[i].second, p.file_order[i - 1].second) << "message " << i << " logged before the one before it";
  // Each message against its sensor's frame: matched by the sensor its topic names and its width.
  // And each message on its own sensor's channel: the topic of the channel it is written on names
  // the sensor its frame_id names (one sensor's frames on the other's topic would pass the rest).
  std::map<std::string, std::uint64_t> messages_of;
  ASSERT_EQ(p.message_channels.size(), p.messages.size());
  for (std::size_t m = 0; m < p.messages.size(); ++m) {
    const Cloud c = cloud(p.messages[m].second);
    const std::string token = c.frame_id.substr(std::string("hesai_").size());
    const auto channel = topics.find(p.message_channels[m]);
    ASSERT_NE(channel, topics.end()) << "message " << m << " on channel " << p.message_channels[m] << ", which no Channel record declares";
    EXPECT_EQ(channel->second, "/hesai/" + token + "/points")
        << "message " << m << " (frame_id " << c.frame_id << ") is on channel " << channel->first << ", another sensor's topic";
    const std::string sensor = token == "ip_192_168_1_201" ? "192.168.1.201:10000" : "192.168.1.202:10000";
    ASSERT_TRUE(token == "ip_192_168_1_201" || token == "ip_192_168_1_202") << c.frame_id;
    EXPECT_LT(c.max_time_stamp, 1000000000u) << c.frame_id << ": a point's time_stamp overflowed";
    bool found = false;
    for (const auto& [key, f] : frames)
      found = found || (key.first == sensor && f.first == c.width && f.second == c.stamp);
    EXPECT_TRUE(found) << c.frame_id << " stamp " << c.stamp << " width " << c.width;
    ++messages_of[sensor];
  }
  EXPECT_EQ(messages_of["192.168.1.201:10000"], 5u);
  EXPECT_EQ(messages_of["192.168.1.202:10000"], 5u);
}

}  // namespace
