// End-to-end tests of the hesai program on the bundled captures and on captures built here
// with known drops, duplicates, late packets, corrupted CRCs and signatures.
#include <gtest/gtest.h>
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <cctype>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "hesai/crc32.h"
#include "hesai/decoder.h"
#include "hesai/sha256.h"
#include "hesai_port/base/crc32_ieee.h"
#include "hesai/hkdf.h"
#include "hesai_port/net/udp.h"
#include "packet_builder.h"
#include "pandar64_manual.h"
#include "safety_stream.h"
#include "test_support.h"
#include "udp_support.h"

using namespace hesai;
using namespace hesai_test;

namespace {


// The integer value of "key": in a flat JSON object (models is read separately).
std::map<std::string, long long> json_numbers(const std::string& json) {
  std::map<std::string, long long> m;
  for (std::size_t q = json.find('"'); q != std::string::npos; q = json.find('"', q + 1)) {
    const std::size_t end = json.find('"', q + 1);
    if (end == std::string::npos) break;
    const std::string key = json.substr(q + 1, end - q - 1);
    if (end + 2 < json.size() && json[end + 1] == ':' && (std::isdigit(static_cast<unsigned char>(json[end + 2])) || json[end + 2] == '-'))
      m[key] = std::stoll(json.substr(end + 2));
    q = end;
  }
  return m;
}

// The number printed after `key` on its line of the text summary ("  key      value"); -1 if absent.
long long text_number(const std::string& text, const std::string& key) {
  const std::size_t at = text.find("  " + key + " ");
  if (at == std::string::npos) return -1;
  return std::stoll(text.substr(text.find_first_not_of(' ', at + 2 + key.size())));
}

std::string temp_dir() {
  char tmpl[] = "/tmp/hesai_cli_XXXXXX";
  return mkdtemp(tmpl);
}

// A classic pcap of Ethernet/IPv4/UDP frames around the payloads (sensor 192.168.1.201:10000).
void write_pcap(const std::string& path, const std::vector<std::vector<std::uint8_t>>& payloads) {
  std::vector<std::uint8_t> f(24, 0);
  store_le32(&f[0], 0xA1B2C3D4);
  store_le16(&f[4], 2);
  store_le16(&f[6], 4);
  store_le32(&f[16], 65535);
  store_le32(&f[20], 1);
  std::uint32_t t = 1700000000;
  for (const auto& p : payloads) {
    std::vector<std::uint8_t> frame(42, 0);
    for (int i = 0; i < 6; ++i) frame[static_cast<std::size_t>(i)] = 0xFF;
    frame[12] = 0x08;
    frame[14] = 0x45;
    hesai::store_le16(&frame[16], 0);
    frame[16] = static_cast<std::uint8_t>((p.size() + 28) >> 8);
    frame[17] = static_cast<std::uint8_t>(p.size() + 28);
    frame[22] = 64;
    frame[23] = 17;
    const std::uint8_t src[4] = {192, 168, 1, 201};
    for (int i = 0; i < 4; ++i) frame[26 + static_cast<std::size_t>(i)] = src[i];
    for (int i = 0; i < 4; ++i) frame[30 + static_cast<std::size_t>(i)] = 255;
    frame[34] = 10000 >> 8; frame[35] = 10000 & 0xFF;
    frame[36] = 2368 >> 8; frame[37] = 2368 & 0xFF;
    frame[38] = static_cast<std::uint8_t>((p.size() + 8) >> 8);
    frame[39] = static_cast<std::uint8_t>(p.size() + 8);
    frame.insert(frame.end(), p.begin(), p.end());
    std::uint8_t rec[16];
    store_le32(rec, t);
    store_le32(rec + 4, 0);
    store_le32(rec + 8, static_cast<std::uint32_t>(frame.size()));
    store_le32(rec + 12, static_cast<std::uint32_t>(frame.size()));
    f.insert(f.end(), rec, rec + 16);
    f.insert(f.end(), frame.begin(), frame.end());
    ++t;
  }
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(f.data()), static_cast<long>(f.size()));
}

// ---- Usage and errors ----

TEST(Cli, HelpAndExitStatuses) {
  EXPECT_EQ(run_cli("--help").status, 0);
  for (const char* cmd : {"decode", "stats", "listen", "replay"}) {
    const CmdResult r = run_cli(std::string(cmd) + " --help");
    EXPECT_EQ(r.status, 0) << cmd;
    EXPECT_NE(r.out.find("usage: hesai"), std::string::npos) << cmd;
  }
  EXPECT_EQ(run_cli("").status, 1);
  EXPECT_EQ(run_cli("frobnicate").status, 1);
  EXPECT_EQ(run_cli("decode").status, 1);
  EXPECT_EQ(run_cli("stats x.pcap --bogus").status, 1);
  EXPECT_EQ(run_cli("decode x.pcap --format tiff").status, 1);
  // --cut-angle in [0, 360), --fov START in [0, 360), END in [0, 360], START != END (frame.h).
  for (const char* bad : {"--cut-angle 360", "--cut-angle -0.01", "--cut-angle nan", "--fov 10:10", "--fov 360:10",
                          "--fov 10:360.5", "--fov 10"})
    EXPECT_EQ(run_cli(std::string("stats x.pcap ") + bad).status, 1) << bad;
  EXPECT_EQ(run_cli("stats " + data_path("pandar64_dual.pcap") + " --cut-angle 359.999 --fov 300:360").status, 0);
  EXPECT_EQ(run_cli("stats /nonexistent/file.pcap").status, 2);
  EXPECT_EQ(run_cli("stats " + data_path("calibration/pandar64_unit_a_angles.csv")).status, 2);  // not a capture
  EXPECT_EQ(run_cli("stats " + data_path("pandar64_dual.pcap") + " --calibration /nonexistent.csv").status, 2);
  // A QT128 calibration for a Pandar64 capture: a configuration error, named.
  EXPECT_EQ(run_cli("stats " + data_path("pandar64_dual.pcap") + " --calibration " +
                data_path("calibration/qt128c2x_unit_a_angles.csv")).status, 1);
}

// Capture errors: named by the file, the code and the byte offset, exit status 2 (README). The
// message texts are a contract: scripts match them.
// hesai --version names the project's version (CMake's), the C ABI, and the paths the core and
// the port choose on this machine, as this process's own calls to them say.
TEST(Cli, VersionNamesTheBuildAndItsCpuPaths) {
  const CmdResult r = run_cli("--version");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind(std::string("hesai ") + HESAI_PROJECT_VERSION + "\n", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("C ABI (libhesai_c) 1\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(std::string("decode: ") + hesai::decode_simd_name() + " "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(std::string("crc32/mpeg-2 (packets): ") + hesai::crc32_path_name() + "\n"), std::string::npos) << r.out;
  const char* ieee = hesai::port::crc32_ieee_path_name(hesai::port::crc32_ieee_best_path());
  EXPECT_NE(r.out.find(std::string("crc32/ieee (mcap, png): ") + ieee + "\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(std::string("sha-256 (signatures): ") + hesai::sha256_path_name() + "\n"), std::string::npos) << r.out;
}

// The top-level usage names each command, and each one it names answers --help with its own
// usage; the sensor line names every sensor command (set, apply and reboot too).
TEST(Cli, UsageNamesEveryCommand) {
  const CmdResult r = run_cli("--help");
  ASSERT_EQ(r.status, 0);
  std::vector<std::string> named;
  std::istringstream lines(r.out.substr(r.out.find("commands:\n") + 10));
  for (std::string line; std::getline(lines, line) && !line.empty();)
    if (line.rfind("  ", 0) == 0 && line[2] != ' ') named.push_back(line.substr(2, line.find(' ', 2) - 2));
  EXPECT_EQ(named, (std::vector<std::string>{"decode", "stats", "listen", "replay", "sensor"})) << r.out;
  for (const std::string& cmd : named) {
    const CmdResult h = run_cli(cmd + " --help");
    EXPECT_EQ(h.status, 0) << cmd;
    EXPECT_NE(h.out.find("usage: hesai " + cmd), std::string::npos) << cmd << ": " << h.out;
  }
  for (const char* sub : {"info", "config", "status", "calibration", "firetimes", "channel-config", "signature", "set",
                          "apply", "reboot"}) {
    EXPECT_NE(r.out.find(sub), std::string::npos) << sub;
    // A sensor command: without a HOST it asks for what it lacks, where an unknown one is named as such.
    const CmdResult no_host = run_cli(std::string("sensor ") + sub);
    EXPECT_EQ(no_host.status, 1) << sub;
    EXPECT_EQ(no_host.err.find("unknown command"), std::string::npos) << sub << ": " << no_host.err;
  }
  EXPECT_NE(run_cli("sensor bogus 127.0.0.1").err.find("unknown command 'bogus'"), std::string::npos);
  const CmdResult unknown = run_cli("frobnicate");
  EXPECT_EQ(unknown.status, 1);
  EXPECT_NE(unknown.err.find("unknown command 'frobnicate'"), std::string::npos);
}

TEST(Cli, CaptureErrorMessages) {
  const std::string dir = temp_dir();
  const std::string not_capture = data_path("calibration/pandar64_firetimes.csv");
  // The bundled Pandar64 capture cut after 5000 bytes: records of 16 + incl_len bytes after the
  // 24-byte header, all of the same length; the cut one starts at 24 + k * (16 + incl_len).
  const std::vector<std::uint8_t> whole = read_file(data_path("pandar64_dual.pcap"));
  const std::size_t record = 16 + load_le32(&whole[24 + 8]);
  const std::size_t cut_at = 24 + (5000 - 24) / record * record;
  const std::string cut = dir + "/cut.pcap", empty = dir + "/empty.pcap", link = dir + "/link.pcap";
  std::ofstream(cut, std::ios::binary).write(reinterpret_cast<const char*>(whole.data()), 5000);
  std::ofstream(empty, std::ios::binary).flush();
  // A classic pcap header of link type 119 (LINKTYPE_PRISM_HEADER, not read here).
  std::vector<std::uint8_t> header(whole.begin(), whole.begin() + 24);
  store_le32(&header[20], 119);
  std::ofstream(link, std::ios::binary).write(reinterpret_cast<const char*>(header.data()), 24);
  const std::pair<std::string, std::string> cases[] = {
      {not_capture, not_capture + ": capture_bad_magic at byte 0: not a pcap, pcapng or MCAP file (or an unsupported version)"},
      {cut, cut + ": capture_truncated at byte " + std::to_string(cut_at) + ": the file ends inside a header, record or block"},
      {empty, empty + ": empty file"},
      {link, link + ": capture_unsupported_link at byte 20: a link type this reader does not unpack"},
      {dir + "/none.pcap", dir + "/none.pcap: open failed: " + std::strerror(ENOENT)},
  };
  for (const auto& [file, message] : cases) {
    const CmdResult r = run_cli("stats --json " + file);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("hesai: " + message + "\n"), std::string::npos) << r.err;
  }
}

// A copy of a bundled calibration file, in a fresh temporary directory, with the line that
// starts with `from` starting with `to` instead.
std::string altered_calibration(const std::string& name, const std::string& from, const std::string& to) {
  const std::vector<std::uint8_t> bytes = read_file(data_path("calibration/" + name));
  std::string text(bytes.begin(), bytes.end());
  const std::size_t at = text.find("\n" + from);
  EXPECT_NE(at, std::string::npos) << name << " has no line " << from;
  if (at != std::string::npos) text.replace(at + 1, from.size(), to);
  const std::string path = temp_dir() + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// A calibration file the decoder cannot use is a configuration error (exit status 1, README
// "The hesai program"), named by file and Error code, and nothing is decoded: never points on
// the design angles as if the file had been applied. Limits: Decoder::set_angles and
// set_firetimes (decoder.h), parse_channel_config_csv (calibration.h).
TEST(Cli, CalibrationValueOutOfRangeIsAConfigurationError) {
  struct Case {
    const char* capture;
    const char* option;
    const char* file;
    const char* from;  // a line of the bundled file...
    const char* to;    // ...becomes this
    const char* error; // expected after "PATH: "
    const char* why;   // and this in the message
  };
  const Case cases[] = {
      {"pandar64_dual.pcap", "--calibration", "pandar64_unit_a_angles.csv", "2,11.05,", "2,95,", "invalid_argument", "elevation"},
      {"qt128c2x_dual.pcap", "--calibration", "qt128c2x_unit_a_angles.csv", "3,-49.51495392,9.384265827", "3,-49.51495392,400",
       "invalid_argument", "azimuth offset"},
      {"pandar64_dual.pcap", "--firetimes", "pandar64_firetimes.csv", "61,-3.62", "61,-5000", "invalid_argument", "firing time"},
      {"qt128c2x_dual.pcap", "--firetimes", "qt128c2x_firetimes.csv", "65,1.456,99,1.456", "65,5000,99,1.456",
       "invalid_argument", "firing time"},
      // Channel 49 twice in Loop1 (lines 4 and 5); channel 200 of a 128-channel sensor (line 6).
      {"qt128c2x_dual.pcap", "--channel-config", "qt128c2x_channel_config.csv", "50,18", "49,18", "line 5: calib_bad_channel", ""},
      {"qt128c2x_dual.pcap", "--channel-config", "qt128c2x_channel_config.csv", "51,19", "51,200", "line 6: calib_bad_channel", ""},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.file) + ": " + c.to);
    const std::string stats = "stats " + data_path(c.capture) + " --json " + c.option + " ";
    // The bundled file itself is accepted.
    EXPECT_EQ(run_cli(stats + data_path(std::string("calibration/") + c.file)).status, 0);
    const std::string path = altered_calibration(c.file, c.from, c.to);
    const CmdResult r = run_cli(stats + path);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find(path + ": " + c.error), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.why), std::string::npos) << r.err;
    EXPECT_EQ(r.out.find("\"packets\""), std::string::npos) << r.out;  // no statistics
  }
  // The ends of the ranges are accepted: elevation 90 degrees, a firing time of -1000 us.
  EXPECT_EQ(run_cli("stats " + data_path("pandar64_dual.pcap") + " --calibration " +
                altered_calibration("pandar64_unit_a_angles.csv", "2,11.05,", "2,90,")).status, 0);
  EXPECT_EQ(run_cli("stats " + data_path("pandar64_dual.pcap") + " --firetimes " +
                altered_calibration("pandar64_firetimes.csv", "61,-3.62", "61,-1000")).status, 0);
}

// The text report prints capture times as UTC dates: the Pandar64 capture's first packet is
// 2020-06-25 12:02:09 and 977341 us (year byte 120, years since 1900 by the vendor SDK's rule;
// see test_golden.cpp). The same packet with year byte 40 is 2040 (by every reading), past 2038:
// a 32-bit time_t (armhf without _TIME_BITS=64) printed such dates wrapped into the 1900s.
TEST(Cli, StatsTextPrintsDatesPast2038) {
  const CmdResult r = run_cli("stats " + data_path("pandar64_dual.pcap"));
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("2020-06-25T12:02:09.977341000Z"), std::string::npos) << r.out;

  auto p = pcap_payloads("pandar64_dual.pcap").at(0);
  ASSERT_EQ(p[1188], 120);
  p[1188] = 40;  // Date & Time year byte: 2040
  const std::string dir = temp_dir();
  write_pcap(dir + "/y2040.pcap", {p});
  const CmdResult late = run_cli("stats " + dir + "/y2040.pcap");
  ASSERT_EQ(late.status, 0) << late.out;
  EXPECT_NE(late.out.find("2040-06-25T12:02:09.977341000Z"), std::string::npos) << late.out;
}

// ---- The bundled captures ----

struct CaptureCase {
  const char* file;
  Model model;
  long long packets;
  long long points;
  long long lost;    // UDP sequence numbers missing from the capture
  long long frames;  // clockwise, cut at 0: the rotations the points span (at the instantiations)
};

void PrintTo(const CaptureCase& c, std::ostream* os) { *os << c.file; }

class CliCapture : public ::testing::TestWithParam<CaptureCase> {};

TEST_P(CliCapture, StatsJsonOnRealCapture) {
  const CaptureCase& c = GetParam();
  const CmdResult r = run_cli("stats " + data_path(c.file) + " --json");
  ASSERT_EQ(r.status, 0) << r.out;
  auto j = json_numbers(r.out);
  for (const char* key : {"packets", "points", "frames", "crc_errors", "signature_valid", "signature_invalid",
                          "signature_missing", "unsigned_accepted", "unsigned_rejected", "signature_unverified",
                          "malformed", "unsupported", "lost",
                          "duplicates", "reordered", "sequence_resyncs", "gps_packets", "first_time_ns",
                          "last_time_ns", "high_temperature", "gps_unlocked", "gps_position_invalid", "fs_packets",
                          "fs_current_fault", "fs_past_fault", "fs_reserved_fault_type", "fs_last_fault_code",
                          "fs_last_fault_id", "fs_last_fault_total", "fs_counter_stalls"})
    EXPECT_TRUE(j.count(key)) << key;
  // fs_states: an object with the eight lidar states of the QT128 manual, in code order.
  EXPECT_NE(r.out.find("\"fs_states\":{\"init\":"), std::string::npos) << r.out;
  for (const char* state : {"init", "normal", "report_fault", "pre_performance_degradation", "performance_degradation",
                            "pre_shutdown", "shutdown", "standby"})
    EXPECT_TRUE(j.count(state)) << state;
  EXPECT_NE(r.out.find("\"models\":{\"" + std::string(model_name(c.model)) + "\":" + std::to_string(c.packets) + "}"),
            std::string::npos) << r.out;
  EXPECT_EQ(j["packets"], c.packets);
  EXPECT_EQ(j["points"], c.points);
  EXPECT_EQ(j["crc_errors"], 0);
  EXPECT_EQ(j["malformed"], 0);
  EXPECT_EQ(j["unsupported"], 0);
  EXPECT_EQ(j["lost"], c.lost);
  EXPECT_EQ(j["duplicates"], 0);
  EXPECT_EQ(j["reordered"], 0);
  EXPECT_EQ(j["frames"], c.frames);
  EXPECT_EQ(j["high_temperature"], 0);  // the Pandar captures' flag bytes are 0
  EXPECT_EQ(j["gps_unlocked"], 0);      // no GPS packets
  // Functional safety: QT128 only; the capture is in state Init throughout, without a stall.
  const long long fs = c.model == Model::qt128c2x ? c.packets : 0;
  EXPECT_EQ(j["fs_packets"], fs);
  EXPECT_EQ(j["init"], fs);
  EXPECT_EQ(j["fs_counter_stalls"], 0);
}

// The frames of a stream of one sensor's packets by this test's own reckoning (the cut at 0
// degrees; as tests/test_frame.cpp reckons them, without FrameAssembler): the block azimuths
// unwrapped, each block moved forward from the one before (across a gap in the capture, by the
// whole turns the packet times and motor speed give), each point placed at its block plus the
// short way to its own azimuth, and a frame per rotation, floor(position / 360 degrees). As
// rotation -> points, the first rotation 0 being the one the first block lies in.
std::map<std::int64_t, std::uint64_t> reckoned_frames(const std::vector<std::vector<std::uint8_t>>& packets,
                                                      Model model, Rotation rotation) {
  const bool cw = rotation == Rotation::clockwise;
  Decoder dec(model);
  dec.set_rotation(rotation);
  PacketPoints pts;
  PacketInfo info;
  std::map<std::int64_t, std::uint64_t> out;
  // Positions in 0.01 degree past the cut before the first block, in the direction of rotation.
  const auto forward = [cw](double from, double to) { return std::fmod((cw ? to - from : from - to) + 72000.0, 36000.0); };
  double block_at = 0, last_az = 0;
  std::int64_t last_ns = 0;
  bool first = true;
  for (const auto& p : packets) {
    EXPECT_EQ(dec.decode(view(p), info, pts), Error::ok);
    std::size_t next = 0;
    for (std::size_t b = 0; b < info.blocks; ++b) {
      const double az = info.block_azimuth[b];
      if (first) {
        block_at = forward(0, az);
        first = false;
      } else {
        double move = forward(last_az, az);
        if (b == 0) {  // whole turns a gap may hide: those the time since the last packet spun
          const double spun = static_cast<double>(info.time_ns - last_ns) * 1e-9 * info.motor_rpm / 60.0 * 36000.0;
          move += 36000.0 * std::round((spun - move) / 36000.0);
        }
        block_at += move;
      }
      last_az = az;
      for (; next < pts.count && pts.points[next].block == b; ++next) {
        const double off = std::fmod(pts.points[next].azimuth_deg * 100.0 - az + 54000.0, 36000.0) - 18000.0;
        ++out[static_cast<std::int64_t>(std::floor((block_at + (cw ? off : -off)) / 36000.0))];
      }
    }
    last_ns = info.time_ns;
  }
  return out;
}

// The frames of `decode --per-frame`: one file per rotation of this test's reckoning
// (reckoned_frames), numbered from 1 in rotation order, each with exactly its rotation's points,
// and no other; stats counts as many.
TEST_P(CliCapture, PerFrameCsvHoldsEachRotationsPoints) {
  const CaptureCase& c = GetParam();
  const auto packets = pcap_payloads(c.file);
  ASSERT_FALSE(packets.empty());
  const auto rotations = reckoned_frames(packets, c.model, Rotation::clockwise);
  ASSERT_EQ(static_cast<long long>(rotations.size()), c.frames);
  ASSERT_EQ(rotations.rbegin()->first - rotations.begin()->first + 1, c.frames) << "a rotation without points";
  const std::string dir = temp_dir();
  const CmdResult r = run_cli("decode " + data_path(c.file) + " --per-frame --format csv --quiet --out " + dir);
  ASSERT_EQ(r.status, 0);
  // Every bundled capture comes from 192.168.1.201 (port 10000): the sensor's token (sinks.h).
  const auto file_of = [&dir](long long id) {
    char name[64];
    std::snprintf(name, sizeof name, "/frame_ip_192_168_1_201_%06lld.csv", id);
    return dir + name;
  };
  for (const auto& [rotation, n] : rotations) {
    const long long id = rotation - rotations.begin()->first + 1;
    std::ifstream f(file_of(id));
    ASSERT_TRUE(f) << file_of(id);
    std::string line;
    std::getline(f, line);
    EXPECT_EQ(line, "frame,packet,block,channel,return,azimuth_deg,elevation_deg,distance_m,x,y,z,intensity,time_ns,sensor");
    std::uint64_t rows = 0, other = 0, other_sensor = 0;
    while (std::getline(f, line)) {
      ++rows;
      other += line.substr(0, line.find(',')) != std::to_string(id);
      other_sensor += line.substr(line.rfind(',') + 1) != "192.168.1.201:10000";
    }
    EXPECT_EQ(other_sensor, 0u) << "rows of frame " << id << " with another sensor";
    EXPECT_EQ(rows, n) << "frame " << id;
    EXPECT_EQ(other, 0u) << "rows of frame " << id << " with another frame number";
  }
  EXPECT_FALSE(std::ifstream(file_of(0))) << "a frame 0";
  EXPECT_FALSE(std::ifstream(file_of(c.frames + 1))) << "a frame after the last rotation";
  const CmdResult s = run_cli("stats " + data_path(c.file) + " --json");
  EXPECT_EQ(json_numbers(s.out)["frames"], c.frames);
}

// frames, by hand (clockwise, cut at 0; the first and last block azimuths and the turns between
// them read from the raw bytes, as tests/golden/count_points.py reads them): Pandar40P blocks
// 1.47 deg -> 4 turns -> 1.42, Pandar64 0.71 -> 4 -> 0.84, PandarQT64 1.20 -> 4 -> 0.60: the first
// blocks' beams reach back past the cut (the spread behind is larger than the first azimuth), so
// rotations -1..4: 6. QT128C2X 10.80 -> 2 -> 10.40, less than its spread: rotations 0..2: 3.
// PandarXT16 269.64 -> 3.25 -> 0.18, XT32 1.08 -> 4 -> 0.90, XT32M2X 0.72 -> 4 (across its gaps,
// by the packet times) -> 0.72: the XT's design offsets are 0, and no beam reaches back past the
// cut: rotations 0..4: 5.
INSTANTIATE_TEST_SUITE_P(Bundled, CliCapture,
                         ::testing::Values(CaptureCase{"pandar40p_dual.pcap", Model::pandar40p, 1439, 434934, 0, 6},
                                           CaptureCase{"pandar64_dual.pcap", Model::pandar64, 2400, 716622, 0, 6},
                                           CaptureCase{"qt128c2x_dual.pcap", Model::qt128c2x, 1800, 337108, 0, 3},
                                           CaptureCase{"pandar_qt64.pcap", Model::pandar_qt64, 1200, 299376, 0, 6}),
                         [](const auto& i) { return std::string(model_name(i.param.model)); });

// The PandarXT family (protocol 6.1); the XT32M2X capture skips 852 UDP sequence numbers in three
// gaps (counted from its raw tails in test_xt.cpp).
INSTANTIATE_TEST_SUITE_P(BundledXt, CliCapture,
                         ::testing::Values(CaptureCase{"pandar_xt16.pcap", Model::pandar_xt16, 1626, 165138, 0, 5},
                                           CaptureCase{"pandar_xt32.pcap", Model::pandar_xt32, 2000, 486606, 0, 5},
                                           CaptureCase{"pandar_xt32m2x.pcap", Model::pandar_xt32m2x, 1815, 223372, 852, 5}),
                         [](const auto& i) { return std::string(model_name(i.param.model)); });

// A counter-clockwise unit: the QT128 capture mirrored (every block azimuth a -> 36000 - a).
// --rotation ccw decodes every packet with the firing-time correction subtracted, as the library
// does counter-clockwise; auto (the default) the same from the first packet on (the dual-return
// QT128C2X's first two packets, which do not show the direction by themselves, are held until
// the third does); cw all of them with the clockwise correction. The frames follow: stats counts
// the library's counter-clockwise frames with ccw and with auto.
TEST(Cli, RotationOption) {
  EXPECT_EQ(run_cli("stats x.pcap --rotation left").status, 1);
  const auto real = pcap_payloads("qt128c2x_dual.pcap");
  std::vector<std::vector<std::uint8_t>> mirrored;
  for (const auto& p : real) mirrored.push_back(counterclockwise_copy(p, Model::qt128c2x));
  const std::string dir = temp_dir();
  write_pcap(dir + "/ccw.pcap", mirrored);
  write_pcap(dir + "/ccw_head.pcap", {mirrored.begin(), mirrored.begin() + 40});

  // Azimuth of every point of the first 40 packets, by the library in each direction.
  std::vector<std::vector<double>> by_packet[2];
  for (const Rotation r : {Rotation::clockwise, Rotation::counterclockwise}) {
    Decoder dec(Model::qt128c2x);
    dec.set_rotation(r);
    PacketPoints pts;
    PacketInfo info;
    for (std::size_t i = 0; i < 40; ++i) {
      ASSERT_EQ(dec.decode(view(mirrored[i]), info, pts), Error::ok);
      std::vector<double> az;
      for (const Point& q : pts) az.push_back(q.azimuth_deg);
      by_packet[r == Rotation::counterclockwise].push_back(az);
    }
  }
  for (const char* mode : {"ccw", "auto", "cw"}) {
    const CmdResult out = run_cli("decode " + dir + "/ccw_head.pcap --quiet --out - --rotation " + mode);
    ASSERT_EQ(out.status, 0) << mode;
    std::istringstream rows(out.out);
    std::string line;
    std::getline(rows, line);  // header
    std::size_t packet = 0, k = 0, checked = 0;
    while (std::getline(rows, line)) {
      std::vector<std::string> col;
      std::istringstream cells(line);
      for (std::string cell; std::getline(cells, cell, ',');) col.push_back(cell);
      const std::size_t p = std::stoul(col.at(1));
      if (p != packet) k = 0;
      packet = p;
      const bool ccw = std::string(mode) != "cw";
      ASSERT_LT(k, by_packet[ccw][p].size());
      EXPECT_NEAR(std::stod(col.at(5)), by_packet[ccw][p][k++], 0.0006) << mode << " packet " << p;
      ++checked;
    }
    EXPECT_GT(checked, 7000u) << mode;
  }
  // The mirror image of the clockwise capture: the blocks 10.80 deg before the cut (349.20), 2 turns
  // back, 10.40 before it (349.60): rotations 0..2, 3 frames.
  const auto frames = reckoned_frames(mirrored, Model::qt128c2x, Rotation::counterclockwise);
  EXPECT_EQ(frames.size(), 3u);
  for (const char* mode : {"ccw", "auto"}) {
    const CmdResult s = run_cli("stats " + dir + "/ccw.pcap --json --rotation " + std::string(mode));
    EXPECT_EQ(json_numbers(s.out)["frames"], 3) << mode;
  }
  const CmdResult text = run_cli("stats " + dir + "/ccw.pcap");
  EXPECT_NE(text.out.find("counterclockwise (detected)"), std::string::npos) << text.out;
}

// ---- --rotation auto from the first packet ----

struct HeadCase {
  const char* file;
  Model model;
};

void PrintTo(const HeadCase& c, std::ostream* os) { *os << model_name(c.model); }

class CliRotationAuto : public ::testing::TestWithParam<HeadCase> {};

// With --rotation auto (the default), the frames of a stream are right from its first packet,
// in either direction: the capture as recorded (clockwise) and mirrored (every block azimuth
// a -> 36000 - a: a counter-clockwise unit) are cut at several angles, among them the captures'
// own start and cuts that the first packets straddle, and every point of their first kHead
// packets must be in the frame of its own rotation by this test's reckoning: it unwraps the
// block azimuths read from the packets' bytes (each move forward in the direction the test made
// the capture spin, from the first block's distance past the cut), places each point at its
// block plus the short way to its own azimuth (the CSV's), and takes the rotation
// floor(position / 360). Frame ids must be the rotations plus one offset, the same for every
// point (a point within 0.001 degree of a cut may fall either side: the CSV has three decimals).
TEST_P(CliRotationAuto, FirstPacketsInTheFrameOfTheirRotation) {
  constexpr std::size_t kHead = 40;
  const HeadCase& c = GetParam();
  const auto recorded = pcap_payloads(c.file);
  ASSERT_GE(recorded.size(), kHead);
  const std::string dir = temp_dir();
  for (const bool cw : {true, false}) {
    std::vector<std::vector<std::uint8_t>> head;
    for (std::size_t i = 0; i < kHead; ++i) head.push_back(cw ? recorded[i] : counterclockwise_copy(recorded[i], c.model));
    const std::string path = dir + (cw ? "/cw.pcap" : "/ccw.pcap");
    write_pcap(path, head);
    auto forward = [cw](double from, double to) { return std::fmod((cw ? to - from : from - to) + 72000.0, 36000.0); };
    // Cuts, 0.01 degree: 0; 0.3 degree behind and ahead of the first block (the stream starts
    // just past the cut, or the first packets cross it); a quarter turn from the first block.
    const double a0 = block_azimuths(head[0], c.model)[0];
    const double sign = cw ? 1.0 : -1.0;
    for (const double cut_cdeg : {0.0, a0 - sign * 30.0, a0 + sign * 30.0, a0 + 9000.0}) {
      const double cut = std::fmod(cut_cdeg + 72000.0, 36000.0);
      char cut_arg[32];
      std::snprintf(cut_arg, sizeof cut_arg, "%.2f", cut / 100.0);
      const std::string what = std::string(cw ? "clockwise" : "mirrored") + " cut " + cut_arg;
      const CmdResult out = run_cli("decode " + path + " --quiet --out - --rotation auto --cut-angle " + cut_arg);
      ASSERT_EQ(out.status, 0) << what << ": " << out.err;
      // And the same rows, byte for byte, as with the direction given.
      const CmdResult set = run_cli("decode " + path + " --quiet --out - --rotation " + (cw ? "cw" : "ccw") + " --cut-angle " + cut_arg);
      EXPECT_EQ(out.out, set.out) << what;

      // Unwrapped position of every block, past the first cut.
      std::vector<std::vector<double>> block_at(kHead);
      double at = 0, last = 0;
      for (std::size_t i = 0; i < kHead; ++i) {
        for (const std::uint16_t az : block_azimuths(head[i], c.model)) {
          if (i == 0 && block_at[0].empty()) {
            at = forward(cut, az);
          } else {
            const double move = forward(last, az);
            ASSERT_LT(move, 18000.0) << "the captures only move forward";
            at += move;
          }
          last = az;
          block_at[i].push_back(at);
        }
      }

      std::istringstream rows(out.out);
      std::string line;
      std::getline(rows, line);  // header
      std::int64_t shift = 0;
      bool have_shift = false;
      std::size_t checked = 0;
      while (std::getline(rows, line)) {
        std::vector<std::string> col;
        std::istringstream cells(line);
        for (std::string cell; std::getline(cells, cell, ',');) col.push_back(cell);
        ASSERT_GE(col.size(), 6u) << line;
        const std::int64_t id = std::stoll(col[0]);
        const std::size_t packet = std::stoul(col[1]);
        const std::size_t block = std::stoul(col[2]);
        ASSERT_LT(packet, kHead);
        ASSERT_LT(block, block_at[packet].size());
        const double block_az = block_azimuths(head[packet], c.model)[block];
        const double off = std::fmod(std::stod(col[5]) * 100.0 - block_az + 54000.0, 36000.0) - 18000.0;  // clockwise, short way
        const double point_at = block_at[packet][block] + (cw ? off : -off);
        if (std::fabs(point_at - 36000.0 * std::round(point_at / 36000.0)) < 0.1) continue;  // on a cut
        const std::int64_t rotation = static_cast<std::int64_t>(std::floor(point_at / 36000.0));
        if (!have_shift) shift = id - rotation;
        have_shift = true;
        ASSERT_EQ(id - rotation, shift) << what << ": packet " << packet << " block " << block << " channel " << col[3]
                                        << ", " << point_at / 100.0 << " degrees past the first cut";
        ++checked;
      }
      EXPECT_GT(checked, 0u) << what;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Bundled, CliRotationAuto,
                         ::testing::Values(HeadCase{"pandar40p_dual.pcap", Model::pandar40p},
                                           HeadCase{"pandar64_dual.pcap", Model::pandar64},
                                           HeadCase{"qt128c2x_dual.pcap", Model::qt128c2x},
                                           HeadCase{"pandar_qt64.pcap", Model::pandar_qt64},
                                           HeadCase{"pandar_xt16.pcap", Model::pandar_xt16},
                                           HeadCase{"pandar_xt32.pcap", Model::pandar_xt32},
                                           HeadCase{"pandar_xt32m2x.pcap", Model::pandar_xt32m2x}),
                         [](const auto& i) { return std::string(model_name(i.param.model)); });

// A sensor whose direction never shows (a stationary motor: every block azimuth the same) has its
// packets held, then released in the assumed direction, clockwise: the oldest once the hold is
// full (Pipeline::kHeldPackets), the rest at the end of the input. Either way every packet's
// points come out, in packet order, as with --rotation cw: 20 packets (released while streaming)
// and 5 (all at the end).
TEST(Cli, UndecidedPacketsAreReleasedInOrder) {
  const auto real = pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_GE(real.size(), 20u);
  const std::string dir = temp_dir();
  for (const std::size_t n : {std::size_t{20}, std::size_t{5}}) {
    std::vector<std::vector<std::uint8_t>> still;
    std::size_t raw_points = 0;
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<std::uint8_t> p = real[i];
      for (std::size_t b = 0; b < 2; ++b) {
        store_le16(&p[12 + b * 514], 1000);
        for (std::size_t c = 0; c < 128; ++c) raw_points += load_le16(&p[12 + b * 514 + 2 + c * 4]) >= 2;
      }
      qt128_seal(p);
      still.push_back(p);
    }
    const std::string path = dir + "/still" + std::to_string(n) + ".pcap";
    write_pcap(path, still);
    const CmdResult automatic = run_cli("decode " + path + " --quiet --out - --rotation auto");
    const CmdResult cw = run_cli("decode " + path + " --quiet --out - --rotation cw");
    ASSERT_EQ(automatic.status, 0) << automatic.err;
    EXPECT_EQ(automatic.out, cw.out) << n << " packets";
    EXPECT_EQ(static_cast<std::size_t>(std::count(automatic.out.begin(), automatic.out.end(), '\n')), raw_points + 1)
        << n << " packets (rows and the header)";
    const CmdResult text = run_cli("stats " + path);
    EXPECT_NE(text.out.find("clockwise (assumed: not detected)"), std::string::npos) << text.out;
  }
}

TEST(Cli, PacketRangeAndRangeFilter) {
  const std::string dir = temp_dir();
  const CmdResult r = run_cli("decode " + data_path("pandar64_dual.pcap") + " --packets 10:12 --out -");
  ASSERT_EQ(r.status, 0);
  // Every row belongs to packet 10 or 11; the count equals the non-zero distances of those two.
  const auto packets = pcap_payloads("pandar64_dual.pcap");
  ASSERT_GT(packets.size(), 11u);
  std::size_t expected = 0;
  for (std::size_t k : {10u, 11u})
    for (std::size_t b = 0; b < 6; ++b)
      for (std::size_t ch = 0; ch < 64; ++ch) expected += load_le16(&packets[k][8 + b * 194 + 2 + ch * 3]) != 0;
  std::size_t rows = 0;
  std::size_t pos = r.out.find('\n') + 1;
  while (pos < r.out.size()) {
    const std::size_t end = r.out.find('\n', pos);
    const std::string row = r.out.substr(pos, end - pos);
    const std::string packet = row.substr(row.find(',') + 1, row.find(',', row.find(',') + 1) - row.find(',') - 1);
    EXPECT_TRUE(packet == "10" || packet == "11") << row;
    ++rows;
    pos = end + 1;
  }
  EXPECT_EQ(rows, expected);
  // This indoor capture sees nothing beyond 2.3 m in these packets: keep what lies within 2 m.
  const CmdResult near = run_cli("decode " + data_path("pandar64_dual.pcap") + " --packets 10:12 --max-range 2 --out -");
  std::size_t near_rows = 0;
  for (std::size_t at = near.out.find('\n') + 1; at < near.out.size(); at = near.out.find('\n', at) + 1) {
    std::string row = near.out.substr(at, near.out.find('\n', at) - at);
    for (int field = 0; field < 7; ++field) row = row.substr(row.find(',') + 1);
    EXPECT_LE(std::stod(row.substr(0, row.find(','))), 2.0);
    ++near_rows;
  }
  EXPECT_GT(near_rows, 0u);
  EXPECT_LT(near_rows, rows);
}

// ---- Outputs ----

// The data after a PCD or PLY header (`end` its last line).
std::string records(const std::string& file, const std::string& end) {
  const std::size_t at = file.find(end);
  return at == std::string::npos ? std::string() : file.substr(at + end.size());
}

// The records of a file's data section, `size` bytes each, sorted.
std::vector<std::string> sorted_records(const std::string& data, std::size_t size) {
  std::vector<std::string> out;
  for (std::size_t at = 0; at + size <= data.size(); at += size) out.push_back(data.substr(at, size));
  std::sort(out.begin(), out.end());
  return out;
}

// One PCD or PLY file for the whole capture is written as a stream: its header gives the
// capture's point count (test_golden.cpp counts 337 108) as 20 zero-padded digits, and its records
// are those of the per-frame files (whose count is known when they are written). The single file
// keeps packet order; near a cut a packet gives points to two frames, so the frames' files hold
// the same records in another order there: compared sorted.
TEST(Cli, OneCloudFileIsStreamedAndItsCountWrittenAtTheEnd) {
  const std::string dir = temp_dir();
  for (const char* format_name : {"pcd", "ply"}) {
    const std::string format = format_name;
    const std::string one = dir + "/one." + format;
    const CmdResult r = run_cli("decode " + data_path("qt128c2x_dual.pcap") + " --quiet --format " + format + " --out " + one);
    ASSERT_EQ(r.status, 0) << r.err;
    ASSERT_EQ(run_cli("decode " + data_path("qt128c2x_dual.pcap") + " --quiet --per-frame --format " + format + " --out " +
                  dir + "/" + format).status, 0);
    const std::string end = format == "pcd" ? "DATA binary\n" : "end_header\n";
    std::string frames;
    for (int id = 1;; ++id) {
      char name[64];
      std::snprintf(name, sizeof name, "/frame_ip_192_168_1_201_%06d.", id);
      std::ifstream f(dir + "/" + format + name + format);
      if (!f) break;
      frames += records(read_text(dir + "/" + format + name + format), end);
    }
    const std::string text = read_text(one);
    const std::size_t record_bytes = format == "pcd" ? 27 : 23;
    EXPECT_EQ(records(text, end).size(), 337108 * record_bytes) << format;
    EXPECT_EQ(frames.size(), 337108 * record_bytes) << format;
    EXPECT_TRUE(sorted_records(records(text, end), record_bytes) == sorted_records(frames, record_bytes)) << format;
    if (format == "pcd") {
      EXPECT_NE(text.find("\nWIDTH 00000000000000337108\n"), std::string::npos);
      EXPECT_NE(text.find("\nPOINTS 00000000000000337108\n"), std::string::npos);
    } else {
      EXPECT_NE(text.find("\nelement vertex 00000000000000337108\n"), std::string::npos);
    }
  }
  std::filesystem::remove_all(dir);  // 36 MB of clouds
}

// A pipe cannot take a PCD or PLY file (its header's count is written last): a usage error that
// says so, before any decoding.
TEST(Cli, OneCloudFileRefusesAPipe) {
  for (const char* format : {"pcd", "ply"}) {
    const CmdResult r = run_cli("decode " + data_path("qt128c2x_dual.pcap") + " --quiet --format " + format + " --out /dev/stdout");
    EXPECT_EQ(r.status, 1) << format;
    EXPECT_TRUE(r.out.empty()) << format;
    EXPECT_NE(r.err.find("give a file"), std::string::npos) << r.err;
  }
}

// An output that cannot be created is an I/O failure: exit 2, whatever the format.
TEST(Cli, OutputThatCannotBeCreatedExits2) {
  const std::string capture = data_path("qt128c2x_dual.pcap");
  for (const char* out : {"--per-frame --out /nonexistent-hesai/frames", "--format pcd --out /nonexistent-hesai/x.pcd",
                                "--format ply --out /nonexistent-hesai/x.ply", "--out /nonexistent-hesai/x.csv",
                                "--format png --out /nonexistent-hesai/x.png"}) {
    const CmdResult r = run_cli("decode " + capture + " --quiet " + std::string(out));
    EXPECT_EQ(r.status, 2) << out;
    EXPECT_NE(r.err.find("/nonexistent-hesai/"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("--help"), std::string::npos) << "not a usage error: " << r.err;
  }
}

// stats on a capture it cannot read prints the error alone: no table of zeros on stdout.
// decode of one leaves an existing output as it was.
TEST(Cli, UnreadableCaptureGivesOnlyItsError) {
  for (const std::string& input : {std::string("/nonexistent-hesai/file.pcap"), data_path("calibration/pandar64_unit_a_angles.csv")}) {
    for (const char* json : {"", " --json"}) {
      const CmdResult r = run_cli("stats " + input + json);
      EXPECT_EQ(r.status, 2) << input;
      EXPECT_EQ(r.out, "") << input;
      EXPECT_NE(r.err.find(input), std::string::npos) << r.err;
    }
  }
  const std::string out = temp_dir() + "/kept.csv";
  std::ofstream(out) << "kept\n";
  EXPECT_EQ(run_cli("decode /nonexistent-hesai/file.pcap --out " + out).status, 2);
  EXPECT_EQ(read_text(out), "kept\n");
}

// ---- Sensor settings: channel configuration and reflectivity mapping ----

// QT128 packets with customised channels (flags bit 6, 80 units per block: the bundled
// configuration's channels for each block's loop, as test_packet_variants.cpp builds them): without
// --channel-config every one is rejected (counted unsupported); with it, every unit with a distance
// of 2 or more is a point (distance 1 is the QT128's marker).
TEST(Cli, ChannelConfigAppliesToCustomisedPackets) {
  const auto real = pcap_payloads("qt128c2x_dual.pcap");
  std::vector<std::size_t> loops[2];
  for (const auto& row : read_numeric_csv("calibration/qt128c2x_channel_config.csv").rows)
    if (row.size() == 2)
      for (std::size_t k = 0; k < 2; ++k) loops[k].push_back(static_cast<std::size_t>(row[k]) - 1);
  ASSERT_EQ(loops[0].size(), 80u);
  std::vector<std::vector<std::uint8_t>> out;
  long long points = 0;
  for (std::size_t i = 0; i < 100; ++i) {
    const auto& p = real[i];
    const std::size_t loop = (p[1066] & 1) ? 0 : 1;  // dual return: both blocks fire block 1's sequence
    out.push_back(qt128_rebuild(p, 80, 0x5D, {loops[loop], loops[loop]}));
    for (std::size_t b = 0; b < 2; ++b)
      for (std::size_t j = 0; j < 80; ++j) points += load_le16(&out.back()[12 + b * 322 + 2 + j * 4]) >= 2;
  }
  const std::string dir = temp_dir();
  write_pcap(dir + "/custom.pcap", out);
  auto j = json_numbers(run_cli("stats " + dir + "/custom.pcap --json").out);
  EXPECT_EQ(j["packets"], 100);
  EXPECT_EQ(j["unsupported"], 100);  // channel_config_required
  EXPECT_EQ(j["points"], 0);
  const std::string config = " --channel-config " + data_path("calibration/qt128c2x_channel_config.csv");
  const CmdResult r = run_cli("stats " + dir + "/custom.pcap --json" + config);
  ASSERT_EQ(r.status, 0);
  j = json_numbers(r.out);
  EXPECT_EQ(j["unsupported"], 0);
  EXPECT_EQ(j["malformed"], 0);
  EXPECT_GT(points, 0);
  EXPECT_EQ(j["points"], points);
  // The real (uncustomised) capture decodes as before with the file given.
  EXPECT_EQ(json_numbers(run_cli("stats " + data_path("qt128c2x_dual.pcap") + " --json" + config).out)["points"], 337108);
  // A QT128 file for a Pandar64 capture, and a BlockNum the QT128 does not send: configuration errors.
  EXPECT_EQ(run_cli("stats " + data_path("pandar64_dual.pcap") + config).status, 1);
  const auto bytes = read_file(data_path("calibration/qt128c2x_channel_config.csv"));
  std::string text(bytes.begin(), bytes.end());
  const std::size_t at = text.find("BlockNum,2");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 10, "BlockNum,3");
  std::ofstream(dir + "/blocks3.csv") << text;
  EXPECT_EQ(run_cli("stats " + data_path("qt128c2x_dual.pcap") + " --channel-config " + dir + "/blocks3.csv").status, 1);
}

// --reflectivity nonlinear: a Pandar64's intensity is its reflectivity byte mapped by the manual's
// Appendix D (as typed in tests/pandar64_manual.h, in hundredths of a percent) to the nearest whole
// percent, halves up; 255, which the manual leaves without a value, stays 255. raw (the default)
// is the byte as sent. No other manual gives a mapping.
TEST(Cli, ReflectivityMapping) {
  const auto packets = pcap_payloads("pandar64_dual.pcap");
  for (const bool nonlinear : {false, true}) {
    const CmdResult r = run_cli("decode " + data_path("pandar64_dual.pcap") + " --packets 0:2 --out -" +
                            (nonlinear ? " --reflectivity nonlinear" : ""));
    ASSERT_EQ(r.status, 0);
    std::size_t rows = 0, mapped = 0;
    std::size_t pos = r.out.find('\n') + 1;
    while (pos < r.out.size()) {
      const std::size_t end = r.out.find('\n', pos);
      std::vector<std::string> f;
      std::stringstream ss(r.out.substr(pos, end - pos));
      for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
      pos = end + 1;
      ASSERT_EQ(f.size(), 14u);
      const std::size_t packet = std::stoul(f[1]), block = std::stoul(f[2]), channel = std::stoul(f[3]);
      const std::uint8_t raw = packets[packet][8 + block * 194 + 2 + (channel - 1) * 3 + 2];
      const int want = !nonlinear || raw == 255 ? raw : (pandar64_manual::kNonlinearReflectivityHundredths[raw] + 50) / 100;
      ASSERT_EQ(std::stoi(f[11]), want) << "raw " << int(raw);
      ++rows;
      mapped += want != raw;
    }
    EXPECT_GT(rows, 500u);
    if (nonlinear) {
      EXPECT_GT(mapped, rows / 4);  // 181 of 545 rows change (a byte of 0 maps to 0)
    }
  }
  EXPECT_EQ(run_cli("stats " + data_path("qt128c2x_dual.pcap") + " --reflectivity nonlinear").status, 1);
  EXPECT_EQ(run_cli("stats " + data_path("pandar40p_dual.pcap") + " --reflectivity nonlinear").status, 1);
  EXPECT_EQ(run_cli("stats " + data_path("pandar64_dual.pcap") + " --reflectivity linear").status, 1);
  EXPECT_EQ(run_cli("stats " + data_path("qt128c2x_dual.pcap") + " --reflectivity raw").status, 0);
}

// ---- Built captures with known faults ----

TEST(Cli, StatsCountsDropsDuplicatesLateAndCrcErrors) {
  const auto real = pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_FALSE(real.empty());
  const std::uint32_t base = load_le32(&real[0][1087]);
  // Sequence numbers 0..19 sent as: 0 1 2 4 5 3 6 6 7 [8 9 10 lost] 11 .. 19, with packet 15's body
  // corrupted; then 10019 10020, a jump beyond the tracker's 4096-number window: a restart.
  std::vector<std::vector<std::uint8_t>> out;
  auto packet_with_seq = [&](std::uint32_t k) {
    auto p = real[k % real.size()];
    store_le32(&p[1087], base + k);
    qt128_seal(p);  // CRC3 covers the sequence number
    return p;
  };
  for (std::uint32_t k : {0u, 1u, 2u, 4u, 5u, 3u, 6u, 6u, 7u, 11u, 12u, 13u, 14u, 15u, 16u, 17u, 18u, 19u, 10019u, 10020u}) {
    auto p = packet_with_seq(k);
    if (k == 15) p[100] ^= 0x40;  // CRC1 fails
    out.push_back(p);
  }
  std::vector<std::uint8_t> junk(300, 0xAB);  // not a Hesai packet
  out.push_back(junk);
  const std::string dir = temp_dir();
  write_pcap(dir + "/faults.pcap", out);
  const CmdResult r = run_cli("stats " + dir + "/faults.pcap --json");
  ASSERT_EQ(r.status, 0);
  auto j = json_numbers(r.out);
  EXPECT_EQ(j["packets"], 21);
  EXPECT_EQ(j["crc_errors"], 1);   // packet 15
  EXPECT_EQ(j["malformed"], 1);    // the junk
  EXPECT_EQ(j["lost"], 4);         // 8, 9, 10, and 15 whose packet failed its CRC (3 arrived late: not lost)
  EXPECT_EQ(j["reordered"], 1);    // 3
  EXPECT_EQ(j["duplicates"], 1);   // the second 6
  EXPECT_EQ(j["sequence_resyncs"], 1);  // 10019: the 9999 numbers skipped are not counted lost
  EXPECT_EQ(j["signature_unverified"], 0);
  EXPECT_NE(r.out.find("\"QT128C2X\":19"), std::string::npos) << r.out;
}

std::string hex32(const std::uint8_t* b) {
  std::string s;
  char h[3];
  for (int i = 0; i < 32; ++i) {
    std::snprintf(h, sizeof h, "%02x", b[i]);
    s += h;
  }
  return s;
}

// A QT128 capture of 11 packets: 6 signed under a session key derived from a secret and two
// randoms, 2 with a flipped signature bit, 3 unsigned (all-zero signature).
struct SignedCapture {
  std::string path, secret, key_hex, lidar_hex, client_hex;
  std::string randoms() const { return " --lidar-random " + lidar_hex + " --client-random " + client_hex; }
};
SignedCapture make_signed_capture() {
  const auto real = pcap_payloads("qt128c2x_dual.pcap");
  SignedCapture c;
  EXPECT_GT(real.size(), 10u);
  if (real.size() <= 10) return c;  // a missing capture: the callers' checks fail
  std::uint8_t lidar[32], client[32], key[32];
  for (int i = 0; i < 32; ++i) {
    lidar[i] = static_cast<std::uint8_t>(0x10 + i);
    client[i] = static_cast<std::uint8_t>(0x80 + i);
  }
  c.secret = "hesai-secret-01";
  EXPECT_EQ(hesai_session_key(ByteView{reinterpret_cast<const std::uint8_t*>(c.secret.data()), c.secret.size()}, lidar,
                              client, key),
            Error::ok);
  std::vector<std::vector<std::uint8_t>> out;
  for (std::size_t k = 0; k < 11; ++k) {
    auto p = real[k];
    if (k < 8) qt128_seal(p, key);
    if (k == 6 || k == 7) p[1100] ^= 0x04;
    out.push_back(p);
  }
  c.path = temp_dir() + "/signed.pcap";
  write_pcap(c.path, out);
  c.key_hex = hex32(key);
  c.lidar_hex = hex32(lidar);
  c.client_hex = hex32(client);
  return c;
}

TEST(Cli, StatsCountsSignatures) {
  const SignedCapture c = make_signed_capture();
  auto j = json_numbers(run_cli("stats " + c.path + " --json --secret " + c.secret + c.randoms()).out);
  EXPECT_EQ(j["signature_valid"], 6);
  EXPECT_EQ(j["signature_invalid"], 2);
  EXPECT_EQ(j["signature_missing"], 3);
  EXPECT_EQ(j["unsigned_rejected"], 3);  // the 3 unsigned packets the test built, refused
  EXPECT_EQ(j["unsigned_accepted"], 0);
  EXPECT_EQ(j["signature_unverified"], 0);
  const long long points_checked = j["points"];

  j = json_numbers(run_cli("stats " + c.path + " --json --session-key " + c.key_hex + " --allow-unsigned").out);
  EXPECT_EQ(j["signature_valid"], 6);
  EXPECT_EQ(j["signature_invalid"], 2);
  EXPECT_EQ(j["signature_missing"], 3);  // accepted, and still counted as unsigned
  EXPECT_EQ(j["unsigned_accepted"], 3);
  EXPECT_EQ(j["unsigned_rejected"], 0);
  EXPECT_GT(j["points"], points_checked);  // the 3 unsigned packets now contribute points

  j = json_numbers(run_cli("stats " + c.path + " --json").out);  // no key
  EXPECT_EQ(j["signature_unverified"], 8);
  EXPECT_EQ(j["signature_valid"], 0);
  EXPECT_EQ(j["signature_invalid"], 0);
}

// A signed packet sent again in the same session is refused and counted as replayed (issue #44,
// finding 1): 1100 QT128 packets signed in order, then packet 1090 again (in the window, already
// accepted), packets 0 and 5 again (more than kReplayWindow = 1024 numbers behind the newest,
// 1099) and packet 1095 again: four replays. The decode writes exactly the unique packets' points
// (the CSV of the capture without the replays); without a key the same packets are not judged.
TEST(Cli, ReplayedSignedPacketsAreRefused) {
  const auto real = pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_GE(real.size(), 1100u);
  std::uint8_t key[32];
  for (int i = 0; i < 32; ++i) key[i] = static_cast<std::uint8_t>(0x40 + i);
  std::vector<std::vector<std::uint8_t>> unique;
  for (std::size_t k = 0; k < 1100; ++k) {
    unique.push_back(real[k]);
    qt128_seal(unique.back(), key);
  }
  auto replayed = unique;
  for (std::size_t k : {std::size_t{1090}, std::size_t{0}, std::size_t{5}, std::size_t{1095}}) replayed.push_back(unique[k]);
  const std::string dir = temp_dir();
  write_pcap(dir + "/unique.pcap", unique);
  write_pcap(dir + "/replayed.pcap", replayed);
  const std::string with_key = " --session-key " + hex32(key);

  auto j = json_numbers(run_cli("stats " + dir + "/replayed.pcap --json" + with_key).out);
  auto u = json_numbers(run_cli("stats " + dir + "/unique.pcap --json" + with_key).out);
  EXPECT_EQ(u["signature_valid"], 1100);
  EXPECT_EQ(u["replayed"], 0);
  EXPECT_EQ(j["packets"], 1104);
  EXPECT_EQ(j["replayed"], 4);
  EXPECT_EQ(j["signature_valid"], 1100);  // the replays verify, but are not counted as valid packets
  EXPECT_EQ(j["points"], u["points"]);
  EXPECT_EQ(j["duplicates"], 0);  // refused before the loss accounting
  const CmdResult a = run_cli("decode " + dir + "/replayed.pcap --out -" + with_key);
  const CmdResult b = run_cli("decode " + dir + "/unique.pcap --out -" + with_key);
  ASSERT_EQ(a.status, 0) << a.err;
  EXPECT_GT(b.out.size(), 100000u);
  EXPECT_TRUE(a.out == b.out) << "the replays' points were written";
  // Without a key nothing is verified, so nothing is judged a replay: the copies are duplicates.
  j = json_numbers(run_cli("stats " + dir + "/replayed.pcap --json").out);
  EXPECT_EQ(j["replayed"], 0);
  EXPECT_EQ(j["signature_unverified"], 1104);
}

// The functional-safety stream of safety_stream.h (each lidar state, faults, one stall), as a
// capture: stats --json and the text summary report what the test built.
TEST(Cli, StatsReportsFunctionalSafety) {
  const SafetyStream s = build_safety_stream();
  ASSERT_FALSE(s.packets.empty());
  const SafetyExpect& e = s.expect;
  const std::string dir = temp_dir();
  write_pcap(dir + "/safety.pcap", s.packets);
  const CmdResult r = run_cli("stats " + dir + "/safety.pcap --json");
  ASSERT_EQ(r.status, 0);
  auto j = json_numbers(r.out);
  EXPECT_EQ(j["packets"], static_cast<long long>(s.packets.size()));
  EXPECT_EQ(j["crc_errors"], 0);  // CRC2 re-sealed
  EXPECT_EQ(j["fs_packets"], static_cast<long long>(e.packets));
  const char* const states[8] = {"init", "normal", "report_fault", "pre_performance_degradation",
                                 "performance_degradation", "pre_shutdown", "shutdown", "standby"};
  for (std::size_t st = 0; st < 8; ++st) EXPECT_EQ(j[states[st]], static_cast<long long>(e.states[st])) << states[st];
  EXPECT_EQ(j["fs_current_fault"], static_cast<long long>(e.current));
  EXPECT_EQ(j["fs_past_fault"], static_cast<long long>(e.past));
  EXPECT_EQ(j["fs_reserved_fault_type"], static_cast<long long>(e.reserved));
  EXPECT_EQ(j["fs_last_fault_code"], e.last_code);
  EXPECT_EQ(j["fs_last_fault_id"], e.last_id);
  EXPECT_EQ(j["fs_last_fault_total"], e.last_total);
  EXPECT_EQ(j["fs_counter_stalls"], static_cast<long long>(e.stalls));
  EXPECT_EQ(e.stalls, 1u);

  const CmdResult t = run_cli("stats " + dir + "/safety.pcap");
  ASSERT_EQ(t.status, 0);
  EXPECT_EQ(text_number(t.out, "fs_packets"), static_cast<long long>(e.packets)) << t.out;
  for (std::size_t st = 0; st < 8; ++st) EXPECT_EQ(text_number(t.out, states[st]), static_cast<long long>(e.states[st])) << t.out;
  EXPECT_EQ(text_number(t.out, "fs_current_fault"), static_cast<long long>(e.current));
  EXPECT_EQ(text_number(t.out, "fs_past_fault"), static_cast<long long>(e.past));
  EXPECT_EQ(text_number(t.out, "fs_counter_stalls"), static_cast<long long>(e.stalls));
  EXPECT_NE(t.out.find("fs_last_fault         code " + std::to_string(e.last_code) + ", " + std::to_string(e.last_id) +
                       " of " + std::to_string(e.last_total) + "\n"),
            std::string::npos) << t.out;
}

// Pandar64 packets with the high-temperature shutdown flag set in some, and GPS packets of both
// layouts: locked, PPS unlocked, NMEA unlocked (status NUL), void position.
TEST(Cli, StatsReportsHighTemperatureAndGpsLock) {
  auto p64 = pcap_payloads("pandar64_dual.pcap");
  ASSERT_GE(p64.size(), 200u);
  const std::size_t flag = 8 + 6 * 194 + 5;  // Pandar64 manual 3.1.2.3: tail after 5 reserved bytes
  std::vector<std::vector<std::uint8_t>> out;
  long long hot = 0;
  for (std::size_t i = 0; i < 200; ++i) {
    if (i % 9 == 4) {
      p64[i][flag] = 0x01;
      ++hot;
    }
    out.push_back(p64[i]);
  }
  struct Gps {
    bool p40;
    std::uint8_t status, pps;
  };
  // unlocked: PPS 0 or status NUL; position invalid: 'V' (or GPGGA '0').
  const Gps gps[] = {{false, 'A', 1}, {false, 'A', 0}, {false, 0, 1}, {false, 'V', 1}, {true, 'A', 1}, {true, 'V', 0}};
  for (std::size_t k = 0; k < std::size(gps); ++k) {  // one GPS packet after every 30 point-cloud packets
    GpsBytes b = gps[k].p40 ? gps_rmc40() : gps_rmc64();
    b[506] = gps[k].status;
    b[507] = gps[k].pps;
    out.insert(out.begin() + static_cast<long>(31 * k + 30), std::vector<std::uint8_t>(b.begin(), b.end()));
  }
  const std::string dir = temp_dir();
  write_pcap(dir + "/status.pcap", out);
  auto j = json_numbers(run_cli("stats " + dir + "/status.pcap --json").out);
  EXPECT_EQ(j["packets"], 206);
  EXPECT_EQ(j["gps_packets"], 6);
  EXPECT_EQ(j["high_temperature"], hot);
  EXPECT_EQ(j["gps_unlocked"], 3);          // {'A', 0}, {0, 1}, {'V', 0}
  EXPECT_EQ(j["gps_position_invalid"], 2);  // the two 'V'
  EXPECT_EQ(j["fs_packets"], 0);
  const CmdResult t = run_cli("stats " + dir + "/status.pcap");
  EXPECT_EQ(text_number(t.out, "high_temperature"), hot) << t.out;
  EXPECT_EQ(text_number(t.out, "gps_unlocked"), 3) << t.out;
  EXPECT_EQ(text_number(t.out, "gps_position_invalid"), 2) << t.out;
}

// Writes `text` to `path` with permission bits `mode` (chmod, so the umask does not interfere).
void write_key_file(const std::string& path, const std::string& text, mode_t mode) {
  std::ofstream(path, std::ios::binary) << text;
  ASSERT_EQ(chmod(path.c_str(), mode), 0);
}

// Every way of giving the key verifies the signed capture as the --session-key flag does (6 valid,
// 2 invalid, 3 missing); the command-line flags warn and name the safer ways; no output ever
// holds the key or the secret.
TEST(Cli, KeysFromFilesAndEnvironmentVerifyAsTheFlags) {
  const SignedCapture c = make_signed_capture();
  const std::string dir = temp_dir();
  write_key_file(dir + "/key", c.key_hex + "\n", 0600);
  write_key_file(dir + "/key_crlf", c.key_hex + "\r\nsecond line\n", 0600);
  write_key_file(dir + "/key_no_newline", c.key_hex, 0400);
  write_key_file(dir + "/secret", c.secret + "\n", 0600);
  struct Case {
    std::string args, env;
    const char* warning;  // a text the warning must hold, or nullptr: stderr stays empty
    std::vector<std::string> names;  // what the warning must name
  };
  const std::vector<Case> cases = {
      {"--session-key " + c.key_hex, "", "--session-key puts key material on the command line",
       {"--session-key-file", "HESAI_SESSION_KEY"}},
      {"--secret " + c.secret + c.randoms(), "", "--secret puts key material on the command line",
       {"--secret-file", "HESAI_SECRET"}},
      {"--session-key-file " + dir + "/key", "", nullptr, {}},
      {"--session-key-file " + dir + "/key_crlf", "", nullptr, {}},
      {"--session-key-file " + dir + "/key_no_newline", "", nullptr, {}},
      {"--secret-file " + dir + "/secret" + c.randoms(), "", nullptr, {}},
      {"", "HESAI_SESSION_KEY=" + c.key_hex, nullptr, {}},
      {"" + c.randoms(), "HESAI_SECRET=" + c.secret, nullptr, {}},
      // A key option takes precedence over the environment (here a wrong key).
      {"--session-key-file " + dir + "/key", "HESAI_SESSION_KEY=" + std::string(64, '0'), nullptr, {}},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.args + " " + k.env);
    const CmdResult r = run_cli("stats " + c.path + " --json --quiet " + k.args, k.env);
    ASSERT_EQ(r.status, 0) << r.err;
    auto j = json_numbers(r.out);
    EXPECT_EQ(j["signature_valid"], 6);
    EXPECT_EQ(j["signature_invalid"], 2);
    EXPECT_EQ(j["signature_missing"], 3);
    EXPECT_EQ(j["signature_unverified"], 0);
    if (k.warning == nullptr) {
      EXPECT_EQ(r.err, "");
    } else {
      EXPECT_NE(r.err.find(std::string("hesai: warning: ") + k.warning), std::string::npos) << r.err;
      for (const std::string& name : k.names) EXPECT_NE(r.err.find(name), std::string::npos) << name << ": " << r.err;
    }
    for (const std::string* secret : {&c.key_hex, &c.secret}) {
      EXPECT_EQ(r.err.find(*secret), std::string::npos) << r.err;
      EXPECT_EQ(r.out.find(*secret), std::string::npos) << r.out;
    }
  }
  std::filesystem::remove_all(dir);
}

// A key file that group or others may read is used, with a warning (as ssh warns of a private
// key file); mode 0600 or 0400 gets none.
TEST(Cli, KeyFileReadableByOthersWarns) {
  const SignedCapture c = make_signed_capture();
  const std::string file = temp_dir() + "/key";
  for (const mode_t mode : {0644u, 0640u, 0604u, 0660u, 0600u, 0400u}) {
    SCOPED_TRACE(mode);
    write_key_file(file, c.key_hex + "\n", mode);
    const CmdResult r = run_cli("stats " + c.path + " --json --quiet --session-key-file " + file);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(json_numbers(r.out)["signature_valid"], 6);
    if ((mode & 077) != 0) {
      char text[16];
      std::snprintf(text, sizeof text, "%04o", static_cast<unsigned>(mode));
      EXPECT_NE(r.err.find("hesai: warning: key file '" + file + "' is accessible by group or others (mode " + text + ")"),
                std::string::npos) << r.err;
    } else {
      EXPECT_EQ(r.err, "");
    }
  }
  std::remove(file.c_str());
}

// Ambiguous, malformed or unreadable keys: usage errors (1), an unreadable key file an I/O failure
// (2); no message shows what the file or variable held.
TEST(Cli, KeyErrors) {
  const SignedCapture c = make_signed_capture();
  const std::string dir = temp_dir();
  write_key_file(dir + "/key", c.key_hex + "\n", 0600);
  const std::string almost = c.key_hex.substr(0, 63) + "g";  // not hex
  write_key_file(dir + "/bad", almost + "\n", 0600);
  write_key_file(dir + "/empty", "", 0600);
  write_key_file(dir + "/secret", c.secret + "\n", 0600);
  const std::string short_secret = "short77";  // 7 characters: HKDF input the sensor refuses
  write_key_file(dir + "/short", short_secret + "\n", 0600);
  struct Case {
    std::string args, env;
    int status;
  };
  const std::vector<Case> cases = {
      {"--session-key-file " + dir + "/key --secret-file " + dir + "/secret" + c.randoms(), "", 1},
      {"--session-key-file " + dir + "/key --session-key-file " + dir + "/key", "", 1},
      {"--session-key " + c.key_hex + " --secret " + c.secret + c.randoms(), "", 1},
      {"", "HESAI_SESSION_KEY=" + c.key_hex + " HESAI_SECRET=" + c.secret, 1},
      {"--session-key-file " + dir + "/bad", "", 1},
      {"--session-key-file " + dir + "/empty", "", 1},
      {"", "HESAI_SESSION_KEY=" + almost, 1},
      {"--secret-file " + dir + "/secret", "", 1},  // no randoms
      {"", "HESAI_SECRET=" + c.secret, 1},          // no randoms
      {"--session-key-file " + dir + "/key" + c.randoms(), "", 1},  // randoms without a secret
      {"--secret-file " + dir + "/short" + c.randoms(), "", 1},
      {"--session-key-file " + dir + "/missing", "", 2},
      {"--secret-file " + dir + c.randoms(), "", 2},  // a directory
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.args + " " + k.env);
    const CmdResult r = run_cli("stats " + c.path + " --json " + k.args, k.env);
    EXPECT_EQ(r.status, k.status) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_NE(r.err.find("hesai stats: "), std::string::npos) << r.err;
    for (const std::string* secret : {&almost, &c.secret, &short_secret}) EXPECT_EQ(r.err.find(*secret), std::string::npos) << r.err;
  }
  std::filesystem::remove_all(dir);
}

// ---- Live: replay into listen on 127.0.0.1 ----

// A key given on the command line is wiped from the program's argv once read: a running
// `listen` no longer shows it in /proc/PID/cmdline (it did for the moment before).
TEST(Cli, CommandLineKeyLeavesTheProcessArguments) {
#if defined(HESAI_CLI_EMULATOR)
  GTEST_SKIP() << "/proc/PID/cmdline shows the emulator's own arguments";
#endif
  const SignedCapture c = make_signed_capture();
  const int port = free_udp_port();
  ASSERT_NE(port, 0);
  const std::string port_text = std::to_string(port);
  std::vector<std::string> words = {HESAI_CLI_PATH, "listen", "--bind", "127.0.0.1", "--port", port_text, "--gps-port", "0",
                                    "--seconds", "20", "--quiet", "--session-key", c.key_hex};
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(&w[0]);
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, HESAI_CLI_PATH, &actions, nullptr, argv.data(), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  const bool listening = wait_for_listener(port);  // the options were read before the socket opened
  const std::string cmdline = read_text("/proc/" + std::to_string(pid) + "/cmdline");
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(listening);
  EXPECT_NE(cmdline.find("--session-key"), std::string::npos);
  EXPECT_EQ(cmdline.find(c.key_hex), std::string::npos);
  EXPECT_EQ(cmdline.find(c.key_hex.substr(0, 8)), std::string::npos);
}

// Starts `listen LISTEN_OPTIONS --port P --gps-port 0 --count 1800 --seconds 30 --json --quiet`,
// waits until it is bound to `bound`:P, replays the QT128 capture (1800 packets) to `to_host`:P
// at 4 times its pace with REPLAY_OPTIONS, and returns what listen printed.
std::string replay_into_listen(const std::string& listen_options, const char* bound, const std::string& to_host,
                               const std::string& replay_options = "", bool json = true) {
  const int port = free_udp_port();
  EXPECT_NE(port, 0);
  const std::string listen = cli() + " listen " + listen_options + " --port " + std::to_string(port) +
                             " --gps-port 0 --count 1800 --seconds 30" + (json ? " --json" : "") + " --quiet 2>/dev/null";
  FILE* l = popen(listen.c_str(), "r");
  if (l == nullptr) {
    ADD_FAILURE() << "cannot start " << listen;
    return "";
  }
  EXPECT_TRUE(wait_for_listener(port, bound));
  const CmdResult sent = run_cli("replay " + data_path("qt128c2x_dual.pcap") + " --to " + to_host + ":" +
                             std::to_string(port) + " --rate 4 --quiet " + replay_options);
  EXPECT_EQ(sent.status, 0) << sent.err;
  std::string out;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, l)) > 0) out.append(buf, n);
  EXPECT_EQ(WEXITSTATUS(pclose(l)), 0);
  return out;
}

// What listen printed (`out`, JSON) after replay_into_listen: the whole capture, every counter as
// `stats` gives it for the file.
void expect_whole_capture(const std::string& out) {
  auto live = json_numbers(out);
  auto file = json_numbers(run_cli("stats " + data_path("qt128c2x_dual.pcap") + " --json").out);
  EXPECT_EQ(live["packets"], 1800) << out;
  EXPECT_EQ(live["points"], file["points"]);
  EXPECT_EQ(live["frames"], file["frames"]);
  EXPECT_EQ(live["lost"], 0);
  EXPECT_EQ(live["crc_errors"], 0);
  // The functional-safety counters travel with the packets' own times: the same as from the file.
  for (const char* key : {"fs_packets", "init", "fs_counter_stalls", "fs_current_fault", "high_temperature", "gps_unlocked"})
    EXPECT_EQ(live[key], file[key]) << key;
  EXPECT_EQ(live["init"], 1800);
}

TEST(Cli, ListenReceivesEveryReplayedPacket) {
  const std::string out = replay_into_listen("--bind 127.0.0.1", "127.0.0.1", "127.0.0.1");
  expect_whole_capture(out);
  // The JSON has the text summary's kernel_drops too: 0 with every packet received, null where the
  // receive path cannot know it (the portable path), never a 0 it does not know.
  const char* drops = hesai::port::UdpReceiver::kernel_drops_known() ? "\"kernel_drops\":0," : "\"kernel_drops\":null,";
  EXPECT_NE(out.find(drops), std::string::npos) << out;
}

// Every count listen's text summary shows is in its JSON under the same name (issue #44, finding 8:
// the JSON, which monitoring reads, once lacked kernel_drops). The text's lines at the first
// indent, but for the five that are not counts and whose JSON differs (first_time and last_time
// are first_time_ns and last_time_ns; spin_rate, rotation and return_mode are words).
TEST(Cli, ListenJsonHasEveryCountOfTheText) {
  const std::string text = replay_into_listen("--bind 127.0.0.1", "127.0.0.1", "127.0.0.1", "", false);
  const std::string json = replay_into_listen("--bind 127.0.0.1", "127.0.0.1", "127.0.0.1");
  std::vector<std::string> keys;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
    if (line.size() > 2 && line.compare(0, 2, "  ") == 0 && line[2] != ' ') keys.push_back(line.substr(2, line.find(' ', 2) - 2));
  EXPECT_GT(keys.size(), 30u) << text;
  for (const char* k : {"kernel_drops", "foreign_packets", "foreign_model_packets", "session_restarts", "replayed"})
    EXPECT_NE(std::find(keys.begin(), keys.end(), k), keys.end()) << k << " not in the text:\n" << text;
  for (const std::string& k : keys) {
    if (k == "first_time" || k == "last_time" || k == "spin_rate" || k == "rotation" || k == "return_mode") continue;
    EXPECT_NE(json.find("\"" + k + "\":"), std::string::npos) << k << " is in the text, not in the JSON:\n" << json;
  }
}

// `listen --multicast` joins the group on the --bind interface and receives what `replay` sends
// to the group through 127.0.0.1: every packet of the capture, decoded as from the file. Both
// processes in a network namespace of the test's own where it can make one (root: CI), else on
// the host's loopback.
TEST(Cli, ListenJoinsAMulticastGroup) {
  const char* group = "239.255.14.2";
  std::string why;
  const auto where = multicast_loopback(group, [&] {
    expect_whole_capture(replay_into_listen(std::string("--multicast ") + group + " --bind 127.0.0.1", group, group,
                                            "--multicast-if 127.0.0.1"));
  }, why);
  if (where == MulticastNet::none) GTEST_SKIP() << why;
  RecordProperty("network", multicast_net_name(where));
  std::printf("ran in %s\n", multicast_net_name(where));
}

// A group outside 224.0.0.0/4 is a usage error (exit 1) naming it; so is --multicast-if for a
// destination that is not a group, and --rcvbuf that is not a byte count the socket can take.
TEST(Cli, MulticastAndReceiveBufferUsageErrors) {
  for (const char* group : {"10.1.2.3", "240.0.0.1", "223.255.255.255", "group"}) {
    const CmdResult r = run_cli(std::string("listen --multicast ") + group + " --port 0 --seconds 1");
    EXPECT_EQ(r.status, 1) << group;
    EXPECT_NE(r.err.find(std::string("'") + group + "'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("multicast"), std::string::npos) << r.err;
  }
  for (const char* bytes : {"0", "-1", "2147483648", "1k"}) {
    const CmdResult r = run_cli(std::string("listen --rcvbuf ") + bytes + " --port 0 --seconds 1");
    EXPECT_EQ(r.status, 1) << bytes;
    EXPECT_NE(r.err.find("--rcvbuf"), std::string::npos) << r.err;
  }
  const CmdResult r = run_cli("replay " + data_path("qt128c2x_dual.pcap") + " --to 127.0.0.1:9 --multicast-if 127.0.0.1");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("multicast"), std::string::npos) << r.err;
}

// `listen --rcvbuf` prints the receive buffer the kernel granted: min(request, net.core.rmem_max)
// usable bytes, Linux reporting twice that (socket(7)); above rmem_max it warns, even with
// --quiet, with the sysctl that would allow the request.
TEST(Cli, ListenReportsTheReceiveBuffer) {
#if !defined(__linux__)
  GTEST_SKIP() << "net.core.rmem_max and the doubled report are Linux's";
#endif
  const std::size_t limit = rmem_max();
  if (limit == 0) GTEST_SKIP() << "/proc/sys/net/core/rmem_max is not readable";
  const std::size_t small = std::min<std::size_t>(65536, limit), big = limit + 1024 * 1024;
  const std::string common = " --bind 127.0.0.1 --port 0 --gps-port 0 --seconds 0.2";
  const CmdResult granted = run_cli("listen --rcvbuf " + std::to_string(small) + common);
  EXPECT_EQ(granted.status, 0) << granted.err;
  EXPECT_NE(granted.err.find("receive buffer " + std::to_string(small) + " bytes (requested " + std::to_string(small) +
                             "; the kernel reports " + std::to_string(2 * small)),
            std::string::npos)
      << granted.err;
  EXPECT_EQ(granted.err.find("capped"), std::string::npos) << granted.err;
  const CmdResult capped = run_cli("listen --quiet --rcvbuf " + std::to_string(big) + common);
  EXPECT_EQ(capped.status, 0) << capped.err;
  EXPECT_NE(capped.err.find("capped the receive buffer at " + std::to_string(limit) + " bytes (requested " +
                            std::to_string(big) + ")"),
            std::string::npos)
      << capped.err;
  EXPECT_NE(capped.err.find("sysctl -w net.core.rmem_max=" + std::to_string(big)), std::string::npos) << capped.err;
}

// A bounded load test: 100 800 packets at full rate (56 loops of the QT128 capture, sequence
// numbers renumbered to count up). Whatever the kernel drops must show as `lost`: nothing
// received is unaccounted for, and nothing is invented.
// Sends one QT128 capture packet renumbered to `seq` (CRC3 covers the number) to 127.0.0.1:port.
void send_renumbered_qt128(int port, std::uint32_t seq, int from_port) {
  const auto packets = pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_FALSE(packets.empty());
  std::vector<std::uint8_t> p = packets[0];
  ASSERT_TRUE(p[11] & 1);  // flags bit 0: the tail has a UDP sequence
  store_le32(&p[qt128_offsets(p).tail + 26], seq);
  qt128_seal(p);
  hesai::port::UdpSender sender;
  sender.set_source("", static_cast<std::uint16_t>(from_port));  // the load's sender: the same sensor
  std::string error;
  ASSERT_TRUE(sender.open("127.0.0.1:" + std::to_string(port), error)) << error;
  EXPECT_TRUE(sender.send(p.data(), p.size()));
}

// The PandarXT32M2X capture replayed to a listener: its three sequence gaps (852 numbers) show
// as lost; with --renumber (protocol 6.1 has no CRC over the number) nothing is lost.
TEST(Cli, ReplayListenXt32m2x) {
  for (const bool renumbered : {false, true}) {
    const int port = free_udp_port();
    ASSERT_NE(port, 0);
    const std::string listen = cli() + " listen --bind 127.0.0.1 --port " + std::to_string(port) +
                               " --gps-port 0 --count 1815 --seconds 60 --idle 5 --json --quiet 2>/dev/null";
    FILE* l = popen(listen.c_str(), "r");
    ASSERT_NE(l, nullptr);
    ASSERT_TRUE(wait_for_listener(port));
    const CmdResult sent = run_cli("replay " + data_path("pandar_xt32m2x.pcap") + " --to 127.0.0.1:" + std::to_string(port) +
                               " --rate 20 --quiet" + (renumbered ? " --renumber" : ""));
    EXPECT_EQ(sent.status, 0);
    std::string out;
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, l)) > 0) out.append(buf, n);
    pclose(l);
    auto j = json_numbers(out);
    EXPECT_EQ(j["packets"], 1815) << out;
    EXPECT_EQ(j["malformed"], 0);
    EXPECT_EQ(j["unsupported"], 0);
    EXPECT_EQ(j["points"], 223372);
    EXPECT_EQ(j["lost"], renumbered ? 0 : 852) << out;
  }
}

TEST(Cli, LoadTestReportsLossHonestly) {
#if defined(HESAI_CLI_EMULATOR)
  GTEST_SKIP() << "full-rate load through an emulator measures the emulator: runs natively only";
#endif
  const int port = free_udp_port();
  ASSERT_NE(port, 0);
  const long long sent_packets = 56 * 1800;  // numbered 0 .. sent_packets - 1 by --renumber
  // --count: the load and one closing packet. With losses it is never reached: --idle 2 ends the
  // listener soon after the last packet, long before --seconds 120.
  const std::string listen = std::string(HESAI_CLI_PATH) + " listen --bind 127.0.0.1 --port " + std::to_string(port) +
                             " --gps-port 0 --count " + std::to_string(sent_packets + 1) +
                             " --seconds 120 --idle 2 --json --quiet 2>/dev/null";
  const auto started = std::chrono::steady_clock::now();
  FILE* l = popen(listen.c_str(), "r");
  ASSERT_NE(l, nullptr);
  ASSERT_TRUE(wait_for_listener(port));
  // The load and the last packet from one port: one sensor to the listener.
  const int from_port = free_udp_port();
  ASSERT_NE(from_port, 0);
  const CmdResult sent = run_cli("replay " + data_path("qt128c2x_dual.pcap") + " --to 127.0.0.1:" + std::to_string(port) +
                             " --rate max --loop 56 --renumber --quiet --from-port " + std::to_string(from_port));
  EXPECT_EQ(sent.status, 0);
  // Packets dropped after the last one received are invisible to any sequence tracker. Once the
  // receiver has drained its socket, one packet numbered after the load makes every drop a gap.
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  send_renumbered_qt128(port, static_cast<std::uint32_t>(sent_packets), from_port);
  std::string out;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, l)) > 0) out.append(buf, n);
  pclose(l);
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(90));
  auto j = json_numbers(out);
  ASSERT_GT(j["packets"], 0) << out;
  EXPECT_EQ(j["crc_errors"], 0);  // renumbered packets carry a re-sealed CRC3
  EXPECT_EQ(j["duplicates"], 0);
  // Numbers 0 .. sent_packets: each either received or counted lost, exactly; unless a drop was
  // longer than the tracker's window, which it reports as a resync and does not count as lost.
  if (j["sequence_resyncs"] == 0) EXPECT_EQ(j["packets"] + j["lost"], sent_packets + 1) << out;
  else EXPECT_LT(j["packets"] + j["lost"], sent_packets + 1) << out;
  RecordProperty("received", std::to_string(j["packets"]));
  RecordProperty("lost", std::to_string(j["lost"]));
  std::fprintf(stderr, "load test: %lld sent, %lld received, %lld lost\n", sent_packets + 1, j["packets"], j["lost"]);
}

// Stream health (issue #32): a Pandar64 stream without its UDP sequence (the unit's default) with
// 100 packets dropped, then dated in the year 2000, then with 9 frozen timestamps: the losses come
// from the block azimuth and the packet time (lost_by), the clock faults are counted and named.
TEST(Cli, StatsStreamHealthWithoutSequence) {
  const std::string dir = temp_dir();
  auto p = pcap_payloads("pandar64_dual.pcap");
  const auto seq = json_numbers(run_cli("stats " + data_path("pandar64_dual.pcap") + " --json").out);
  EXPECT_NE(run_cli("stats " + data_path("pandar64_dual.pcap") + " --json").out.find("\"lost_by\":\"udp_sequence\""),
            std::string::npos);
  EXPECT_EQ(seq.at("time_stalls"), 0);
  EXPECT_EQ(seq.at("time_virtual"), 0);
  EXPECT_EQ(seq.at("time_jumps"), 0);
  for (auto& q : p) q.resize(1194);  // Pandar64 manual, Chapter 3: the UDP sequence off
  p.erase(p.begin() + 700, p.begin() + 800);
  write_pcap(dir + "/dropped.pcap", p);
  CmdResult r = run_cli("stats " + dir + "/dropped.pcap --json");
  ASSERT_EQ(r.status, 0);
  auto j = json_numbers(r.out);
  EXPECT_EQ(j["lost"], 100);
  EXPECT_NE(r.out.find("\"lost_by\":\"azimuth_time\""), std::string::npos) << r.out;
  EXPECT_EQ(j["time_stalls"], 0);
  EXPECT_EQ(j["time_virtual"], 0);
  r = run_cli("stats " + dir + "/dropped.pcap");
  EXPECT_EQ(text_number(r.out, "lost"), 100) << r.out;
  EXPECT_NE(r.out.find("  lost_by               azimuth_time"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("free-running"), std::string::npos) << r.out;

  const std::size_t tail = 1172;  // Pandar64 manual 3.1.2.3: timestamp @10, date-time @16 (year first)
  for (auto& q : p) q[tail + 16] = 0;  // 2000 + 0
  for (std::size_t i = 301; i <= 309; ++i) {
    for (std::size_t b = 10; b < 14; ++b) p[i][tail + b] = p[300][tail + b];
    for (std::size_t b = 16; b < 22; ++b) p[i][tail + b] = p[300][tail + b];
  }
  write_pcap(dir + "/virtual.pcap", p);
  j = json_numbers(run_cli("stats " + dir + "/virtual.pcap --json").out);
  EXPECT_EQ(j["time_virtual"], static_cast<long long>(p.size()));
  EXPECT_EQ(j["time_stalls"], 9);
  EXPECT_EQ(j["lost"], 100);
  r = run_cli("stats " + dir + "/virtual.pcap");
  EXPECT_EQ(text_number(r.out, "time_virtual"), static_cast<long long>(p.size())) << r.out;
  EXPECT_EQ(text_number(r.out, "time_stalls"), 9) << r.out;
  EXPECT_NE(r.out.find("the unit's free-running clock, not PTP or GPS time"), std::string::npos) << r.out;
}

// Blockage markers by channel, repeated returns and IP fragments in stats (issue #32): QT128C2X
// packets with distance 1 in channel 70 of both blocks of packets 10..14 and channel 100 of block 1
// of packets 20..22 (CRCs resealed); the frame of packet 30 rewritten as an IPv4 fragment (flags
// MF), which the capture reader skips.
TEST(Cli, StatsBlockageDuplicatesFragments) {
  const std::string dir = temp_dir();
  auto p = pcap_payloads("qt128c2x_dual.pcap");
  const auto unit = [](std::size_t block, std::size_t channel) { return 12 + 514 * block + 2 + 4 * (channel - 1); };
  for (std::size_t i = 10; i < 15; ++i) {
    store_le16(&p[i][unit(0, 70)], 1);
    store_le16(&p[i][unit(1, 70)], 1);
  }
  for (std::size_t i = 20; i < 23; ++i) store_le16(&p[i][unit(0, 100)], 1);
  for (std::size_t i = 10; i < 23; ++i) hesai_test::qt128_seal(p[i]);
  write_pcap(dir + "/blocked.pcap", p);
  // write_pcap's records: 24-byte file header, then 16 + 42 + 1127 bytes each; the IPv4 flags and
  // fragment offset at frame byte 20.
  std::vector<std::uint8_t> file = read_file(dir + "/blocked.pcap");
  file[24 + 30 * (16 + 42 + 1127) + 16 + 20] = 0x20;
  std::ofstream(dir + "/blocked.pcap", std::ios::binary).write(reinterpret_cast<const char*>(file.data()),
                                                                static_cast<long>(file.size()));
  CmdResult r = run_cli("stats " + dir + "/blocked.pcap --json");
  ASSERT_EQ(r.status, 0) << r.err;
  auto j = json_numbers(r.out);
  EXPECT_EQ(j["packets"], static_cast<long long>(p.size() - 1));
  EXPECT_EQ(j["ip_fragments"], 1);
  EXPECT_EQ(j["blockage_units"], 13);
  std::string by = "[";
  for (int ch = 1; ch <= 128; ++ch) by += std::string(ch > 1 ? "," : "") + (ch == 70 ? "10" : ch == 100 ? "3" : "0");
  EXPECT_NE(r.out.find("\"blockage_by_channel\":" + by + "]"), std::string::npos) << r.out;
  EXPECT_GT(j["duplicate_returns"], 0);  // counted from the bytes in test_health.cpp
  EXPECT_EQ(j["beyond_rated_range"], 0);
  EXPECT_EQ(j["lost"], 1);  // the fragment's packet, by its UDP sequence
  r = run_cli("stats " + dir + "/blocked.pcap");
  EXPECT_EQ(text_number(r.out, "blockage_units"), 13) << r.out;
  EXPECT_NE(r.out.find("  blockage_by_channel   channel 70: 10, channel 100: 3\n"), std::string::npos) << r.out;
  EXPECT_EQ(text_number(r.out, "ip_fragments"), 1) << r.out;
  EXPECT_NE(r.out.find("warning: 1 IP fragments were skipped"), std::string::npos) << r.out;
  // A capture without fragments has no warning, and a Pandar64's array has its 64 channels.
  r = run_cli("stats " + data_path("pandar64_dual.pcap") + " --json");
  std::string zeros = "[0";
  for (int ch = 2; ch <= 64; ++ch) zeros += ",0";
  EXPECT_NE(r.out.find("\"blockage_by_channel\":" + zeros + "],"), std::string::npos) << r.out;
  EXPECT_EQ(run_cli("stats " + data_path("pandar64_dual.pcap")).out.find("warning"), std::string::npos);
}

// An azimuth FOV on a sequence-less Pandar64 (issue #32): the packets whose first block azimuth
// lies in [90, 150) degrees missing on every rotation: lost 0, and fov_gap_deg the block azimuths
// either side of the last such gap, as the test reads them.
TEST(Cli, StatsFovGapIsNotLoss) {
  const std::string dir = temp_dir();
  std::vector<std::vector<std::uint8_t>> p;
  std::uint16_t before = 0, after = 0;
  bool in_gap = false;
  for (auto q : pcap_payloads("pandar64_dual.pcap")) {
    q.resize(1194);
    const std::uint16_t az = load_le16(&q[8]);  // Pandar64 manual 3.1.2: block 1's azimuth after the 8-byte header
    if (az >= 9000 && az < 15000) {
      if (!in_gap && !p.empty()) before = load_le16(&p.back()[8]);
      in_gap = true;
      continue;
    }
    if (in_gap) after = az;
    in_gap = false;
    p.push_back(q);
  }
  write_pcap(dir + "/fov.pcap", p);
  const CmdResult r = run_cli("stats " + dir + "/fov.pcap --json");
  ASSERT_EQ(r.status, 0);
  EXPECT_EQ(json_numbers(r.out)["lost"], 0) << r.out;
  char want[64];
  std::snprintf(want, sizeof want, "\"fov_gap_deg\":[%u.%02u,%u.%02u]", before / 100u, before % 100u, after / 100u,
                after % 100u);
  EXPECT_NE(r.out.find(want), std::string::npos) << want << "\n" << r.out;
  EXPECT_NE(run_cli("stats " + data_path("pandar64_dual.pcap") + " --json").out.find("\"fov_gap_deg\":null"), std::string::npos);
  EXPECT_NE(run_cli("stats " + dir + "/fov.pcap").out.find("  fov_gap_deg"), std::string::npos);
}

// Two sensors in one capture (issue #32): a sequence-less Pandar64 from 192.168.1.201 with 100
// packets dropped and 9 frozen timestamps, interleaved with the QT128C2X capture (sequence on) from
// 192.168.1.202, both to port 2368 from 10000: the run's lost is the Pandar64's 100, lost_by "mixed",
// and `sensors` holds one object per address with its own counts.
TEST(Cli, StatsPerSensorObjects) {
  const std::string dir = temp_dir();
  auto p64 = pcap_payloads("pandar64_dual.pcap");
  const std::size_t tail = 1172;
  for (std::size_t i = 301; i <= 309; ++i) {
    for (std::size_t b = 10; b < 14; ++b) p64[i][tail + b] = p64[300][tail + b];
    for (std::size_t b = 16; b < 22; ++b) p64[i][tail + b] = p64[300][tail + b];
  }
  for (auto& q : p64) q.resize(1194);
  p64.erase(p64.begin() + 700, p64.begin() + 800);
  const auto qt = pcap_payloads("qt128c2x_dual.pcap");
  std::vector<std::vector<std::uint8_t>> all;
  std::vector<bool> from_qt;
  for (std::size_t i = 0; i < std::max(p64.size(), qt.size()); ++i) {
    if (i < p64.size()) { all.push_back(p64[i]); from_qt.push_back(false); }
    if (i < qt.size()) { all.push_back(qt[i]); from_qt.push_back(true); }
  }
  write_pcap(dir + "/two.pcap", all);
  // write_pcap's records: 16-byte header, then the frame; the IPv4 source's last byte at frame byte 29.
  std::vector<std::uint8_t> file = read_file(dir + "/two.pcap");
  std::size_t at = 24;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (from_qt[i]) file[at + 16 + 29] = 202;
    at += 16 + load_le32(&file[at + 8]);
  }
  std::ofstream(dir + "/two.pcap", std::ios::binary).write(reinterpret_cast<const char*>(file.data()),
                                                            static_cast<long>(file.size()));
  const CmdResult r = run_cli("stats " + dir + "/two.pcap --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::size_t sensors = r.out.find("\"sensors\":[");
  ASSERT_NE(sensors, std::string::npos) << r.out;
  EXPECT_EQ(json_numbers(r.out.substr(0, sensors))["lost"], 100);  // the run's (json_numbers keeps a key's last value)
  EXPECT_NE(r.out.find("\"lost_by\":\"mixed\""), std::string::npos) << r.out;
  const std::size_t a = r.out.find("{\"source\":\"192.168.1.201:10000\",\"model\":\"Pandar64\",", sensors);
  const std::size_t b = r.out.find("{\"source\":\"192.168.1.202:10000\",\"model\":\"QT128C2X\",", sensors);
  ASSERT_NE(a, std::string::npos) << r.out;
  ASSERT_NE(b, std::string::npos) << r.out;
  EXPECT_LT(a, b);  // in the order they first sent
  const auto one = json_numbers(r.out.substr(a, b - a));
  EXPECT_EQ(one.at("packets"), static_cast<long long>(p64.size()));
  EXPECT_EQ(one.at("lost"), 100);
  EXPECT_EQ(one.at("time_stalls"), 9);
  EXPECT_NE(r.out.substr(a, b - a).find("\"lost_by\":\"azimuth_time\""), std::string::npos);
  const auto two = json_numbers(r.out.substr(b));
  EXPECT_EQ(two.at("packets"), static_cast<long long>(qt.size()));
  EXPECT_EQ(two.at("lost"), 0);
  EXPECT_EQ(two.at("time_stalls"), 0);
  EXPECT_NE(r.out.substr(b).find("\"lost_by\":\"udp_sequence\""), std::string::npos);
  // One sensor: no `sensors` key.
  EXPECT_EQ(run_cli("stats " + data_path("qt128c2x_dual.pcap") + " --json").out.find("\"sensors\""), std::string::npos);
}

// The keys of a JSON object's top level, in order (strings followed by ':' at depth 1).
std::vector<std::string> top_level_keys(const std::string& json) {
  std::vector<std::string> keys;
  int depth = 0;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (c == '{' || c == '[') ++depth;
    else if (c == '}' || c == ']') --depth;
    else if (c == '"') {
      std::size_t end = i + 1;
      while (end < json.size() && json[end] != '"') end += json[end] == '\\' ? std::size_t{2} : std::size_t{1};
      if (depth == 1 && end + 1 < json.size() && json[end + 1] == ':') keys.push_back(json.substr(i + 1, end - i - 1));
      i = end;
    }
  }
  return keys;
}

// `stats --help` names every key of `stats --json`, and no key it does not have (the list is
// written by hand beside the JSON writer, report.cpp's stats_json; a key added to one and not the
// other fails here). Both QT128C2X's functional-safety keys and the per-sensor `sensors` show.
TEST(Cli, StatsHelpNamesEveryJsonKey) {
  const CmdResult help = run_cli("stats --help");
  ASSERT_EQ(help.status, 0);
  const std::size_t from = help.out.find("\n  --json ");  // the option's paragraph, not the usage line
  const std::size_t to = help.out.find("\n  --quiet");
  ASSERT_LT(from, to) << help.out;
  std::string list = help.out.substr(from + 9, to - from - 9);
  for (std::size_t open; (open = list.find('(')) != std::string::npos;) list.erase(open, list.find(')', open) - open + 1);
  std::set<std::string> named;
  std::string word;
  for (const char c : list + " ") {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') word += c;
    else if (!word.empty()) named.insert(std::exchange(word, std::string()));
  }
  named.erase("one");  // "one JSON object: ..."
  named.erase("JSON");
  named.erase("object");
  std::set<std::string> keys;
  for (const std::string& k : top_level_keys(run_cli("stats " + data_path("qt128c2x_dual.pcap") + " --json").out)) keys.insert(k);
  ASSERT_GT(keys.size(), 30u);
  keys.insert("sensors");  // with several sensors only (StatsPerSensorObjects)
  EXPECT_EQ(named, keys);
}

}  // namespace
