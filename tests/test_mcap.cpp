// The MCAP writer and the PointCloud2 encoding (port/), read back by a small parser written here
// from the MCAP specification (https://mcap.dev/spec): record structure, offsets and CRCs.
// The reference reader (npm's @mcap/core) reads the same files in tests/mcap/.
#include <gtest/gtest.h>
#include <gtest/gtest-spi.h>

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "hesai_port/mcap.h"
#include "hesai_port/pointcloud2.h"
#include "test_support.h"

using namespace hesai;
using hesai::port::crc32_ieee;

namespace {

std::uint64_t le(const std::vector<std::uint8_t>& b, std::size_t at, int n) {
  std::uint64_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8) | b.at(at + static_cast<std::size_t>(i));
  return v;
}

// One record: opcode, where its content starts, its length.
struct Record {
  std::uint8_t op = 0;
  std::size_t at = 0;   // offset of the opcode
  std::size_t body = 0; // offset of the content
  std::uint64_t length = 0;
};

// The records of bytes [from, to), which must tile the range exactly.
std::vector<Record> records(const std::vector<std::uint8_t>& b, std::size_t from, std::size_t to) {
  std::vector<Record> out;
  std::size_t at = from;
  while (at < to) {
    EXPECT_LE(at + 9, to) << "record head past the end at " << at;
    if (at + 9 > to) break;
    Record r{b[at], at, at + 9, le(b, at + 1, 8)};
    EXPECT_LE(r.length, to - r.body) << "record at " << at << " overruns";
    if (r.length > to - r.body) break;
    out.push_back(r);
    at = r.body + r.length;
  }
  EXPECT_EQ(at, to);
  return out;
}

std::string str_at(const std::vector<std::uint8_t>& b, std::size_t& at) {
  const auto n = static_cast<std::size_t>(le(b, at, 4));
  std::string s(b.begin() + static_cast<std::ptrdiff_t>(at + 4), b.begin() + static_cast<std::ptrdiff_t>(at + 4 + n));
  at += 4 + n;
  return s;
}

const std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};

// What the structural check found.
struct Parsed {
  std::string profile;
  std::vector<Record> summary;
  std::vector<std::pair<std::uint64_t, std::vector<std::uint8_t>>> messages;  // log_time, data (via the index)
  std::uint64_t chunks = 0;
};

// Checks an MCAP file the way a strict indexed reader would, and returns its messages.
Parsed check_mcap(const std::vector<std::uint8_t>& b) {
  Parsed p;
  EXPECT_GE(b.size(), 8u + 9 + 9 + 20 + 8);
  if (b.size() < 8 + 9 + 9 + 20 + 8) return p;
  EXPECT_EQ(0, std::memcmp(b.data(), kMagic, 8));
  EXPECT_EQ(0, std::memcmp(b.data() + b.size() - 8, kMagic, 8));
  // Footer: the last record before the magic, 20 bytes.
  const std::size_t footer = b.size() - 8 - 9 - 20;
  EXPECT_EQ(b[footer], 0x02);
  EXPECT_EQ(le(b, footer + 1, 8), 20u);
  const auto summary_start = static_cast<std::size_t>(le(b, footer + 9, 8));
  const auto summary_offset_start = static_cast<std::size_t>(le(b, footer + 17, 8));
  const auto summary_crc = static_cast<std::uint32_t>(le(b, footer + 25, 4));
  EXPECT_LT(summary_start, summary_offset_start);
  EXPECT_LE(summary_offset_start, footer);
  // summary_crc: from the summary's start through the footer's summary_offset_start.
  EXPECT_EQ(summary_crc, crc32_ieee(b.data() + summary_start, footer + 25 - summary_start)) << "summary_crc";

  // Header, then the data section up to the Data End, which ends right before the summary.
  const std::vector<Record> head = records(b, 8, 8 + 9 + le(b, 9, 8));
  EXPECT_EQ(head.size(), 1u);
  std::size_t at = 8 + 9;
  p.profile = str_at(b, at);
  const std::vector<Record> data = records(b, 8, summary_start);
  EXPECT_GE(data.size(), 2u);
  if (data.size() < 2) return p;
  const Record& end = data.back();
  EXPECT_EQ(end.op, 0x0F);
  EXPECT_EQ(end.length, 4u);
  EXPECT_EQ(le(b, end.body, 4), crc32_ieee(b.data(), end.at)) << "data_section_crc: every byte before the Data End";
  std::map<std::size_t, const Record*> by_offset;
  for (const Record& r : data) by_offset[r.at] = &r;
  for (std::size_t i = 1; i + 1 < data.size(); ++i) {
    const Record& r = data[i];
    EXPECT_TRUE(r.op == 0x06 || r.op == 0x07) << "data record " << i << " opcode " << int(r.op);
    if (r.op != 0x06) continue;
    ++p.chunks;
    // Chunk: start, end, uncompressed size, CRC, compression "", records.
    const std::uint64_t size = le(b, r.body + 16, 8);
    const auto crc = static_cast<std::uint32_t>(le(b, r.body + 24, 4));
    EXPECT_EQ(le(b, r.body + 28, 4), 0u) << "compression ''";
    EXPECT_EQ(le(b, r.body + 32, 8), size);
    const std::size_t rec = r.body + 40;
    EXPECT_EQ(r.length, 40 + size);
    EXPECT_EQ(crc, crc32_ieee(b.data() + rec, static_cast<std::size_t>(size))) << "chunk at " << r.at;
    for (const Record& inner : records(b, rec, rec + static_cast<std::size_t>(size)))
      EXPECT_TRUE(inner.op == 0x03 || inner.op == 0x04 || inner.op == 0x05);
  }

  // Summary: records grouped by opcode; the Summary Offsets describe the groups exactly.
  p.summary = records(b, summary_start, summary_offset_start);
  std::map<std::uint8_t, std::pair<std::size_t, std::size_t>> groups;  // opcode: start, end
  for (const Record& r : p.summary) {
    auto [it, fresh] = groups.try_emplace(r.op, r.at, r.body + r.length);
    if (!fresh) {
      EXPECT_EQ(it->second.second, r.at) << "summary records of opcode " << int(r.op) << " not grouped";
      it->second.second = r.body + static_cast<std::size_t>(r.length);
    }
  }
  const std::vector<Record> offsets = records(b, summary_offset_start, footer);
  EXPECT_EQ(offsets.size(), groups.size());
  for (const Record& o : offsets) {
    EXPECT_EQ(o.op, 0x0E);
    const auto g = groups.find(b[o.body]);
    EXPECT_NE(g, groups.end()) << "summary offset for a missing group";
    if (g == groups.end()) continue;
    EXPECT_EQ(le(b, o.body + 1, 8), g->second.first);
    EXPECT_EQ(le(b, o.body + 9, 8), g->second.second - g->second.first);
  }
  EXPECT_TRUE(groups.count(0x04) && groups.count(0x0B)) << "channels and statistics in the summary";

  // Chunk indexes: point at the chunks and their message indexes, which point at the messages.
  std::uint64_t indexed_chunks = 0;
  for (const Record& ci : p.summary) {
    if (ci.op != 0x08) continue;
    ++indexed_chunks;
    const auto chunk_at = static_cast<std::size_t>(le(b, ci.body + 16, 8));
    const auto c = by_offset.find(chunk_at);
    EXPECT_NE(c, by_offset.end()) << "chunk index to no record";
    if (c == by_offset.end()) continue;
    EXPECT_EQ(c->second->op, 0x06);
    EXPECT_EQ(le(b, ci.body + 24, 8), 9 + c->second->length);
    EXPECT_EQ(le(b, ci.body + 0, 8), le(b, c->second->body, 8));     // message_start_time
    EXPECT_EQ(le(b, ci.body + 8, 8), le(b, c->second->body + 8, 8)); // message_end_time
    const std::size_t rec = c->second->body + 40;
    std::size_t m = ci.body + 32;
    const std::size_t map_end = m + 4 + static_cast<std::size_t>(le(b, m, 4));
    for (m += 4; m < map_end; m += 10) {
      const auto mi = by_offset.find(static_cast<std::size_t>(le(b, m + 2, 8)));
      EXPECT_NE(mi, by_offset.end()) << "message index offset to no record";
      if (mi == by_offset.end()) continue;
      EXPECT_EQ(mi->second->op, 0x07);
      EXPECT_EQ(le(b, mi->second->body, 2), le(b, m, 2));  // channel
      const std::size_t list = mi->second->body + 2;
      const std::size_t n = static_cast<std::size_t>(le(b, list, 4)) / 16;
      for (std::size_t k = 0; k < n; ++k) {
        const std::uint64_t t = le(b, list + 4 + 16 * k, 8);
        const std::size_t msg = rec + static_cast<std::size_t>(le(b, list + 12 + 16 * k, 8));
        EXPECT_EQ(b.at(msg), 0x05);
        EXPECT_EQ(le(b, msg + 9 + 6, 8), t) << "message index time is the message's log_time";
        const std::size_t len = static_cast<std::size_t>(le(b, msg + 1, 8)) - 22;
        p.messages.emplace_back(t, std::vector<std::uint8_t>(b.begin() + static_cast<std::ptrdiff_t>(msg + 31),
                                                             b.begin() + static_cast<std::ptrdiff_t>(msg + 31 + len)));
      }
    }
    EXPECT_EQ(map_end + 8 + 4 + 16, ci.body + ci.length);  // message_index_length, "", two sizes
  }
  EXPECT_EQ(indexed_chunks, p.chunks);
  return p;
}

// The failure messages check_mcap() reports for `b`, one a line; empty when it finds none.
std::string failures_of(const std::vector<std::uint8_t>& b) {
  testing::TestPartResultArray results;
  {
    testing::ScopedFakeTestPartResultReporter reporter(
        testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &results);
    check_mcap(b);
  }
  std::string all;
  for (int i = 0; i < results.size(); ++i) all += std::string(results.GetTestPartResult(i).message()) + "\n";
  return all;
}

TEST(Crc32Ieee, CatalogueCheckValue) {
  // CRC-32/ISO-HDLC ("CRC-32", zlib) of "123456789": 0xCBF43926 (the CRC catalogue).
  EXPECT_EQ(crc32_ieee("123456789", 9), 0xCBF43926u);
  EXPECT_EQ(crc32_ieee("", 0), 0u);
  // "The quick brown fox jumps over the lazy dog": 0x414FA339 (zlib's crc32 of it).
  EXPECT_EQ(crc32_ieee("The quick brown fox jumps over the lazy dog", 43), 0x414FA339u);
}

TEST(Crc32Ieee, SplitAtEveryOffsetAndCombined) {
  const char* text = "123456789";
  for (std::size_t k = 0; k <= 9; ++k) {
    EXPECT_EQ(crc32_ieee(text + k, 9 - k, crc32_ieee(text, k)), 0xCBF43926u) << k;
    EXPECT_EQ(port::crc32_ieee_combine(crc32_ieee(text, k), crc32_ieee(text + k, 9 - k), 9 - k), 0xCBF43926u) << k;
  }
  std::vector<std::uint8_t> big(3000001);
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<std::uint8_t>(i * 7 + (i >> 9));
  const std::uint32_t whole = crc32_ieee(big.data(), big.size());
  for (const std::size_t k : {std::size_t{1}, std::size_t{4096}, std::size_t{1234567}}) {
    const std::uint32_t a = crc32_ieee(big.data(), k), c = crc32_ieee(big.data() + k, big.size() - k);
    EXPECT_EQ(port::crc32_ieee_combine(a, c, big.size() - k), whole) << k;
  }
}

std::string temp_path(const char* name) { return testing::TempDir() + name; }

TEST(McapWriter, RecordsOffsetsAndCrcsOfChunkedMessages) {
  const std::string path = temp_path("hesai_test_writer.mcap");
  port::McapWriter w;
  ASSERT_TRUE(w.open(path, "ros2", "test"));
  const std::uint16_t s = w.add_schema("pkg/msg/Thing", "ros2msg", "uint8 a\n");
  const std::uint16_t c = w.add_channel(s, "/thing", "cdr", {{"k", "v"}});
  // 5 messages of 400 000 bytes: a chunk closes once its records reach 1 MiB, so after the third
  // message (1 200 000 + records) and at the end: two chunks.
  std::vector<std::vector<std::uint8_t>> sent;
  for (std::uint32_t i = 0; i < 5; ++i) {
    std::vector<std::uint8_t> m(400000);
    for (std::size_t k = 0; k < m.size(); ++k) m[k] = static_cast<std::uint8_t>(k * (i + 3));
    const std::uint64_t t = 1000 + 10 * i;
    if (i % 2 == 0) {
      ASSERT_TRUE(w.write_message(c, i, t, t, m.data(), m.size()));
    } else {  // in pieces
      ASSERT_TRUE(w.begin_message(c, i, t, t, m.size()));
      ASSERT_TRUE(w.append(m.data(), 123));
      ASSERT_TRUE(w.append(m.data() + 123, m.size() - 123));
      ASSERT_TRUE(w.end_message());
    }
    sent.push_back(m);
  }
  ASSERT_TRUE(w.close());
  const std::vector<std::uint8_t> b = hesai_test::read_file(path);
  const Parsed p = check_mcap(b);
  EXPECT_EQ(p.profile, "ros2");
  EXPECT_EQ(p.chunks, 2u);
  ASSERT_EQ(p.messages.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(p.messages[i].first, 1000 + 10 * i);
    EXPECT_TRUE(p.messages[i].second == sent[i]) << i;
  }
  // Statistics: 5 messages, 1 schema, 1 channel, 2 chunks, times 1000..1040.
  for (const Record& r : p.summary) {
    if (r.op != 0x0B) continue;
    EXPECT_EQ(le(b, r.body, 8), 5u);
    EXPECT_EQ(le(b, r.body + 8, 2), 1u);
    EXPECT_EQ(le(b, r.body + 10, 4), 1u);
    EXPECT_EQ(le(b, r.body + 22, 4), 2u);
    EXPECT_EQ(le(b, r.body + 26, 8), 1000u);
    EXPECT_EQ(le(b, r.body + 34, 8), 1040u);
  }
  std::remove(path.c_str());
}

TEST(McapWriter, TheCheckerCatchesAFlippedByte) {
  const std::string path = temp_path("hesai_test_writer_flip.mcap");
  port::McapWriter w;
  ASSERT_TRUE(w.open(path, "ros2", "test"));
  const std::uint16_t c = w.add_channel(0, "/x", "cdr", {});
  ASSERT_TRUE(w.write_message(c, 0, 5, 5, "abcdefgh", 8));
  ASSERT_TRUE(w.close());
  std::vector<std::uint8_t> b = hesai_test::read_file(path);
  EXPECT_EQ(failures_of(b), "");
  // The message's last byte: the chunk's CRC and the data section's no longer match.
  std::size_t at = 0;
  for (std::size_t i = 0; i + 8 <= b.size(); ++i)
    if (std::memcmp(b.data() + i, "abcdefgh", 8) == 0) at = i + 7;
  ASSERT_NE(at, 0u);
  b[at] ^= 1;
  std::string f = failures_of(b);
  EXPECT_NE(f.find("chunk at"), std::string::npos) << f;
  EXPECT_NE(f.find("data_section_crc"), std::string::npos) << f;
  b[at] ^= 1;
  b[b.size() - 8 - 1] ^= 1;  // the footer's summary_crc
  f = failures_of(b);
  EXPECT_NE(f.find("summary_crc"), std::string::npos) << f;
  EXPECT_EQ(f.find("chunk at"), std::string::npos) << f;
  std::remove(path.c_str());
}

TEST(McapWriter, MessageSizeMustMatchAndPipesAreRefused) {
  const std::string path = temp_path("hesai_test_writer_bad.mcap");
  port::McapWriter w;
  ASSERT_TRUE(w.open(path, "ros2", "test"));
  const std::uint16_t c = w.add_channel(0, "/x", "cdr", {});
  ASSERT_TRUE(w.begin_message(c, 0, 1, 1, 10));
  EXPECT_FALSE(w.append("0123456789ab", 12));
  EXPECT_FALSE(w.close());
  std::remove(path.c_str());
  // Chunk headers are rewritten in place: a pipe cannot hold an MCAP file.
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  port::McapWriter piped;
  const port::WriteResult r = piped.open("/dev/fd/" + std::to_string(fds[1]), "ros2", "test");
  EXPECT_FALSE(r);
  EXPECT_EQ(r.os_error(), ESPIPE);
  close(fds[0]);
  close(fds[1]);
}

// The program, started through the emulator in cross builds (qemu-user).
std::string cli() {
#if defined(HESAI_CLI_EMULATOR)
  return std::string(HESAI_CLI_EMULATOR) + " " + HESAI_CLI_PATH;
#else
  return HESAI_CLI_PATH;
#endif
}

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
  for (const auto& [t, data] : p.messages) {
    ASSERT_GE(data.size(), 4u + 32);
    const std::vector<std::uint8_t> head = port::pointcloud2_head(0, "xt32", 0);
    const std::uint64_t width = le(data, 4 + 24, 4);  // after "xt32" + NUL (5, padded to 8)
    EXPECT_EQ(data.size(), head.size() + 32 * width + 1);
    EXPECT_EQ(le(data, 4 + 8, 4), 5u);
    EXPECT_EQ(0, std::memcmp(data.data() + 4 + 12, "xt32", 5));
    EXPECT_EQ(le(data, 0 + 4, 4) * 1000000000ull + le(data, 4 + 4, 4), t) << "log_time is header.stamp";
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

TEST(PointCloud2, HeadBytesCheckedByHand) {
  // stamp 1 700 000 000.123456789 s, frame "hesai", 2 points.
  const std::vector<std::uint8_t> h = port::pointcloud2_head(1700000000123456789, "hesai", 2);
  // Offsets after the 4-byte encapsulation (CDR alignment counts from there): stamp.sec 0,
  // nanosec 4, frame_id length 8 ("hesai" + NUL = 6) and bytes 12..17, pad to 20: height 20,
  // width 24, field count 28; ten fields of 16 + (name + NUL rounded up to 4) bytes each, names
  // x y z (4 each) intensity 12 return_type 12 channel 8 azimuth 8 elevation 12 distance 12
  // time_stamp 12: 248 bytes from 32 to 280; is_bigendian 280, pad, point_step 284, row_step 288,
  // data length 292; data from 296: 300 bytes with the encapsulation.
  ASSERT_EQ(h.size(), 300u);
  const std::uint8_t enc[4] = {0, 1, 0, 0};
  EXPECT_EQ(0, std::memcmp(h.data(), enc, 4));
  EXPECT_EQ(le(h, 4 + 0, 4), 1700000000u);
  EXPECT_EQ(le(h, 4 + 4, 4), 123456789u);
  EXPECT_EQ(le(h, 4 + 8, 4), 6u);
  EXPECT_EQ(0, std::memcmp(h.data() + 4 + 12, "hesai", 6));
  EXPECT_EQ(le(h, 4 + 20, 4), 1u);
  EXPECT_EQ(le(h, 4 + 24, 4), 2u);
  EXPECT_EQ(le(h, 4 + 28, 4), 10u);
  // The first field: "x", offset 0, FLOAT32 (7), count 1.
  EXPECT_EQ(le(h, 4 + 32, 4), 2u);
  EXPECT_EQ(h[4 + 36], 'x');
  EXPECT_EQ(le(h, 4 + 40, 4), 0u);
  EXPECT_EQ(h[4 + 44], 7);
  EXPECT_EQ(le(h, 4 + 48, 4), 1u);
  // The last field, time_stamp (28 bytes, 252..280): name length 11 at 252, name at 256, offset 28
  // at 268, UINT32 (6) at 272, count 1 at 276.
  EXPECT_EQ(le(h, 4 + 252, 4), 11u);
  EXPECT_EQ(0, std::memcmp(h.data() + 4 + 256, "time_stamp", 11));
  EXPECT_EQ(le(h, 4 + 280 - 12, 4), 28u);
  EXPECT_EQ(h[4 + 280 - 8], 6);
  EXPECT_EQ(le(h, 4 + 280 - 4, 4), 1u);
  EXPECT_EQ(h[4 + 280], 0);  // is_bigendian
  EXPECT_EQ(le(h, 4 + 284, 4), 32u);
  EXPECT_EQ(le(h, 4 + 288, 4), 64u);
  EXPECT_EQ(le(h, 4 + 292, 4), 64u);
  EXPECT_EQ(port::pointcloud2_size(h.size(), 2), 300u + 64 + 1);
}

TEST(PointCloud2, PointRecordCheckedByHand) {
  Point p;
  p.x = 1.5f;            // 0x3FC00000
  p.y = -2.0f;           // 0xC0000000
  p.z = 0.25f;           // 0x3E800000
  p.intensity = 200;
  p.return_index = 1;
  p.channel = 5;         // nebula's 0-based channel 4
  p.azimuth_deg = 180;   // pi as float32: 0x40490FDB
  p.elevation_deg = 90;  // pi/2: 0x3FC90FDB
  p.distance_m = 8.0f;   // 0x41000000
  p.time_ns = 1000000000 + 70000;
  std::uint8_t r[32];
  port::encode_point(p, 1000000000, r);
  const std::vector<std::uint8_t> v(r, r + 32);
  EXPECT_EQ(le(v, 0, 4), 0x3FC00000u);
  EXPECT_EQ(le(v, 4, 4), 0xC0000000u);
  EXPECT_EQ(le(v, 8, 4), 0x3E800000u);
  EXPECT_EQ(v[12], 200);
  EXPECT_EQ(v[13], 1);
  EXPECT_EQ(le(v, 14, 2), 4u);
  EXPECT_EQ(le(v, 16, 4), 0x40490FDBu);
  EXPECT_EQ(le(v, 20, 4), 0x3FC90FDBu);
  EXPECT_EQ(le(v, 24, 4), 0x41000000u);
  EXPECT_EQ(le(v, 28, 4), 70000u);
}

TEST(PointCloud2, DefinitionAsRosbag2WritesIt) {
  const std::string& d = port::pointcloud2_definition();
  const std::string rule = "\n" + std::string(80, '=') + "\nMSG: ";
  EXPECT_EQ(d.rfind("# This message holds a collection of N-dimensional points", 0), 0u);
  const std::size_t pf = d.find(rule + "sensor_msgs/PointField\n");
  const std::size_t hd = d.find(rule + "std_msgs/Header\n");
  const std::size_t tm = d.find(rule + "builtin_interfaces/Time\n");
  ASSERT_NE(pf, std::string::npos);
  ASSERT_NE(hd, std::string::npos);
  ASSERT_NE(tm, std::string::npos);
  EXPECT_LT(pf, hd);
  EXPECT_LT(hd, tm);
  // The definition's fields, as the .msg files declare them.
  for (const char* line : {"\nstd_msgs/Header header\n", "\nPointField[] fields\n", "\nuint8[] data ",
                           "\nuint8 FLOAT32 = 7\n", "\nbuiltin_interfaces/Time stamp\n", "\nuint32 nanosec\n"})
    EXPECT_NE(d.find(line), std::string::npos) << line;
}

}  // namespace
