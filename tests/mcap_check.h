// A structural MCAP checker for the tests, written from the MCAP specification
// (https://mcap.dev/spec), independent of port/src/formats/mcap.cpp: it walks the records, follows the
// footer, summary offsets, chunk indexes and message indexes, and checks every CRC (with
// crc32_ieee, whose check values test_mcap.cpp proves). Failures are gtest EXPECTs.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "hesai_port/formats/mcap.h"

namespace hesai_test {

inline std::uint64_t le(const std::vector<std::uint8_t>& b, std::size_t at, int n) {
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
inline std::vector<Record> records(const std::vector<std::uint8_t>& b, std::size_t from, std::size_t to) {
  std::vector<Record> out;
  std::size_t at = from;
  while (at < to) {
    EXPECT_LE(at + 9, to) << "record head past the end at " << at;
    if (at + 9 > to) break;
    Record r{b[at], at, at + 9, le(b, at + 1, 8)};
    EXPECT_LE(r.length, to - r.body) << "record at " << at << " overruns";
    if (r.length > to - r.body) break;
    out.push_back(r);
    at = r.body + static_cast<std::size_t>(r.length);  // r.length <= to - r.body: it fits
  }
  EXPECT_EQ(at, to);
  return out;
}

inline std::string str_at(const std::vector<std::uint8_t>& b, std::size_t& at) {
  const auto n = static_cast<std::size_t>(le(b, at, 4));
  std::string s(b.begin() + static_cast<std::ptrdiff_t>(at + 4), b.begin() + static_cast<std::ptrdiff_t>(at + 4 + n));
  at += 4 + n;
  return s;
}

inline const std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};

// What the structural check found.
struct Parsed {
  std::string profile;
  std::vector<Record> summary;
  std::vector<std::pair<std::uint64_t, std::vector<std::uint8_t>>> messages;  // log_time, data (via the index)
  std::vector<std::uint16_t> message_channels;  // messages[i]'s channel id, read from its Message record
  std::uint64_t chunks = 0;
  // Metadata records of the data section, by name: their key-value pairs.
  std::map<std::string, std::map<std::string, std::string>> metadata;
  // Every message of the data section in file order: channel, log_time.
  std::vector<std::pair<std::uint16_t, std::uint64_t>> file_order;
};

// Checks an MCAP file the way a strict indexed reader would, and returns its messages.
inline Parsed check_mcap(const std::vector<std::uint8_t>& b) {
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
  EXPECT_EQ(summary_crc, hesai::port::crc32_ieee(b.data() + summary_start, footer + 25 - summary_start)) << "summary_crc";

  // Header, then the data section up to the Data End, which ends right before the summary.
  const std::vector<Record> head = records(b, 8, 8 + 9 + static_cast<std::size_t>(le(b, 9, 8)));
  EXPECT_EQ(head.size(), 1u);
  std::size_t at = 8 + 9;
  p.profile = str_at(b, at);
  const std::vector<Record> data = records(b, 8, summary_start);
  EXPECT_GE(data.size(), 2u);
  if (data.size() < 2) return p;
  const Record& end = data.back();
  EXPECT_EQ(end.op, 0x0F);
  EXPECT_EQ(end.length, 4u);
  EXPECT_EQ(le(b, end.body, 4), hesai::port::crc32_ieee(b.data(), end.at)) << "data_section_crc: every byte before the Data End";
  std::map<std::size_t, const Record*> by_offset;
  for (const Record& r : data) by_offset[r.at] = &r;
  for (std::size_t i = 1; i + 1 < data.size(); ++i) {
    const Record& r = data[i];
    EXPECT_TRUE(r.op == 0x06 || r.op == 0x07 || r.op == 0x0C) << "data record " << i << " opcode " << int(r.op);
    if (r.op == 0x0C) {  // Metadata: name, then a map of string pairs
      std::size_t m = r.body;
      const std::string name = str_at(b, m);
      const std::size_t map_end = m + 4 + static_cast<std::size_t>(le(b, m, 4));
      EXPECT_EQ(map_end, r.body + r.length) << "metadata " << name;
      std::map<std::string, std::string>& pairs = p.metadata[name];
      for (m += 4; m < map_end;) {
        const std::string k = str_at(b, m);
        pairs[k] = str_at(b, m);
      }
    }
    if (r.op != 0x06) continue;
    ++p.chunks;
    // Chunk: start, end, uncompressed size, CRC, compression "", records.
    const std::uint64_t size = le(b, r.body + 16, 8);
    const auto crc = static_cast<std::uint32_t>(le(b, r.body + 24, 4));
    EXPECT_EQ(le(b, r.body + 28, 4), 0u) << "compression ''";
    EXPECT_EQ(le(b, r.body + 32, 8), size);
    const std::size_t rec = r.body + 40;
    EXPECT_EQ(r.length, 40 + size);
    EXPECT_EQ(crc, hesai::port::crc32_ieee(b.data() + rec, static_cast<std::size_t>(size))) << "chunk at " << r.at;
    for (const Record& inner : records(b, rec, rec + static_cast<std::size_t>(size))) {
      EXPECT_TRUE(inner.op == 0x03 || inner.op == 0x04 || inner.op == 0x05);
      if (inner.op == 0x05)
        p.file_order.emplace_back(static_cast<std::uint16_t>(le(b, inner.body, 2)), le(b, inner.body + 6, 8));
    }
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
  // Metadata indexes: each at a Metadata record of its name and length; statistics count them.
  std::size_t metadata_indexes = 0;
  for (const Record& mi : p.summary) {
    if (mi.op == 0x0B) {
      EXPECT_EQ(le(b, mi.body + 8 + 2 + 4 + 4, 4), p.metadata.size()) << "statistics metadata_count";
    }
    if (mi.op != 0x0D) continue;
    ++metadata_indexes;
    const auto r = by_offset.find(static_cast<std::size_t>(le(b, mi.body, 8)));
    EXPECT_NE(r, by_offset.end()) << "metadata index to no record";
    if (r == by_offset.end()) continue;
    EXPECT_EQ(r->second->op, 0x0C);
    EXPECT_EQ(le(b, mi.body + 8, 8), 9 + r->second->length);
    std::size_t at_name = mi.body + 16, at_record = r->second->body;
    EXPECT_EQ(str_at(b, at_name), str_at(b, at_record));
  }
  EXPECT_EQ(metadata_indexes, p.metadata.size());

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
        p.message_channels.push_back(static_cast<std::uint16_t>(le(b, msg + 9, 2)));
      }
    }
    EXPECT_EQ(map_end + 8 + 4 + 16, ci.body + ci.length);  // message_index_length, "", two sizes
  }
  EXPECT_EQ(indexed_chunks, p.chunks);
  return p;
}

/// A file in the temporary directory that no other test process can be using: its name carries
/// this process's id (two ctest runs of one machine, or two presets, share the directory).
inline std::string temp_path(const char* name) { return testing::TempDir() + std::to_string(getpid()) + "_" + name; }

}  // namespace hesai_test
