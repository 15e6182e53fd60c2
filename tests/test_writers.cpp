// Point-cloud writers: CSV text, PCD and PLY records read back byte by byte, PCL reading our
// PCD (when pcl_pcd2ply is installed), and PNG files decoded here by an independent decoder
// (chunk CRCs, zlib header, inflate of stored and fixed-Huffman blocks, Adler-32, unfiltering).
#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "hesai_port/formats/png.h"
#include "hesai_port/formats/writers.h"

namespace {

using hesai::Point;
namespace port = hesai::port;

std::string temp_path(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return ::testing::TempDir() + "hesai_" + std::to_string(::getpid()) + "_" + info->name() + "_" + name;
}

std::vector<std::uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<std::uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string read_text(const std::string& path) {
  const std::vector<std::uint8_t> b = read_bytes(path);
  return std::string(b.begin(), b.end());
}

bool on_path(const char* program) {
  const std::string cmd = std::string("command -v ") + program + " >/dev/null 2>&1";
  return std::system(cmd.c_str()) == 0;
}

Point make_point(float x, float y, float z, std::uint8_t intensity) {
  Point p;
  p.x = x;
  p.y = y;
  p.z = z;
  p.intensity = intensity;
  return p;
}

// ---------------------------------------------------------------- CSV

TEST(CsvWriter, HeaderIsTheColumnContract) {
  const std::string path = temp_path("h.csv");
  port::CsvWriter w;
  ASSERT_TRUE(w.open(path).ok());
  ASSERT_TRUE(w.close().ok());
  EXPECT_EQ(read_text(path),
            "frame,packet,block,channel,return,azimuth_deg,elevation_deg,distance_m,x,y,z,intensity,time_ns,sensor\n");
  std::remove(path.c_str());
}

TEST(CsvWriter, FormatsRowsWithFixedDecimals) {
  Point a;
  a.block = 3;
  a.channel = 17;
  a.return_index = 1;
  a.azimuth_deg = 123.456f;
  a.elevation_deg = -15.0f;
  a.distance_m = 12.3456f;
  a.x = 1.5f;
  a.y = -2.25f;
  a.z = 0.125f;
  a.intensity = 200;
  a.time_ns = 1700000000123456789;

  Point b;  // extremes: tiny negatives print as zero, sign kept where a digit shows
  b.block = 0;
  b.channel = 128;
  b.return_index = 0;
  b.azimuth_deg = 359.999f;
  b.elevation_deg = -0.0001f;
  b.distance_m = 200.0f;
  b.x = -0.00001f;
  b.y = -1.23456f;
  b.z = -0.0f;
  b.intensity = 255;
  b.time_ns = -5;

  const std::string path = temp_path("rows.csv");
  port::CsvWriter w;
  ASSERT_TRUE(w.open(path).ok());
  EXPECT_TRUE(w.write(a, 42, 123456789012u, "192.168.1.201:2368").ok());
  EXPECT_TRUE(w.write(b, 4294967295u, 18446744073709551615u, "\"a,b\"").ok());
  EXPECT_EQ(w.rows(), 2u);
  ASSERT_TRUE(w.close().ok());
  EXPECT_EQ(read_text(path),
            "frame,packet,block,channel,return,azimuth_deg,elevation_deg,distance_m,x,y,z,intensity,time_ns,sensor\n"
            "42,123456789012,3,17,1,123.456,-15.000,12.3456,1.5000,-2.2500,0.1250,200,1700000000123456789,192.168.1.201:2368\n"
            "4294967295,18446744073709551615,0,128,0,359.999,0.000,200.0000,0.0000,-1.2346,0.0000,255,-5,\"a,b\"\n");
  std::remove(path.c_str());
}

// The fixed-point fields against the C library's printf ("%.3f", "%.4f"; a value that rounds to
// zero printed without its minus sign): floats spread over every exponent (a stride through all
// 2^32 bit patterns, 128 values per exponent and sign), and the exact ties, where rounding to even
// matters: n/16 for odd n is halfway at 3 decimals (n * 62.5), n/32 at 4 decimals (n * 312.5).
TEST(CsvWriter, FixedDecimalsRoundAsPrintf) {
  auto printf_fixed = [](float v, int decimals) {
    char s[64];
    std::snprintf(s, sizeof s, "%.*f", decimals, static_cast<double>(v));
    std::string t = s;
    if (t[0] == '-' && t.find_first_not_of("0.", 1) == std::string::npos) t.erase(0, 1);
    return t;
  };
  std::vector<float> values;
  for (std::uint64_t bits = 0; bits <= 0xFFFFFFFFu; bits += 65537) {
    float v;
    const auto b = static_cast<std::uint32_t>(bits);
    std::memcpy(&v, &b, sizeof v);
    values.push_back(v);
  }
  for (int n = -(1 << 16) + 1; n < (1 << 16); n += 2) {
    values.push_back(static_cast<float>(n) / 16.0f);
    values.push_back(static_cast<float>(n) / 32.0f);
  }
  char row[port::kCsvMaxRow];
  for (const float v : values) {
    Point p;
    p.azimuth_deg = v;  // field 5: 3 decimals
    p.x = v;            // field 8: 4 decimals
    const std::string s(row, port::format_csv_row(row, p, 0, 0));
    std::size_t at[14] = {0};
    std::size_t commas = 0;
    for (std::size_t i = 0; i < s.size() && commas < 13; ++i)
      if (s[i] == ',') at[++commas] = i + 1;
    ASSERT_EQ(commas, 12u) << s;
    ASSERT_EQ(s.substr(at[5], at[6] - at[5] - 1), printf_fixed(v, 3)) << s;
    ASSERT_EQ(s.substr(at[8], at[9] - at[8] - 1), printf_fixed(v, 4)) << s;
  }
  EXPECT_GT(values.size(), 130000u);
}

TEST(CsvWriter, ManyRowsCrossBufferBlocks) {
  const std::string path = temp_path("many.csv");
  constexpr std::size_t kRows = 60000;  // about 5 MB: several 1 MiB blocks
  port::CsvWriter w;
  ASSERT_TRUE(w.open(path).ok());
  std::vector<Point> pts(kRows);
  for (std::size_t i = 0; i < kRows; ++i) {
    pts[i] = make_point(-123.4567f, 98.7654f, -1.5f, static_cast<std::uint8_t>(i % 256));
    pts[i].distance_m = 150.25f;
    pts[i].azimuth_deg = 270.5f;
    pts[i].elevation_deg = -24.75f;
    pts[i].channel = 64;
    pts[i].time_ns = 1700000000000000000 + static_cast<std::int64_t>(i);
    ASSERT_TRUE(w.write(pts[i], 7, i, "/pandar_packets").ok());
  }
  ASSERT_TRUE(w.close().ok());
  std::istringstream in(read_text(path));
  std::string line;
  std::getline(in, line);
  std::size_t n = 0;
  while (std::getline(in, line)) {
    const std::string expect = "7," + std::to_string(n) + ",0,64,0,270.500,-24.750,150.2500,-123.4567,98.7654,-1.5000," +
                               std::to_string(n % 256) + "," + std::to_string(1700000000000000000 + n) + ",/pandar_packets";
    if (line != expect) {
      ADD_FAILURE() << "row " << n << ": " << line << " != " << expect;
      break;
    }
    ++n;
  }
  EXPECT_EQ(n, kRows);
  std::remove(path.c_str());
}

TEST(CsvWriter, WritesToCallerStreamAndLeavesItOpen) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  port::CsvWriter w;
  ASSERT_TRUE(w.open(f, "tmp").ok());
  const Point pts[2] = {make_point(1, 2, 3, 4), make_point(-1, -2, -3, 5)};
  EXPECT_TRUE(w.write(pts, 2, 1, 2, "s").ok());
  ASSERT_TRUE(w.close().ok());
  EXPECT_FALSE(w.is_open());
  // The stream is still usable: read it back.
  ASSERT_EQ(std::fseek(f, 0, SEEK_SET), 0);
  std::string text;
  char buf[256];
  std::size_t got = 0;
  while ((got = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, got);
  std::fclose(f);
  EXPECT_EQ(text,
            "frame,packet,block,channel,return,azimuth_deg,elevation_deg,distance_m,x,y,z,intensity,time_ns,sensor\n"
            "1,2,0,0,0,0.000,0.000,0.0000,1.0000,2.0000,3.0000,4,0,s\n"
            "1,2,0,0,0,0.000,0.000,0.0000,-1.0000,-2.0000,-3.0000,5,0,s\n");
}

TEST(CsvWriter, ReportsErrors) {
  port::CsvWriter w;
  const port::WriteResult not_open = w.write(Point{}, 0, 0, "s");
  EXPECT_FALSE(not_open.ok());
  EXPECT_NE(not_open.message().find("not open"), std::string::npos);

  const port::WriteResult r = w.open("/nonexistent-dir/out.csv");
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.os_error(), ENOENT);
  EXPECT_NE(r.message().find("'/nonexistent-dir/out.csv'"), std::string::npos) << r.message();
  EXPECT_FALSE(w.is_open());
}

TEST(CsvWriter, RefusesASensorFieldOverItsLimit) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  port::CsvWriter w;
  ASSERT_TRUE(w.open(f, "tmp").ok());
  EXPECT_TRUE(w.write(Point{}, 1, 0, std::string(port::CsvWriter::kMaxSensorBytes, 's')).ok());
  const port::WriteResult r = w.write(Point{}, 1, 0, std::string(port::CsvWriter::kMaxSensorBytes + 1, 's'));
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.message().find("sensor field"), std::string::npos) << r.message();
  EXPECT_EQ(w.rows(), 1u);
  (void)w.close();
  std::fclose(f);
}

TEST(CsvWriter, ReportsFullDisk) {
  if (::access("/dev/full", W_OK) != 0) GTEST_SKIP() << "no /dev/full";
  port::CsvWriter w;
  ASSERT_TRUE(w.open("/dev/full").ok());
  for (int i = 0; i < 20000; ++i) (void)w.write(make_point(1, 2, 3, 4), 0, static_cast<std::uint64_t>(i), "s");
  const port::WriteResult r = w.close();
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.os_error(), ENOSPC) << r.message();
}

// ---------------------------------------------------------------- PCD

// Three points whose binary encodings are typed below from IEEE-754 by hand.
std::vector<Point> record_points() {
  std::vector<Point> v(3);
  v[0] = make_point(1.0f, -2.0f, 0.5f, 255);  // 0x3F800000, 0xC0000000, 0x3F000000, 255.0f = 0x437F0000
  v[0].channel = 128;
  v[0].return_index = 1;
  v[0].time_ns = 1500000000;  // 1.5 s = 0x3FF8000000000000
  v[1] = make_point(0.0f, 2.0f, -1.0f, 0);  // 0, 0x40000000, 0xBF800000, 0
  v[1].channel = 1;
  v[1].time_ns = 2147483648000000000;  // 2^31 s = 0x41E0000000000000
  v[2] = make_point(-0.5f, 0.25f, 4.0f, 1);  // 0xBF000000, 0x3E800000, 0x40800000, 1.0f = 0x3F800000
  v[2].channel = 300 % 256;                  // 44
  v[2].time_ns = -1500000000;                // -1.5 s = 0xBFF8000000000000
  return v;
}

TEST(PcdWriter, HeaderAndLittleEndianRecords) {
  const std::string path = temp_path("r.pcd");
  ASSERT_TRUE(port::write_pcd(path, record_points()).ok());
  const std::vector<std::uint8_t> file = read_bytes(path);
  const std::string header =
      "# .PCD v0.7 - Point Cloud Data file format\n"
      "VERSION 0.7\n"
      "FIELDS x y z intensity ring return timestamp\n"
      "SIZE 4 4 4 4 2 1 8\n"
      "TYPE F F F F U U F\n"
      "COUNT 1 1 1 1 1 1 1\n"
      "WIDTH 3\n"
      "HEIGHT 1\n"
      "VIEWPOINT 0 0 0 1 0 0 0\n"
      "POINTS 3\n"
      "DATA binary\n";
  ASSERT_EQ(file.size(), header.size() + 3 * 27);
  EXPECT_EQ(std::string(file.begin(), file.begin() + static_cast<long>(header.size())), header);
  const std::vector<std::uint8_t> expect = {
      // x y z intensity ring return timestamp
      0x00, 0x00, 0x80, 0x3F, 0x00, 0x00, 0x00, 0xC0, 0x00, 0x00, 0x00, 0x3F, 0x00, 0x00, 0x7F, 0x43,
      0x80, 0x00, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xF8, 0x3F,
      0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x40, 0x00, 0x00, 0x80, 0xBF, 0x00, 0x00, 0x00, 0x00,
      0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xE0, 0x41,
      0x00, 0x00, 0x00, 0xBF, 0x00, 0x00, 0x80, 0x3E, 0x00, 0x00, 0x80, 0x40, 0x00, 0x00, 0x80, 0x3F,
      0x2C, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xF8, 0xBF};
  EXPECT_EQ(std::vector<std::uint8_t>(file.begin() + static_cast<long>(header.size()), file.end()), expect);
  std::remove(path.c_str());
}

TEST(PcdWriter, EmptyCloudAndOpenFailure) {
  const std::string path = temp_path("e.pcd");
  ASSERT_TRUE(port::write_pcd(path, std::vector<Point>{}).ok());
  const std::string text = read_text(path);
  EXPECT_NE(text.find("\nWIDTH 0\n"), std::string::npos);
  EXPECT_NE(text.find("\nPOINTS 0\nDATA binary\n"), std::string::npos);
  std::remove(path.c_str());
  const port::WriteResult r = port::write_pcd("/nonexistent-dir/x.pcd", std::vector<Point>{});
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.os_error(), ENOENT);
}

// Splits s at whitespace.
std::vector<std::string> words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> out;
  std::string w;
  while (in >> w) out.push_back(w);
  return out;
}

TEST(PcdWriter, PclReadsIt) {
  if (!on_path("pcl_pcd2ply")) GTEST_SKIP() << "pcl_pcd2ply not installed (Debian package pcl-tools)";
  std::vector<Point> pts(4);
  const float xyz[4][3] = {{1.25f, -3.5f, 0.75f}, {-12.125f, 40.5f, -2.0f}, {0.0f, 0.0f, 0.0f}, {100.5f, -0.25f, 8.0f}};
  for (int i = 0; i < 4; ++i) {
    const auto k = static_cast<std::size_t>(i);
    pts[k] = make_point(xyz[i][0], xyz[i][1], xyz[i][2], static_cast<std::uint8_t>(10 * i + 5));
    pts[k].channel = static_cast<std::uint8_t>(i + 1);
    pts[k].return_index = static_cast<std::uint8_t>(i % 2);
    pts[k].time_ns = static_cast<std::int64_t>(i) * 250000000;  // 0, 0.25, 0.5, 0.75 s
  }
  const std::string pcd = temp_path("pcl.pcd");
  const std::string ply = temp_path("pcl.ply");
  ASSERT_TRUE(port::write_pcd(pcd, pts).ok());
  // -format 0: ASCII PLY; -use_camera 0: no camera element.
  const std::string cmd = "pcl_pcd2ply -format 0 -use_camera 0 '" + pcd + "' '" + ply + "' >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;

  std::istringstream in(read_text(ply));
  std::string line;
  std::vector<std::string> props;
  std::size_t vertices = 0;
  bool in_vertex = false;
  bool ascii = false;
  while (std::getline(in, line) && line != "end_header") {
    const std::vector<std::string> w = words(line);
    if (w.size() == 3 && w[0] == "format") ascii = (w[1] == "ascii");
    if (w.size() == 3 && w[0] == "element") {
      in_vertex = (w[1] == "vertex");
      if (in_vertex) vertices = std::stoul(w[2]);
    }
    if (in_vertex && w.size() == 3 && w[0] == "property") props.push_back(w[2]);
  }
  EXPECT_TRUE(ascii);
  ASSERT_EQ(vertices, 4u);
  ASSERT_EQ(props, (std::vector<std::string>{"x", "y", "z", "intensity", "ring", "return", "timestamp"}));
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(std::getline(in, line));
    const std::vector<std::string> v = words(line);
    ASSERT_EQ(v.size(), 7u) << line;
    EXPECT_DOUBLE_EQ(std::stod(v[0]), xyz[i][0]) << line;
    EXPECT_DOUBLE_EQ(std::stod(v[1]), xyz[i][1]) << line;
    EXPECT_DOUBLE_EQ(std::stod(v[2]), xyz[i][2]) << line;
    EXPECT_EQ(std::stoi(v[3]), 10 * i + 5) << line;
    EXPECT_EQ(std::stoi(v[4]), i + 1) << line;
    EXPECT_EQ(std::stoi(v[5]), i % 2) << line;
    EXPECT_DOUBLE_EQ(std::stod(v[6]), 0.25 * i) << line;
  }
  std::remove(pcd.c_str());
  std::remove(ply.c_str());
}

// ---------------------------------------------------------------- PLY

std::uint32_t le32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}
float lef32(const std::uint8_t* p) {
  const std::uint32_t u = le32(p);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}
double lef64(const std::uint8_t* p) {
  const std::uint64_t u = le32(p) | static_cast<std::uint64_t>(le32(p + 4)) << 32;
  double d;
  std::memcpy(&d, &u, 8);
  return d;
}

TEST(PlyWriter, HeaderAndBinaryRecordsReadBack) {
  const std::vector<Point> pts = record_points();
  const std::string path = temp_path("r.ply");
  ASSERT_TRUE(port::write_ply(path, pts).ok());
  const std::vector<std::uint8_t> file = read_bytes(path);
  const std::string text(file.begin(), file.end());
  const std::size_t end = text.find("end_header\n");
  ASSERT_NE(end, std::string::npos);
  std::istringstream in(text.substr(0, end));
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line, "ply");
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line, "format binary_little_endian 1.0");
  std::vector<std::pair<std::string, std::string>> props;  // type, name
  std::size_t vertices = 0;
  while (std::getline(in, line)) {
    const std::vector<std::string> w = words(line);
    if (w.empty() || w[0] == "comment") continue;
    if (w[0] == "element") {
      ASSERT_EQ(w.size(), 3u);
      ASSERT_EQ(w[1], "vertex");
      vertices = std::stoul(w[2]);
    } else {
      ASSERT_EQ(w.size(), 3u) << line;
      ASSERT_EQ(w[0], "property") << line;
      props.emplace_back(w[1], w[2]);
    }
  }
  ASSERT_EQ(vertices, 3u);
  const std::vector<std::pair<std::string, std::string>> expect_props = {
      {"float", "x"},     {"float", "y"},     {"float", "z"},         {"uchar", "intensity"},
      {"uchar", "ring"},  {"uchar", "return"}, {"double", "timestamp"}};
  ASSERT_EQ(props, expect_props);
  const std::size_t record = 3 * 4 + 3 * 1 + 8;
  const std::size_t data = end + std::strlen("end_header\n");
  ASSERT_EQ(file.size(), data + 3 * record);
  for (std::size_t i = 0; i < 3; ++i) {
    const std::uint8_t* r = file.data() + data + i * record;
    EXPECT_EQ(lef32(r), pts[i].x);
    EXPECT_EQ(lef32(r + 4), pts[i].y);
    EXPECT_EQ(lef32(r + 8), pts[i].z);
    EXPECT_EQ(r[12], pts[i].intensity);
    EXPECT_EQ(r[13], pts[i].channel);
    EXPECT_EQ(r[14], pts[i].return_index);
  }
  EXPECT_EQ(lef64(file.data() + data + 15), 1.5);
  EXPECT_EQ(lef64(file.data() + data + record + 15), 2147483648.0);
  EXPECT_EQ(lef64(file.data() + data + 2 * record + 15), -1.5);
  std::remove(path.c_str());

  // A present-day time: the double nearest to the exact decimal seconds (the literal below,
  // which the compiler rounds correctly), not an approximation through a double of nanoseconds.
  Point now;
  now.time_ns = 1700683915271066246;  // double(time_ns) / 1e9 would round to the next double
  ASSERT_TRUE(port::write_ply(path, &now, 1).ok());
  const std::vector<std::uint8_t> one = read_bytes(path);
  ASSERT_EQ(one.size(), data + record);  // same header length: "element vertex 1" for "... 3"
  EXPECT_EQ(lef64(one.data() + one.size() - 8), 1700683915.271066246);
  std::remove(path.c_str());
}

// ---------------------------------------------------------------- Streamed PCD and PLY

// What write_pcd / write_ply give for `pts`, with the count in the header as 20 zero-padded digits.
std::string known_count_file(port::CloudFormat f, const std::vector<Point>& pts, const std::string& path) {
  const bool pcd = f == port::CloudFormat::pcd;
  EXPECT_TRUE((pcd ? port::write_pcd(path, pts) : port::write_ply(path, pts)).ok());
  std::string text = read_text(path);
  std::remove(path.c_str());
  std::string n = std::to_string(pts.size());
  n.insert(0, 20 - n.size(), '0');
  for (const char* key : {"\nWIDTH ", "\nPOINTS ", "\nelement vertex "}) {
    const std::size_t at = text.find(key);
    if (at == std::string::npos) continue;
    const std::size_t from = at + std::strlen(key);
    text.replace(from, text.find('\n', from) - from, n);
  }
  return text;
}

// A streamed file is the known-count file but for the padded count: 3 points, and 100 000
// (2.7 MB of PCD records, across several 1 MiB blocks).
TEST(CloudWriter, StreamedFileIsTheKnownCountFileWithAPaddedCount) {
  std::vector<Point> many(100000);
  for (std::size_t i = 0; i < many.size(); ++i) {
    many[i] = make_point(static_cast<float>(i) * 0.001f, -1.0f, 0.5f, static_cast<std::uint8_t>(i));
    many[i].channel = static_cast<std::uint8_t>(i % 128 + 1);
    many[i].time_ns = 1700000000000000000 + static_cast<std::int64_t>(i) * 1000;
  }
  for (const port::CloudFormat f : {port::CloudFormat::pcd, port::CloudFormat::ply}) {
    for (const std::vector<Point>& pts : {record_points(), many}) {
      const std::string path = temp_path(f == port::CloudFormat::pcd ? "s.pcd" : "s.ply");
      port::CloudWriter w;
      ASSERT_TRUE(w.open(path, f).ok());
      for (const Point& p : pts) w.write(p);
      EXPECT_EQ(w.count(), pts.size());
      ASSERT_TRUE(w.close().ok());
      EXPECT_FALSE(w.is_open());
      EXPECT_TRUE(read_text(path) == known_count_file(f, pts, temp_path("known"))) << path << ", " << pts.size();
      std::remove(path.c_str());
    }
  }
  // PCL reads the padded count.
  if (!on_path("pcl_pcd2ply")) GTEST_SKIP() << "pcl_pcd2ply not installed (Debian package pcl-tools)";
  const std::string pcd = temp_path("pcl.pcd");
  const std::string ply = temp_path("pcl.ply");
  port::CloudWriter w;
  ASSERT_TRUE(w.open(pcd, port::CloudFormat::pcd).ok());
  for (const Point& p : many) w.write(p);
  ASSERT_TRUE(w.close().ok());
  const std::string cmd = "pcl_pcd2ply -format 0 -use_camera 0 '" + pcd + "' '" + ply + "' >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  EXPECT_NE(read_text(ply).find("\nelement vertex 100000\n"), std::string::npos);
  std::remove(pcd.c_str());
  std::remove(ply.c_str());
}

TEST(CloudWriter, RefusesAPipeAndReportsFailures) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  port::CloudWriter w;
  const port::WriteResult piped = w.open("/proc/self/fd/" + std::to_string(fds[1]), port::CloudFormat::pcd);
  EXPECT_FALSE(piped.ok());
  EXPECT_EQ(piped.os_error(), ESPIPE) << piped.message();
  EXPECT_FALSE(w.is_open());
  ::close(fds[0]);
  ::close(fds[1]);

  const port::WriteResult missing = w.open("/nonexistent-dir/x.ply", port::CloudFormat::ply);
  EXPECT_FALSE(missing.ok());
  EXPECT_EQ(missing.os_error(), ENOENT);
  EXPECT_FALSE(w.close().ok());  // not open

  ASSERT_TRUE(w.open("/dev/null", port::CloudFormat::ply).ok());  // seekable, so accepted
  w.write(make_point(1, 2, 3, 4));
  EXPECT_TRUE(w.close().ok());

  if (::access("/dev/full", W_OK) != 0) GTEST_SKIP() << "no /dev/full";
  ASSERT_TRUE(w.open("/dev/full", port::CloudFormat::pcd).ok());
  for (int i = 0; i < 50000; ++i) w.write(make_point(1, 2, 3, 4));  // 1.35 MB: one block fails
  const port::WriteResult full = w.close();
  EXPECT_FALSE(full.ok());
  EXPECT_EQ(full.os_error(), ENOSPC) << full.message();
}

// ---------------------------------------------------------------- PNG: an independent decoder

// Reflected CRC-32, bit by bit (no table), as PNG's annex D describes it.
std::uint32_t ref_crc32(const std::uint8_t* p, std::size_t n) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return ~c;
}

std::uint32_t ref_adler32(const std::vector<std::uint8_t>& d) {
  std::uint64_t a = 1, b = 0;
  for (std::uint8_t x : d) {
    a = (a + x) % 65521;
    b = (b + a) % 65521;
  }
  return static_cast<std::uint32_t>(b << 16 | a);
}

std::uint32_t be32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) << 24 | static_cast<std::uint32_t>(p[1]) << 16 |
         static_cast<std::uint32_t>(p[2]) << 8 | p[3];
}

// Inflate of stored and fixed-Huffman blocks (RFC 1951); dynamic blocks fail the test.
class Inflater {
 public:
  Inflater(const std::uint8_t* d, std::size_t n) : d_(d), n_(n) {}

  bool run(std::vector<std::uint8_t>& out) {
    static const int kLenBase[29] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                     31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
    static const int kLenExtra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                      2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
    static const int kDistBase[30] = {1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,    65,    97,    129,
                                      193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
    static const int kDistExtra[30] = {0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
    bool last = false;
    while (!last) {
      last = bits(1) == 1;
      const std::uint32_t type = bits(2);
      if (type == 0) {
        bitpos_ = (bitpos_ + 7) / 8 * 8;
        if (bitpos_ / 8 + 4 > n_) return false;
        const std::uint8_t* p = d_ + bitpos_ / 8;
        const unsigned len = p[0] | static_cast<unsigned>(p[1]) << 8;
        const unsigned nlen = p[2] | static_cast<unsigned>(p[3]) << 8;
        if ((len ^ 0xFFFFu) != nlen) return false;
        if (bitpos_ / 8 + 4 + len > n_) return false;
        out.insert(out.end(), p + 4, p + 4 + len);
        bitpos_ += (4 + len) * 8;
        ++stored_blocks;
      } else if (type == 1) {
        ++fixed_blocks;
        for (;;) {
          const int sym = fixed_symbol();
          if (sym < 0 || bad_) return false;
          if (sym < 256) {
            out.push_back(static_cast<std::uint8_t>(sym));
            continue;
          }
          if (sym == 256) break;
          const int li = sym - 257;
          if (li >= 29) return false;
          const std::size_t len = static_cast<std::size_t>(kLenBase[li]) + bits(kLenExtra[li]);
          std::uint32_t dc = 0;
          for (int i = 0; i < 5; ++i) dc = dc << 1 | bits(1);  // Huffman codes: MSB first
          if (dc >= 30) return false;
          const std::size_t dist = static_cast<std::size_t>(kDistBase[dc]) + bits(kDistExtra[dc]);
          if (dist > out.size() || dist > 32768) return false;
          for (std::size_t i = 0; i < len; ++i) out.push_back(out[out.size() - dist]);
        }
      } else {
        return false;
      }
      if (bad_) return false;
    }
    used = (bitpos_ + 7) / 8;
    return true;
  }
  std::size_t used = 0;  // bytes consumed
  int stored_blocks = 0;
  int fixed_blocks = 0;

 private:
  std::uint32_t bits(int n) {
    std::uint32_t v = 0;
    for (int i = 0; i < n; ++i, ++bitpos_) {
      if (bitpos_ / 8 >= n_) {
        bad_ = true;
        return 0;
      }
      const unsigned byte = d_[bitpos_ / 8];
      v |= ((byte >> (bitpos_ % 8)) & 1u) << i;
    }
    return v;
  }
  // RFC 1951 3.2.6: 7-bit codes 0000000-0010111 are 256-279; 8-bit 00110000-10111111 are 0-143,
  // 11000000-11000111 are 280-287; 9-bit 110010000-111111111 are 144-255.
  int fixed_symbol() {
    std::uint32_t c = 0;
    for (int i = 0; i < 7; ++i) c = c << 1 | bits(1);
    if (c <= 0x17) return 256 + static_cast<int>(c);
    c = c << 1 | bits(1);
    if (c >= 0x30 && c <= 0xBF) return static_cast<int>(c - 0x30);
    if (c >= 0xC0 && c <= 0xC7) return 280 + static_cast<int>(c - 0xC0);
    c = c << 1 | bits(1);
    if (c >= 0x190 && c <= 0x1FF) return 144 + static_cast<int>(c - 0x190);
    return -1;
  }
  const std::uint8_t* d_;
  std::size_t n_;
  std::size_t bitpos_ = 0;
  bool bad_ = false;
};

// Decodes a zlib stream: header checks, inflate, no trailing bytes, Adler-32.
bool unzlib(const std::vector<std::uint8_t>& z, std::vector<std::uint8_t>& out, Inflater* stats = nullptr) {
  if (z.size() < 6) return false;
  if ((z[0] & 0x0F) != 8 || (z[0] >> 4) > 7) return false;  // CM = deflate, window <= 32K
  if ((z[0] * 256 + z[1]) % 31 != 0 || (z[1] & 0x20) != 0) return false;  // FCHECK, no FDICT
  Inflater inf(z.data() + 2, z.size() - 6);
  out.clear();
  if (!inf.run(out)) return false;
  if (2 + inf.used != z.size() - 4) return false;  // nothing between the deflate data and Adler
  if (stats != nullptr) *stats = inf;
  return be32(z.data() + z.size() - 4) == ref_adler32(out);
}

struct DecodedPng {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  std::vector<std::uint8_t> zlib;
  int idat_chunks = 0;
  int stored_blocks = 0;
  int fixed_blocks = 0;
  std::array<int, 5> filter_rows{};  // rows per filter type

  std::array<int, 3> px(std::uint32_t x, std::uint32_t y) const {
    const std::uint8_t* p = rgb.data() + (static_cast<std::size_t>(y) * width + x) * 3;
    return {p[0], p[1], p[2]};
  }
};

int paeth_ref(int a, int b, int c) {
  const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return (pa <= pb && pa <= pc) ? a : (pb <= pc ? b : c);
}

// Parses and checks a whole PNG: signature, every chunk CRC, IHDR, IDATs, IEND; then inflates
// and unfilters. Adds a GoogleTest failure and returns false on any defect.
bool decode_png(const std::vector<std::uint8_t>& f, DecodedPng& out) {
  out = DecodedPng();
  const std::uint8_t sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
  if (f.size() < 8 || std::memcmp(f.data(), sig, 8) != 0) {
    ADD_FAILURE() << "bad signature";
    return false;
  }
  std::size_t pos = 8;
  bool ihdr = false, iend = false;
  while (pos + 12 <= f.size() && !iend) {
    const std::uint32_t len = be32(f.data() + pos);
    if (len > f.size() - pos - 12) {
      ADD_FAILURE() << "chunk length past the end";
      return false;
    }
    const std::string type(f.begin() + static_cast<long>(pos) + 4, f.begin() + static_cast<long>(pos) + 8);
    const std::uint8_t* data = f.data() + pos + 8;
    const std::uint32_t crc = be32(data + len);
    if (crc != ref_crc32(f.data() + pos + 4, 4 + len)) {
      ADD_FAILURE() << "CRC mismatch in chunk " << type;
      return false;
    }
    if (type == "IHDR") {
      if (len != 13 || ihdr || pos != 8) {
        ADD_FAILURE() << "bad IHDR";
        return false;
      }
      out.width = be32(data);
      out.height = be32(data + 4);
      if (data[8] != 8 || data[9] != 2 || data[10] != 0 || data[11] != 0 || data[12] != 0) {
        ADD_FAILURE() << "IHDR is not 8-bit RGB, deflate, filter 0, no interlace";
        return false;
      }
      ihdr = true;
    } else if (type == "IDAT") {
      out.zlib.insert(out.zlib.end(), data, data + len);
      ++out.idat_chunks;
    } else if (type == "IEND") {
      iend = true;
    }
    pos += 12 + len;
  }
  if (!ihdr || !iend || pos != f.size() || out.idat_chunks == 0) {
    ADD_FAILURE() << "missing IHDR/IDAT/IEND or bytes after IEND";
    return false;
  }
  std::vector<std::uint8_t> raw;
  Inflater stats(nullptr, 0);
  if (!unzlib(out.zlib, raw, &stats)) {
    ADD_FAILURE() << "zlib stream does not decode";
    return false;
  }
  out.stored_blocks = stats.stored_blocks;
  out.fixed_blocks = stats.fixed_blocks;
  const std::size_t stride = static_cast<std::size_t>(out.width) * 3;
  if (raw.size() != (stride + 1) * out.height) {
    ADD_FAILURE() << "inflated size " << raw.size() << " does not match the image";
    return false;
  }
  out.rgb.assign(stride * out.height, 0);
  for (std::size_t y = 0; y < out.height; ++y) {
    const std::uint8_t ft = raw[y * (stride + 1)];
    if (ft < 5) ++out.filter_rows[ft];
    const std::uint8_t* in = raw.data() + y * (stride + 1) + 1;
    std::uint8_t* row = out.rgb.data() + y * stride;
    for (std::size_t i = 0; i < stride; ++i) {
      const int a = i >= 3 ? row[i - 3] : 0;
      const int b = y > 0 ? row[i - stride] : 0;
      const int c = (i >= 3 && y > 0) ? row[i - stride - 3] : 0;
      int pred = 0;
      switch (ft) {
        case 0: pred = 0; break;
        case 1: pred = a; break;
        case 2: pred = b; break;
        case 3: pred = (a + b) / 2; break;
        case 4: pred = paeth_ref(a, b, c); break;
        default: ADD_FAILURE() << "filter type " << int{ft}; return false;
      }
      row[i] = static_cast<std::uint8_t>(in[i] + pred);
    }
  }
  return true;
}

// ---------------------------------------------------------------- PNG tests

TEST(Png, Checksums) {
  const std::uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(port::png_crc32(check, 9), 0xCBF43926u);  // CRC-32/ISO-HDLC check value
  EXPECT_EQ(port::png_crc32(check + 4, 5, port::png_crc32(check, 4)), 0xCBF43926u);
  const std::uint8_t wiki[] = {'W', 'i', 'k', 'i', 'p', 'e', 'd', 'i', 'a'};
  EXPECT_EQ(port::adler32(wiki, 9), 0x11E60398u);  // RFC 1950's example word, checked by hand
  EXPECT_EQ(port::adler32(wiki + 3, 6, port::adler32(wiki, 3)), 0x11E60398u);
  // Long input: the modulo must be taken before b overflows.
  std::vector<std::uint8_t> ff(100000, 0xFF);
  EXPECT_EQ(port::adler32(ff.data(), ff.size()), ref_adler32(ff));
  EXPECT_EQ(port::png_crc32(ff.data(), ff.size()), ref_crc32(ff.data(), ff.size()));
}

std::vector<std::uint8_t> pseudo_random(std::size_t n, std::uint32_t seed) {
  std::vector<std::uint8_t> v(n);
  std::uint32_t s = seed;
  for (std::size_t i = 0; i < n; ++i) {
    s = s * 1103515245u + 12345u;
    // Mix of noise and repeats so that both literals and long/far matches occur.
    v[i] = (i / 1000) % 3 == 0 ? static_cast<std::uint8_t>(s >> 24) : static_cast<std::uint8_t>((i * 7) % 251);
  }
  return v;
}

TEST(Png, ZlibRoundTrip) {
  for (port::PngDeflate mode : {port::PngDeflate::stored, port::PngDeflate::fixed_huffman}) {
    for (std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{65535}, std::size_t{65536}, std::size_t{200000}}) {
      const std::vector<std::uint8_t> data = pseudo_random(n, static_cast<std::uint32_t>(n));
      const std::vector<std::uint8_t> z = port::zlib_compress(data.data(), data.size(), mode);
      std::vector<std::uint8_t> back;
      Inflater stats(nullptr, 0);
      ASSERT_TRUE(unzlib(z, back, &stats)) << "mode " << int(mode) << " n " << n;
      EXPECT_EQ(back, data) << "mode " << int(mode) << " n " << n;
      if (mode == port::PngDeflate::stored) {
        EXPECT_EQ(stats.stored_blocks, n == 0 ? 1 : static_cast<int>((n + 65534) / 65535));
      } else {
        EXPECT_EQ(stats.fixed_blocks, 1);
      }
    }
  }
}

TEST(Png, PythonZlibAgrees) {
  if (!on_path("python3")) GTEST_SKIP() << "python3 not installed";
  const std::vector<std::uint8_t> data = pseudo_random(150000, 7);
  for (port::PngDeflate mode : {port::PngDeflate::stored, port::PngDeflate::fixed_huffman}) {
    const std::vector<std::uint8_t> z = port::zlib_compress(data.data(), data.size(), mode);
    const std::string zpath = temp_path("z.bin");
    const std::string outpath = temp_path("z.out");
    ASSERT_TRUE(port::write_file(zpath, z.data(), z.size()).ok());
    const std::string cmd = "python3 -c 'import sys, zlib; open(sys.argv[2], \"wb\").write(zlib.decompress(open(sys.argv[1], \"rb\").read()))' '" +
                            zpath + "' '" + outpath + "'";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    EXPECT_EQ(read_bytes(outpath), data);
    std::remove(zpath.c_str());
    std::remove(outpath.c_str());
  }
}

// A 240 x 160 view of +-10 m: 8 px per metre (the shorter side covers 20 m), sensor at pixel
// (120, 80). A point (x, y) lands on pixel (floor(120 + 8x), floor(80 - 8y)).
port::PngOptions small_options(port::PngDeflate mode) {
  port::PngOptions o;
  o.width = 240;
  o.height = 160;
  o.range_m = 10.0f;
  o.range_rings = false;
  o.scale_bar = false;
  o.legend = false;
  o.deflate = mode;
  return o;
}

std::vector<Point> small_scene() {
  std::vector<Point> v;
  v.push_back(make_point(5.0f, 5.0f, 0, 255));     // (160, 40): red end of the ramp
  v.push_back(make_point(-5.0f, -2.5f, 0, 0));     // (80, 100): blue end
  v.push_back(make_point(0.06f, 7.99f, 0, 255));   // (floor(120.48), floor(16.08)) with intensity 255 ...
  v.push_back(make_point(0.0f, 8.0f, 0, 0));       // ... and (120, 16) with 0 after it: the larger wins
  v.push_back(make_point(20.0f, 0.0f, 0, 255));    // outside: skipped
  v.push_back(make_point(std::nanf(""), 1.0f, 0, 255));  // not finite: skipped
  return v;
}

void expect_rgb(const DecodedPng& img, std::uint32_t x, std::uint32_t y, std::array<int, 3> rgb) {
  EXPECT_EQ(img.px(x, y), rgb) << "pixel (" << x << ", " << y << ")";
}

const std::array<int, 3> kBg = {12, 14, 20};
const std::array<int, 3> kRed = {240, 40, 30};
const std::array<int, 3> kBlue = {40, 70, 230};
const std::array<int, 3> kGreen = {60, 210, 70};
const std::array<int, 3> kWhite = {225, 225, 225};

TEST(Png, StoredBlocksDecodeToTheScene) {
  const std::string path = temp_path("s.png");
  ASSERT_TRUE(port::write_png(path, small_scene(), small_options(port::PngDeflate::stored)).ok());
  DecodedPng img;
  ASSERT_TRUE(decode_png(read_bytes(path), img));
  EXPECT_EQ(img.width, 240u);
  EXPECT_EQ(img.height, 160u);
  EXPECT_GE(img.stored_blocks, 2);  // 160 * 721 bytes need two stored blocks
  EXPECT_EQ(img.fixed_blocks, 0);
  expect_rgb(img, 160, 40, kRed);
  expect_rgb(img, 80, 100, kBlue);
  expect_rgb(img, 120, 16, kRed);
  expect_rgb(img, 120, 80, kWhite);  // the sensor cross
  expect_rgb(img, 123, 80, kWhite);
  expect_rgb(img, 124, 80, kBg);
  expect_rgb(img, 0, 0, kBg);
  expect_rgb(img, 239, 159, kBg);
  expect_rgb(img, 161, 40, kBg);
  expect_rgb(img, 160, 41, kBg);
  // Nothing else was drawn: count the non-background pixels.
  int lit = 0;
  for (std::uint32_t y = 0; y < img.height; ++y) {
    for (std::uint32_t x = 0; x < img.width; ++x) lit += img.px(x, y) != kBg;
  }
  EXPECT_EQ(lit, 3 + 13);  // (160,40), (80,100), (120,16); the cross is 13 pixels
  std::remove(path.c_str());
}

TEST(Png, FixedHuffmanDecodesToTheSameImage) {
  const std::vector<std::uint8_t> stored =
      port::encode_png(port::render_birdseye(small_scene().data(), small_scene().size(), small_options(port::PngDeflate::stored)),
                       port::PngDeflate::stored);
  const std::vector<std::uint8_t> fixed =
      port::encode_png(port::render_birdseye(small_scene().data(), small_scene().size(), small_options(port::PngDeflate::stored)),
                       port::PngDeflate::fixed_huffman);
  DecodedPng a, b;
  ASSERT_TRUE(decode_png(stored, a));
  ASSERT_TRUE(decode_png(fixed, b));
  EXPECT_EQ(b.fixed_blocks, 1);
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_LT(fixed.size() * 20, stored.size());
}

// Every filter type must round-trip. Rows are built so that each filter is the best for some:
// y % 8 = 0 noise; 1 pixels alternating 0/2 under noise (None); 2, 3 a horizontal ramp (Sub,
// then Up); 4, 5 v = 60 + x - y (Average is exact on 5); 6, 7 v = x + y (Paeth is exact on 7).
TEST(Png, AllFilterTypesRoundTrip) {
  port::RgbImage img(97, 61);
  std::uint32_t seed = 12345;
  for (std::uint32_t y = 0; y < img.height; ++y) {
    for (std::uint32_t x = 0; x < img.width; ++x) {
      std::uint8_t* p = img.at(x, y);
      seed = seed * 1103515245u + 12345u;
      for (std::uint32_t c = 0; c < 3; ++c) {
        std::uint32_t v = 0;
        switch (y % 8) {
          case 0: v = seed >> (8 + 8 * c); break;
          case 1: v = (x % 2) * 2; break;
          case 2: case 3: v = x * 2 + c * 10; break;
          case 4: case 5: v = 60 + x - y + c * 10; break;
          default: v = x + y + c * 10; break;
        }
        p[c] = static_cast<std::uint8_t>(v);
      }
    }
  }
  for (port::PngDeflate mode : {port::PngDeflate::stored, port::PngDeflate::fixed_huffman}) {
    const std::vector<std::uint8_t> png = port::encode_png(img, mode);
    DecodedPng d;
    ASSERT_TRUE(decode_png(png, d));
    EXPECT_EQ(d.width, 97u);
    EXPECT_EQ(d.height, 61u);
    EXPECT_EQ(d.rgb, img.rgb);
    for (std::size_t f = 0; f < 5; ++f) EXPECT_GT(d.filter_rows[f], 0) << "filter type " << f << " never used";
  }
}

TEST(Png, ColourRangeHeightModeAndPointRadius) {
  port::PngOptions o = small_options(port::PngDeflate::fixed_huffman);
  o.color_min = 0.0f;
  o.color_max = 200.0f;
  o.point_radius_px = 1;
  std::vector<Point> pts = {make_point(-5.0f, 5.0f, 0, 100), make_point(5.0f, -5.0f, 0, 250)};
  DecodedPng img;
  ASSERT_TRUE(decode_png(port::encode_png(port::render_birdseye(pts.data(), pts.size(), o)), img));
  for (std::uint32_t y = 39; y <= 41; ++y) {
    for (std::uint32_t x = 79; x <= 81; ++x) expect_rgb(img, x, y, kGreen);  // 100 of 0..200
  }
  expect_rgb(img, 78, 40, kBg);
  expect_rgb(img, 80, 42, kBg);
  expect_rgb(img, 160, 120, kRed);  // 250 clamps to the top

  o = small_options(port::PngDeflate::fixed_huffman);
  o.color_by = port::ColorBy::height;  // default -3..+3 m
  pts = {make_point(-5.0f, 5.0f, 0.0f, 0), make_point(5.0f, -5.0f, 3.0f, 0), make_point(5.0f, 5.0f, -10.0f, 255)};
  ASSERT_TRUE(decode_png(port::encode_png(port::render_birdseye(pts.data(), pts.size(), o)), img));
  expect_rgb(img, 80, 40, kGreen);
  expect_rgb(img, 160, 120, kRed);
  expect_rgb(img, 160, 40, kBlue);
}

TEST(Png, InvalidOptionsAreReported) {
  const std::vector<Point> pts = small_scene();
  port::PngOptions o;
  o.width = 10;
  std::string why;
  EXPECT_TRUE(port::render_birdseye(pts.data(), pts.size(), o, &why).rgb.empty());
  EXPECT_NE(why.find("width"), std::string::npos);
  o = port::PngOptions();
  o.range_m = 0.0f;
  const port::WriteResult r = port::write_png(temp_path("bad.png"), pts, o);
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.message().find("range_m"), std::string::npos) << r.message();
  o = port::PngOptions();
  o.color_min = 5.0f;  // max left unset
  EXPECT_FALSE(port::write_png(temp_path("bad.png"), pts, o).ok());
  o = port::PngOptions();
  o.color_min = 5.0f;
  o.color_max = 5.0f;
  EXPECT_FALSE(port::write_png(temp_path("bad.png"), pts, o).ok());
  EXPECT_FALSE(port::write_png("/nonexistent-dir/x.png", pts).ok());
}

// A synthetic street scene: a ground disc, two walls, a "car" and a few retro-reflectors.
std::vector<Point> synthetic_scene() {
  std::vector<Point> v;
  const float kPi = 3.14159265f;
  for (int ring = 1; ring <= 40; ++ring) {  // ground returns on circles every 1.3 m (off the 20 m rings)
    const float r = 1.3f * static_cast<float>(ring);
    const int n = 200 + ring * 40;
    for (int i = 0; i < n; ++i) {
      const float a = 2 * kPi * static_cast<float>(i) / static_cast<float>(n);
      v.push_back(make_point(r * std::sin(a), r * std::cos(a), -1.8f, static_cast<std::uint8_t>(10 + ring % 20)));
    }
  }
  for (int i = 0; i < 3000; ++i) {  // walls at x = -8 m and x = +12 m, y from -55 to 55 m
    const float y = -55.0f + 110.0f * static_cast<float>(i) / 3000.0f;
    v.push_back(make_point(-8.0f, y, 1.0f, 60));
    v.push_back(make_point(12.0f, y, 2.0f, 90));
  }
  for (int i = 0; i <= 40; ++i) {  // a 2 x 4.5 m car outline ahead-left
    const float t = static_cast<float>(i) / 40.0f;
    v.push_back(make_point(-4.0f + 2.0f * t, 15.0f, 0.5f, 140));
    v.push_back(make_point(-4.0f + 2.0f * t, 19.5f, 0.5f, 140));
    v.push_back(make_point(-4.0f, 15.0f + 4.5f * t, 0.5f, 140));
    v.push_back(make_point(-2.0f, 15.0f + 4.5f * t, 0.5f, 140));
  }
  for (int k = 0; k < 6; ++k) {  // retro-reflective signs on the right wall
    for (int i = 0; i < 30; ++i) {
      v.push_back(make_point(11.8f, -40.0f + 16.0f * static_cast<float>(k) + 0.05f * static_cast<float>(i), 2.0f, 250));
    }
  }
  return v;
}

TEST(Png, DefaultViewWithScaleRingsAndLegend) {
  const std::vector<Point> scene = synthetic_scene();
  const char* keep = std::getenv("HESAI_WRITERS_PNG_DIR");  // set to look at the images
  const std::string path = keep != nullptr ? std::string(keep) + "/birdseye_intensity.png" : temp_path("view.png");
  ASSERT_TRUE(port::write_png(path, scene).ok());
  if (keep != nullptr) {
    port::PngOptions o;
    o.color_by = port::ColorBy::height;
    ASSERT_TRUE(port::write_png(std::string(keep) + "/birdseye_height.png", scene, o).ok());
  }
  const std::vector<std::uint8_t> file = read_bytes(path);
  DecodedPng img;
  ASSERT_TRUE(decode_png(file, img));
  EXPECT_EQ(img.width, 1024u);
  EXPECT_EQ(img.height, 1024u);
  EXPECT_LT(file.size(), 1024u * 1024u * 3u / 10u);  // compressed well below a tenth of raw

  // 1024 px over 120 m: 8.533 px/m. Rings every 20 m: the 20 m ring crosses the +x axis
  // 170.7 px right of the centre (512, 512), at pixel 682.
  const std::array<int, 3> ring = {38, 44, 58};
  EXPECT_EQ(img.px(682, 511), ring);
  EXPECT_EQ(img.px(341, 511), ring);  // 20 m ring, -x side: 512 - 170.7 = 341.3
  EXPECT_EQ(img.px(511, 170), ring);  // 40 m ring, +y side: 512 - 341.3 = 170.7
  // The right wall (x = 12 m, intensity 90) at column floor(512 + 102.4) = 614.
  bool wall = false;
  for (std::uint32_t y = 100; y < 900; ++y) wall |= img.px(614, y) != kBg && img.px(614, y) != ring;
  EXPECT_TRUE(wall);
  // Legend (top right): the ramp's red top and blue bottom both appear in the upper right.
  bool red = false, blue = false, white_upper_right = false;
  for (std::uint32_t y = 0; y < 512; ++y) {
    for (std::uint32_t x = 768; x < 1024; ++x) {
      red |= img.px(x, y) == kRed;
      blue |= img.px(x, y) == kBlue;
      white_upper_right |= img.px(x, y) == kWhite;
    }
  }
  EXPECT_TRUE(red);
  EXPECT_TRUE(blue);
  EXPECT_TRUE(white_upper_right);  // labels
  // Scale bar (bottom left): white pixels in the lower-left corner.
  int white = 0;
  for (std::uint32_t y = 900; y < 1024; ++y) {
    for (std::uint32_t x = 0; x < 300; ++x) white += img.px(x, y) == kWhite;
  }
  EXPECT_GT(white, 100);
}

}  // namespace
