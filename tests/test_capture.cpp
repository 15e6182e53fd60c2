// Capture-file reader (port/): pcap and pcapng, link layers, IP, UDP, damaged files.
//
// Expected values come from the file-format specifications (draft-ietf-opsawg-pcap,
// draft-ietf-opsawg-pcapng, RFC 791/8200/768, IEEE 802.1Q), from the synthetic captures this
// file builds itself, and for the bundled captures from a record walk written here and from
// tshark (dates and counts read off `tshark -r`, and the tshark cross-check at the end).
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>
#include <set>
#include <string>
#include <vector>

#include "hesai_port/capture/capture.h"

namespace {

using hesai::ByteView;
using hesai::port::CaptureError;
using hesai::port::CaptureFile;
using hesai::port::CaptureParser;
using hesai::port::CaptureStatus;
using hesai::port::FrameKind;
using hesai::port::UdpDatagram;
using Bytes = std::vector<std::uint8_t>;

ByteView view(const Bytes& b) { return {b.data(), b.size()}; }

Bytes read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

// ---- A small writer for frames and capture files ------------------------------------------------

void be16(Bytes& b, std::uint32_t v) {
  b.push_back(static_cast<std::uint8_t>(v >> 8));
  b.push_back(static_cast<std::uint8_t>(v));
}
void append(Bytes& b, const Bytes& tail) { b.insert(b.end(), tail.begin(), tail.end()); }
Bytes cat(Bytes a, const Bytes& b) {
  append(a, b);
  return a;
}

// Writes integers in one chosen byte order.
struct Out {
  Bytes b;
  bool big = false;
  void u8(std::uint32_t v) { b.push_back(static_cast<std::uint8_t>(v)); }
  void u16(std::uint32_t v) {
    for (int i = 0; i < 2; ++i) u8(v >> (big ? 8 - 8 * i : 8 * i));
  }
  void u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) u8(v >> (big ? 24 - 8 * i : 8 * i));
  }
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) u8(static_cast<std::uint32_t>(v >> (big ? 56 - 8 * i : 8 * i)));
  }
  void raw(const Bytes& x) { append(b, x); }
  void put32_at(std::size_t at, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) b[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(v >> (big ? 24 - 8 * i : 8 * i));
  }
};

Bytes payload_bytes(std::size_t n, std::uint8_t seed) {
  Bytes p(n);
  for (std::size_t i = 0; i < n; ++i) p[i] = static_cast<std::uint8_t>(seed + 7 * i);
  return p;
}

const Bytes src4 = {192, 168, 1, 201};
const Bytes dst4 = {255, 255, 255, 255};
const Bytes src6 = {0xFE, 0x80, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x01};
const Bytes dst6 = {0xFF, 0x02, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x01};

// UDP header (checksum 0: "not computed" for IPv4) and payload. `len_field` overrides the length.
Bytes udp(std::uint16_t sport, std::uint16_t dport, const Bytes& payload, int len_field = -1) {
  Bytes b;
  be16(b, sport);
  be16(b, dport);
  be16(b, len_field >= 0 ? static_cast<std::uint32_t>(len_field) : static_cast<std::uint32_t>(8 + payload.size()));
  be16(b, 0);
  append(b, payload);
  return b;
}

struct V4 {
  std::uint8_t proto = 17;
  std::uint16_t flags_offset = 0x4000;  // DF
  std::size_t option_words = 0;         // IHL = 5 + option_words
  int ihl_override = -1;
  int total_override = -1;
};
Bytes ipv4(const Bytes& l4, V4 o = {}) {
  Bytes b;
  const std::size_t ihl = 5 + o.option_words;
  b.push_back(static_cast<std::uint8_t>(0x40 | (o.ihl_override >= 0 ? o.ihl_override : static_cast<int>(ihl))));
  b.push_back(0);
  be16(b, o.total_override >= 0 ? static_cast<std::uint32_t>(o.total_override) : static_cast<std::uint32_t>(ihl * 4 + l4.size()));
  be16(b, 0x1234);  // identification
  be16(b, o.flags_offset);
  b.push_back(64);  // TTL
  b.push_back(o.proto);
  be16(b, 0);  // header checksum: not checked by the reader
  append(b, src4);
  append(b, dst4);
  for (std::size_t i = 0; i < o.option_words; ++i) append(b, {1, 1, 1, 1});  // NOP options
  append(b, l4);
  return b;
}

// IPv6 header; `after` holds the extension headers and the upper-layer header.
Bytes ipv6(std::uint8_t next, const Bytes& after) {
  Bytes b = {0x60, 0, 0, 0};
  be16(b, static_cast<std::uint32_t>(after.size()));
  b.push_back(next);
  b.push_back(64);
  append(b, src6);
  append(b, dst6);
  append(b, after);
  return b;
}
// Hop-by-hop or destination options header of 8 bytes (one PadN option), then `rest`.
Bytes ext8(std::uint8_t next, const Bytes& rest) {
  // Sized once, not grown by insert: g++ 12 -O3 reports a false -Warray-bounds on the insert
  // into an 8-byte vector (armhf cross build).
  Bytes b(8 + rest.size(), 0);
  b[0] = next;
  b[2] = 1;  // PadN
  b[3] = 4;  // of 4 bytes
  std::copy(rest.begin(), rest.end(), b.begin() + 8);
  return b;
}
// Destination options header of 16 bytes (Hdr Ext Len 1), then `rest`.
Bytes ext16(std::uint8_t next, const Bytes& rest) {
  Bytes b = {next, 1, 1, 12, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  append(b, rest);
  return b;
}
// Routing header type 0 with no segments left (8 bytes).
Bytes routing8(std::uint8_t next, const Bytes& rest) {
  Bytes b = {next, 0, 0, 0, 0, 0, 0, 0};
  append(b, rest);
  return b;
}
Bytes fragment8(std::uint8_t next, const Bytes& rest) {
  Bytes b = {next, 0, 0x00, 0x01, 0, 0, 0, 42};  // offset 0, M = 1
  append(b, rest);
  return b;
}

Bytes ethernet(std::uint16_t type, const Bytes& l3, const std::vector<std::uint16_t>& tags = {}) {
  Bytes b = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x00, 0x21, 0x1C, 0x00, 0x00, 0x01};
  for (std::size_t i = 0; i < tags.size(); ++i) {
    be16(b, tags[i]);
    be16(b, 0x0000u | static_cast<std::uint32_t>(100 + i));  // TCI: VLAN id 100, 101, ...
  }
  be16(b, type);
  append(b, l3);
  return b;
}
Bytes sll(std::uint16_t proto, const Bytes& l3) {
  Bytes b = {0x00, 0x00, 0x00, 0x01, 0x00, 0x06, 0x00, 0x21, 0x1C, 0x00, 0x00, 0x01, 0x00, 0x00};
  be16(b, proto);
  append(b, l3);
  return b;
}
Bytes sll2(std::uint16_t proto, const Bytes& l3) {
  Bytes b;
  be16(b, proto);
  be16(b, 0);                            // reserved
  append(b, {0, 0, 0, 2});               // interface index
  append(b, {0x00, 0x01});               // ARPHRD_ETHER
  append(b, {0x00, 0x06});               // packet type, address length
  append(b, {0x00, 0x21, 0x1C, 0x00, 0x00, 0x01, 0x00, 0x00});
  append(b, l3);
  return b;
}
Bytes null_link(std::uint32_t family, bool big, const Bytes& l3) {
  Out o;
  o.big = big;
  o.u32(family);
  o.raw(l3);
  return o.b;
}

Bytes eth_udp(std::uint16_t sport, std::uint16_t dport, const Bytes& payload) {
  return ethernet(0x0800, ipv4(udp(sport, dport, payload)));
}
Bytes eth_arp() {
  Bytes arp = {0, 1, 8, 0, 6, 4, 0, 1, 0, 0x21, 0x1C, 0, 0, 1, 192, 168, 1, 201,
               0, 0, 0, 0, 0, 0, 192, 168, 1, 1};
  return ethernet(0x0806, arp);
}
Bytes eth_tcp() {
  Bytes tcp(20, 0);
  tcp[12] = 0x50;
  return ethernet(0x0800, ipv4(tcp, V4{6}));
}

// Classic pcap writer.
struct PcapRec {
  std::uint32_t sec, frac;
  Bytes data;
  std::uint32_t orig = 0;  // 0: data.size()
};
struct File {
  Bytes bytes;
  std::vector<std::size_t> starts;  // offset of each record / block
  std::vector<std::size_t> ends;    // offset past it
  std::vector<bool> udp;            // a packet record with a complete UDP datagram
};
File pcap_file(bool big, bool ns, std::uint32_t link, std::uint32_t snaplen, const std::vector<PcapRec>& recs) {
  Out o;
  o.big = big;
  o.u32(ns ? 0xA1B23C4Du : 0xA1B2C3D4u);
  o.u16(2);
  o.u16(4);
  o.u32(0);
  o.u32(0);
  o.u32(snaplen);
  o.u32(link);
  File f;
  for (const PcapRec& r : recs) {
    f.starts.push_back(o.b.size());
    o.u32(r.sec);
    o.u32(r.frac);
    o.u32(static_cast<std::uint32_t>(r.data.size()));
    o.u32(r.orig != 0 ? r.orig : static_cast<std::uint32_t>(r.data.size()));
    o.raw(r.data);
    f.ends.push_back(o.b.size());
    f.udp.push_back(true);
  }
  f.bytes = o.b;
  return f;
}

// pcapng writer: blocks appended in the byte order of the current section.
struct Pcapng {
  Out o;
  File f;
  void block(std::uint32_t type, const Bytes& body, bool packet = false) {
    f.starts.push_back(o.b.size());
    const std::size_t padded = (body.size() + 3) / 4 * 4;
    o.u32(type);
    o.u32(static_cast<std::uint32_t>(12 + padded));
    o.raw(body);
    for (std::size_t i = body.size(); i < padded; ++i) o.u8(0);
    o.u32(static_cast<std::uint32_t>(12 + padded));
    f.ends.push_back(o.b.size());
    f.udp.push_back(packet);
  }
  Out body() const {
    Out b;
    b.big = o.big;
    return b;
  }
  void shb(bool big) {
    o.big = big;
    Out b = body();
    b.u32(0x1A2B3C4Du);
    b.u16(1);
    b.u16(0);
    b.u64(~std::uint64_t{0});  // section length not given
    block(0x0A0D0D0Au, b.b);
  }
  // tsresol < 0: option absent. tsoffset: if_tsoffset in seconds when nonzero.
  void idb(std::uint16_t link, std::uint32_t snaplen, int tsresol = -1, std::int64_t tsoffset = 0) {
    Out b = body();
    b.u16(link);
    b.u16(0);
    b.u32(snaplen);
    if (tsresol >= 0) {
      b.u16(9);
      b.u16(1);
      b.u32(0);
      b.b[b.b.size() - 4] = static_cast<std::uint8_t>(tsresol);
    }
    if (tsoffset != 0) {
      b.u16(14);
      b.u16(8);
      b.u64(static_cast<std::uint64_t>(tsoffset));
    }
    if (tsresol >= 0 || tsoffset != 0) {
      b.u16(0);
      b.u16(0);
    }
    block(1, b.b);
  }
  void epb(std::uint32_t iface, std::uint64_t ts, const Bytes& data, std::uint32_t orig = 0, bool udp_ok = true) {
    Out b = body();
    b.u32(iface);
    b.u32(static_cast<std::uint32_t>(ts >> 32));
    b.u32(static_cast<std::uint32_t>(ts));
    b.u32(static_cast<std::uint32_t>(data.size()));
    b.u32(orig != 0 ? orig : static_cast<std::uint32_t>(data.size()));
    b.raw(data);
    block(6, b.b, udp_ok);
  }
  void pb(std::uint16_t iface, std::uint64_t ts, const Bytes& data) {
    Out b = body();
    b.u16(iface);
    b.u16(0);
    b.u32(static_cast<std::uint32_t>(ts >> 32));
    b.u32(static_cast<std::uint32_t>(ts));
    b.u32(static_cast<std::uint32_t>(data.size()));
    b.u32(static_cast<std::uint32_t>(data.size()));
    b.raw(data);
    block(2, b.b, true);
  }
  void spb(const Bytes& data, bool udp_ok = true) {
    Out b = body();
    b.u32(static_cast<std::uint32_t>(data.size()));
    b.raw(data);
    block(3, b.b, udp_ok);
  }
  File done() {
    f.bytes = o.b;
    return f;
  }
};

// Every datagram of a capture, plus the final status.
struct Parsed {
  CaptureError open = CaptureError::ok;
  std::vector<UdpDatagram> datagrams;
  CaptureStatus last = CaptureStatus::error;
  CaptureError error = CaptureError::ok;
  std::uint64_t error_offset = 0;
  hesai::port::CaptureStats stats;
};
Parsed parse_all(ByteView file) {
  Parsed p;
  CaptureParser parser;
  p.open = parser.open(file);
  UdpDatagram d;
  // Each record takes at least 12 bytes, so more calls than this means the parser loops.
  for (std::size_t guard = 0; guard < file.size / 12 + 3; ++guard) {
    p.last = parser.next(d);
    if (p.last != CaptureStatus::datagram) break;
    p.datagrams.push_back(d);
  }
  p.error = parser.error();
  p.error_offset = parser.error_offset();
  p.stats = parser.stats();
  return p;
}

std::vector<std::uint8_t> payload_of(const UdpDatagram& d) {
  return Bytes(d.payload.data, d.payload.data + d.payload.size);
}

// ---- The bundled captures -----------------------------------------------------------------------

struct Bundled {
  const char* file;
  std::size_t packets;       // tshark -r FILE | wc -l
  std::size_t payload;       // Hesai payload bytes (manuals: 1262 Pandar40P, 1198 Pandar64 + seq, 1127 QT128)
  std::uint64_t first_ns;    // first frame's time, tshark frame.time_epoch
  std::uint8_t first_bytes[2];  // FF EE block preamble (Pandar40P), EE FF pre-header (Pandar64, QT128)
};

void PrintTo(const Bundled& b, std::ostream* os) { *os << b.file; }

class BundledCapture : public testing::TestWithParam<Bundled> {};

TEST_P(BundledCapture, MatchesAnIndependentRecordWalk) {
  const Bundled& c = GetParam();
  const Bytes file = read_file(std::string(HESAI_DATA_DIR) + "/" + c.file);
  // Ethernet II (14) + IPv4 without options (20) + UDP (8) per record.
  const std::size_t record = 16 + 14 + 20 + 8 + c.payload;
  ASSERT_EQ(file.size(), 24 + c.packets * record);

  // A walk of the little-endian microsecond pcap records, outside the parser.
  ASSERT_GE(file.size(), 24u);
  EXPECT_EQ(hesai::load_le32(file.data()), 0xA1B2C3D4u);
  std::vector<std::size_t> data_offsets;
  std::size_t off = 24;
  while (off + 16 <= file.size()) {
    const std::size_t incl = hesai::load_le32(file.data() + off + 8);
    data_offsets.push_back(off + 16);
    off += 16 + incl;
  }
  EXPECT_EQ(off, file.size());
  ASSERT_EQ(data_offsets.size(), c.packets);
  EXPECT_EQ(std::uint64_t{hesai::load_le32(file.data() + 24)} * 1000000000u +
                std::uint64_t{hesai::load_le32(file.data() + 28)} * 1000u,
            c.first_ns);

  CaptureParser parser;
  ASSERT_EQ(parser.open(view(file)), CaptureError::ok);
  EXPECT_EQ(parser.format(), hesai::port::CaptureFormat::pcap);
  EXPECT_FALSE(parser.big_endian());
  EXPECT_EQ(parser.pcap_link_type(), 1u);
  UdpDatagram d;
  std::size_t n = 0;
  std::uint64_t first_ns = 0;
  while (parser.next(d) == CaptureStatus::datagram) {
    ASSERT_LT(n, data_offsets.size());
    if (n == 0) first_ns = d.time_ns;
    EXPECT_EQ(d.record_index, n);
    EXPECT_EQ(d.file_offset + 16, data_offsets[n]);
    EXPECT_EQ(static_cast<std::size_t>(d.payload.data - file.data()), data_offsets[n] + 42);
    EXPECT_EQ(d.payload.size, c.payload);
    EXPECT_EQ(d.src_port, 10000);
    EXPECT_EQ(d.dst_port, 2368);
    EXPECT_EQ(d.ip_version, 4);
    EXPECT_EQ(Bytes(d.src_addr.begin(), d.src_addr.begin() + 4), src4);
    EXPECT_EQ(Bytes(d.dst_addr.begin(), d.dst_addr.begin() + 4), dst4);
    EXPECT_EQ(d.payload[0], c.first_bytes[0]);
    EXPECT_EQ(d.payload[1], c.first_bytes[1]);
    ++n;
  }
  EXPECT_EQ(parser.error(), CaptureError::ok);
  EXPECT_EQ(n, c.packets);
  EXPECT_EQ(first_ns, c.first_ns);
  EXPECT_EQ(parser.stats().records, c.packets);
  EXPECT_EQ(parser.stats().datagrams, c.packets);
  EXPECT_EQ(parser.stats().skipped(), 0u);
  EXPECT_EQ(parser.next(d), CaptureStatus::end);  // end stays end
}

INSTANTIATE_TEST_SUITE_P(
    Captures, BundledCapture,
    testing::Values(Bundled{"pandar40p_dual.pcap", 1439, 1262, 1673400149311270000u, {0xFF, 0xEE}},
                    Bundled{"pandar64_dual.pcap", 2400, 1198, 1673403880497375000u, {0xEE, 0xFF}},
                    Bundled{"qt128c2x_dual.pcap", 1800, 1127, 1730273788973845000u, {0xEE, 0xFF}}),
    [](const testing::TestParamInfo<Bundled>& i) {
      std::string s = i.param.file;
      return s.substr(0, s.find('.'));
    });

// ---- Classic pcap -------------------------------------------------------------------------------

struct PcapVariant {
  bool big;
  bool ns;
  std::uint8_t magic[4];  // the file's first bytes, from the pcap specification
};
void PrintTo(const PcapVariant& v, std::ostream* os) {
  *os << (v.big ? "big-endian" : "little-endian") << (v.ns ? " ns" : " us");
}

class PcapFormat : public testing::TestWithParam<PcapVariant> {};

TEST_P(PcapFormat, ReadsRecordsInEitherOrderAndResolution) {
  const PcapVariant& v = GetParam();
  const Bytes p0 = payload_bytes(20, 1);
  const Bytes p2 = payload_bytes(5, 2);
  Bytes small = eth_udp(2369, 2370, p2);
  small.resize(60, 0);  // Ethernet minimum frame: padding after the IP datagram
  const File f = pcap_file(v.big, v.ns, 1, 65535,
                           {{1700000000u, v.ns ? 123456789u : 123456u, eth_udp(10000, 2368, p0)},
                            {1700000001u, 0, eth_arp()},
                            {1700000002u, v.ns ? 999999999u : 999999u, small}});
  ASSERT_TRUE(std::equal(v.magic, v.magic + 4, f.bytes.begin()));
  // Version 2.4 in the file's byte order.
  EXPECT_EQ(Bytes(f.bytes.begin() + 4, f.bytes.begin() + 8),
            v.big ? Bytes({0, 2, 0, 4}) : Bytes({2, 0, 4, 0}));

  CaptureParser parser;
  ASSERT_EQ(parser.open(view(f.bytes)), CaptureError::ok);
  EXPECT_EQ(parser.big_endian(), v.big);
  EXPECT_EQ(parser.nanosecond_pcap(), v.ns);
  UdpDatagram d;
  ASSERT_EQ(parser.next(d), CaptureStatus::datagram);
  EXPECT_EQ(d.time_ns, v.ns ? 1700000000123456789u : 1700000000123456000u);
  EXPECT_EQ(d.src_port, 10000);
  EXPECT_EQ(d.dst_port, 2368);
  EXPECT_EQ(payload_of(d), p0);
  EXPECT_EQ(d.file_offset, 24u);
  EXPECT_EQ(d.record_index, 0u);
  ASSERT_EQ(parser.next(d), CaptureStatus::datagram);
  EXPECT_EQ(d.time_ns, v.ns ? 1700000002999999999u : 1700000002999999000u);
  EXPECT_EQ(d.src_port, 2369);
  EXPECT_EQ(d.dst_port, 2370);
  EXPECT_EQ(payload_of(d), p2);  // the UDP length, not the padded frame
  EXPECT_EQ(d.file_offset, f.starts[2]);
  EXPECT_EQ(d.record_index, 2u);
  EXPECT_EQ(parser.next(d), CaptureStatus::end);
  EXPECT_EQ(parser.stats().records, 3u);
  EXPECT_EQ(parser.stats().non_udp, 1u);
  EXPECT_EQ(parser.stats().datagrams, 2u);
}

INSTANTIATE_TEST_SUITE_P(Variants, PcapFormat,
                         testing::Values(PcapVariant{false, false, {0xD4, 0xC3, 0xB2, 0xA1}},
                                         PcapVariant{true, false, {0xA1, 0xB2, 0xC3, 0xD4}},
                                         PcapVariant{false, true, {0x4D, 0x3C, 0xB2, 0xA1}},
                                         PcapVariant{true, true, {0xA1, 0xB2, 0x3C, 0x4D}}),
                         [](const testing::TestParamInfo<PcapVariant>& i) {
                           return std::string(i.param.big ? "Big" : "Little") + (i.param.ns ? "Nano" : "Micro");
                         });

TEST(Pcap, SnapLengthCutsAreCountedNotFatal) {
  const Bytes frame = eth_udp(10000, 2368, payload_bytes(200, 3));
  const Bytes cut(frame.begin(), frame.begin() + 64);
  const File f = pcap_file(false, false, 1, 64,
                           {{1, 0, cut, static_cast<std::uint32_t>(frame.size())},
                            {2, 0, eth_udp(1, 2, payload_bytes(10, 4))}});
  const Parsed p = parse_all(view(f.bytes));
  ASSERT_EQ(p.open, CaptureError::ok);
  EXPECT_EQ(p.last, CaptureStatus::end);
  ASSERT_EQ(p.datagrams.size(), 1u);
  EXPECT_EQ(p.datagrams[0].record_index, 1u);
  EXPECT_EQ(p.stats.truncated, 1u);
  EXPECT_EQ(p.stats.records, p.stats.datagrams + p.stats.skipped());
}

TEST(Pcap, OtherLinkTypes) {
  const Bytes pl = payload_bytes(9, 5);
  struct Case {
    std::uint32_t link;
    Bytes frame;
  };
  const std::vector<Case> cases = {
      {113, sll(0x0800, ipv4(udp(7, 8, pl)))},
      {276, sll2(0x86DD, ipv6(17, udp(7, 8, pl)))},
      {101, ipv4(udp(7, 8, pl))},
      {12, ipv6(17, udp(7, 8, pl))},
      {228, ipv4(udp(7, 8, pl))},
      {229, ipv6(0, ext8(43, routing8(60, ext16(17, udp(7, 8, pl)))))},
      {0, null_link(2, false, ipv4(udp(7, 8, pl)))},
      {0, null_link(30, true, ipv6(17, udp(7, 8, pl)))},
      {108, null_link(2, true, ipv4(udp(7, 8, pl)))},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.link);
    const File f = pcap_file(true, false, c.link, 0, {{1, 2, c.frame}});
    const Parsed p = parse_all(view(f.bytes));
    ASSERT_EQ(p.open, CaptureError::ok);
    ASSERT_EQ(p.datagrams.size(), 1u);
    EXPECT_EQ(p.last, CaptureStatus::end);
    EXPECT_EQ(payload_of(p.datagrams[0]), pl);
    EXPECT_EQ(p.datagrams[0].src_port, 7);
    EXPECT_EQ(p.datagrams[0].dst_port, 8);
    EXPECT_EQ(p.datagrams[0].time_ns, 1000002000u);
  }
}

TEST(Pcap, BadHeaders) {
  const Bytes text = {'t', 'i', 'm', 'e', ',', 'a', 'z', 'i', 'm', 'u', 't', 'h', '\n'};
  Parsed p = parse_all(view(text));
  EXPECT_EQ(p.open, CaptureError::bad_magic);
  EXPECT_EQ(p.last, CaptureStatus::error);
  EXPECT_EQ(parse_all(view(Bytes{'h', 'i'})).open, CaptureError::bad_magic);
  EXPECT_EQ(parse_all(view(Bytes{})).open, CaptureError::truncated);
  EXPECT_EQ(parse_all(view(Bytes{0xD4, 0xC3})).open, CaptureError::truncated);

  File f = pcap_file(false, false, 105, 0, {});  // IEEE 802.11
  CaptureParser parser;
  EXPECT_EQ(parser.open(view(f.bytes)), CaptureError::unsupported_link);
  EXPECT_EQ(parser.error_offset(), 20u);
  f = pcap_file(false, false, 1, 0, {});
  f.bytes[4] = 3;  // major version 3
  EXPECT_EQ(parser.open(view(f.bytes)), CaptureError::bad_magic);
  EXPECT_EQ(parser.error_offset(), 4u);
  // FCS length bits above the link type are not part of it (Ethernet with a 4-byte FCS).
  f = pcap_file(false, false, 0x10000001u | 0x04000000u | 0x40000000u, 0, {{0, 0, eth_udp(1, 2, {1})}});
  EXPECT_EQ(parser.open(view(f.bytes)), CaptureError::ok);
}

TEST(Pcap, AbsurdRecordLengthsGiveTheRecordOffset) {
  const Bytes frame = eth_udp(1, 2, payload_bytes(30, 6));
  const std::vector<PcapRec> recs = {{1, 0, frame}, {2, 0, frame}, {3, 0, frame}};
  const File good = pcap_file(true, false, 1, 65535, recs);
  const std::size_t second = good.starts[1];
  Out o;
  o.big = true;

  struct Case {
    const char* what;
    std::size_t field;  // offset inside the record header
    std::uint32_t value;
    CaptureError expected;
  };
  const Case cases[] = {
      {"incl_len 0xFFFFFFFF", 8, 0xFFFFFFFFu, CaptureError::bad_record},
      {"incl_len above 256 KiB", 8, 256 * 1024 + 1, CaptureError::bad_record},
      {"incl_len above snaplen", 8, 65536, CaptureError::bad_record},
      {"orig_len below incl_len", 12, static_cast<std::uint32_t>(frame.size() - 1), CaptureError::bad_record},
      {"incl_len past the end", 8, 4000, CaptureError::truncated},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    o.b = good.bytes;
    o.put32_at(second + c.field, c.value);
    if (c.field == 8) o.put32_at(second + 12, c.value);  // orig_len = incl_len: only incl_len is wrong
    const Parsed p = parse_all(view(o.b));
    ASSERT_EQ(p.open, CaptureError::ok);
    EXPECT_EQ(p.datagrams.size(), 1u);
    EXPECT_EQ(p.last, CaptureStatus::error);
    EXPECT_EQ(p.error, c.expected);
    EXPECT_EQ(p.error_offset, second);
  }
}

// Cutting a capture anywhere gives its complete records, then a clean end (at a record
// boundary) or capture_truncated at the offset of the cut record. Each cut is a separate heap
// buffer of exactly that size, so AddressSanitizer sees any read past it.
void check_every_cut(const File& f) {
  for (std::size_t len = 0; len <= f.bytes.size(); ++len) {
    SCOPED_TRACE(len);
    std::unique_ptr<std::uint8_t[]> cut(new std::uint8_t[len]);
    if (len > 0) std::memcpy(cut.get(), f.bytes.data(), len);
    const Parsed p = parse_all(ByteView{cut.get(), len});
    const std::size_t header_end = f.starts.empty() ? f.bytes.size() : f.starts[0];
    if (len < header_end && (f.starts.empty() || f.bytes[0] != 0x0A)) {
      EXPECT_EQ(p.open, CaptureError::truncated);
      EXPECT_EQ(p.error_offset, 0u);
      continue;
    }
    std::size_t complete = 0;
    bool boundary = len == header_end;
    std::size_t cut_start = 0;
    for (std::size_t i = 0; i < f.starts.size(); ++i) {
      if (f.ends[i] <= len) {
        if (f.udp[i]) ++complete;
        if (f.ends[i] == len) boundary = true;
      } else if (f.starts[i] < len) {
        cut_start = f.starts[i];
      }
    }
    if (f.bytes[0] == 0x0A && len < f.ends[0]) {  // pcapng: the first section header is cut
      EXPECT_EQ(p.open, CaptureError::truncated);
      EXPECT_EQ(p.error_offset, 0u);
      continue;
    }
    ASSERT_EQ(p.open, CaptureError::ok);
    EXPECT_EQ(p.datagrams.size(), complete);
    if (boundary) {
      EXPECT_EQ(p.last, CaptureStatus::end);
    } else {
      EXPECT_EQ(p.last, CaptureStatus::error);
      EXPECT_EQ(p.error, CaptureError::truncated);
      EXPECT_EQ(p.error_offset, cut_start);
    }
  }
}

TEST(Pcap, EveryCutEndsCleanlyOrAsTruncated) {
  for (bool big : {false, true}) {
    const File f = pcap_file(big, false, 1, 65535,
                             {{1, 0, eth_udp(1, 2, payload_bytes(11, 1))},
                              {2, 0, eth_udp(3, 4, payload_bytes(0, 0))},
                              {3, 0, eth_udp(5, 6, payload_bytes(3, 2))}});
    check_every_cut(f);
  }
}

// ---- pcapng -------------------------------------------------------------------------------------

class PcapngOrder : public testing::TestWithParam<bool> {};

TEST_P(PcapngOrder, SectionsInterfacesAndBlocks) {
  const bool big = GetParam();
  const Bytes p0 = payload_bytes(17, 10), p1 = payload_bytes(18, 11), p2 = payload_bytes(19, 12);
  const Bytes p3 = payload_bytes(20, 13), p4 = payload_bytes(21, 14), p5 = payload_bytes(22, 15);
  Pcapng w;
  w.shb(big);
  w.idb(1, 0);             // Ethernet, no if_tsresol: microseconds
  w.idb(101, 65535, 9);    // raw IP, nanoseconds
  w.idb(113, 65535, 0x94); // SLL, 2^-20 s
  w.block(0x00000BADu, {1, 2, 3, 4, 5});  // custom block: skipped
  w.epb(0, 1700000000123456u, eth_udp(10000, 2368, p0));
  w.epb(1, 1700000000123456789u, ipv4(udp(10001, 2368, p1)));
  w.epb(2, (std::uint64_t{1700000000} << 20) | (1u << 19), sll(0x0800, ipv4(udp(10002, 2368, p2))));
  w.block(5, Bytes(20, 0));  // interface statistics: skipped
  w.epb(0, 1, eth_arp(), 0, false);
  w.spb(eth_udp(10003, 2368, p3));
  w.pb(1, 1700000000000000001u, ipv4(udp(10004, 2368, p4)));
  w.shb(!big);               // a new section in the other byte order: interfaces start again
  w.idb(276, 0, 3, -100);    // SLL2, milliseconds, if_tsoffset -100 s
  w.epb(0, 1700000000005u, sll2(0x0800, ipv4(udp(10005, 2368, p5))));
  const File f = w.done();

  // The section header as the pcapng specification lays it out (block type, length 28, BOM,
  // version 1.0, section length -1, length).
  const Bytes shb_le = {0x0A, 0x0D, 0x0D, 0x0A, 28, 0, 0, 0, 0x4D, 0x3C, 0x2B, 0x1A, 1, 0, 0, 0,
                        0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 28, 0, 0, 0};
  const Bytes shb_be = {0x0A, 0x0D, 0x0D, 0x0A, 0, 0, 0, 28, 0x1A, 0x2B, 0x3C, 0x4D, 0, 1, 0, 0,
                        0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0, 0, 0, 28};
  ASSERT_EQ(Bytes(f.bytes.begin(), f.bytes.begin() + 28), big ? shb_be : shb_le);

  CaptureParser parser;
  ASSERT_EQ(parser.open(view(f.bytes)), CaptureError::ok);
  EXPECT_EQ(parser.format(), hesai::port::CaptureFormat::pcapng);
  EXPECT_EQ(parser.big_endian(), big);
  UdpDatagram d;
  struct Want {
    std::uint16_t sport;
    const Bytes* payload;
    std::uint64_t ns;
    std::uint32_t iface;
    std::uint32_t index;
  };
  const Want want[] = {
      {10000, &p0, 1700000000123456000u, 0, 0},
      {10001, &p1, 1700000000123456789u, 1, 1},
      {10002, &p2, 1700000000500000000u, 2, 2},
      {10003, &p3, 0, 0, 4},  // a Simple Packet Block has no timestamp
      {10004, &p4, 1700000000000000001u, 1, 5},
      {10005, &p5, 1699999900005000000u, 0, 6},
  };
  for (const Want& w8 : want) {
    SCOPED_TRACE(w8.sport);
    ASSERT_EQ(parser.next(d), CaptureStatus::datagram);
    EXPECT_EQ(d.src_port, w8.sport);
    EXPECT_EQ(d.dst_port, 2368);
    EXPECT_EQ(payload_of(d), *w8.payload);
    EXPECT_EQ(d.time_ns, w8.ns);
    EXPECT_EQ(d.interface_id, w8.iface);
    EXPECT_EQ(d.record_index, w8.index);
  }
  EXPECT_EQ(parser.big_endian(), !big);
  EXPECT_EQ(parser.next(d), CaptureStatus::end);
  EXPECT_EQ(parser.stats().records, 7u);
  EXPECT_EQ(parser.stats().non_udp, 1u);
  EXPECT_EQ(parser.stats().other_blocks, 2u);
}

TEST_P(PcapngOrder, EveryCutEndsCleanlyOrAsTruncated) {
  Pcapng w;
  w.shb(GetParam());
  w.idb(1, 0, 9);
  w.epb(0, 5, eth_udp(1, 2, payload_bytes(7, 1)));
  w.block(0x00000BADu, {1, 2, 3});
  w.spb(eth_udp(1, 2, payload_bytes(2, 1)));
  w.shb(!GetParam());
  w.idb(101, 0);
  w.epb(0, 5, ipv4(udp(3, 4, payload_bytes(1, 1))));
  check_every_cut(w.done());
}

TEST_P(PcapngOrder, BadBlocksGiveTheBlockOffset) {
  const bool big = GetParam();
  auto base = [&] {
    Pcapng w;
    w.shb(big);
    w.idb(1, 0);
    w.epb(0, 5, eth_udp(1, 2, payload_bytes(7, 1)));
    return w;
  };
  // Each case appends one bad block after a good packet; the error names that block's offset.
  auto run = [&](const char* what, Pcapng w, CaptureError expected, std::size_t at) {
    SCOPED_TRACE(what);
    const File f = w.done();
    const Parsed p = parse_all(view(f.bytes));
    ASSERT_EQ(p.open, CaptureError::ok);
    EXPECT_EQ(p.datagrams.size(), 1u);
    EXPECT_EQ(p.last, CaptureStatus::error);
    EXPECT_EQ(p.error, expected);
    EXPECT_EQ(p.error_offset, at);
  };
  {
    Pcapng w = base();
    const std::size_t at = w.o.b.size();
    w.epb(0, 6, eth_udp(1, 2, payload_bytes(8, 1)));
    w.o.put32_at(at + 4, 13);  // not a multiple of 4
    run("length 13", w, CaptureError::bad_record, at);
  }
  {
    Pcapng w = base();
    const std::size_t at = w.o.b.size();
    w.block(0x00000BADu, Bytes(12, 0));
    w.o.put32_at(at + 4, 17);   // not a multiple of 4,
    w.o.put32_at(at + 13, 17);  // although the "trailing" length matches
    run("length 17", w, CaptureError::bad_record, at);
  }
  {
    Pcapng w = base();
    const std::size_t at = w.o.b.size();
    w.epb(0, 6, eth_udp(1, 2, payload_bytes(8, 1)));
    w.o.put32_at(at + 4, 8);  // below the 12-byte minimum
    run("length 8", w, CaptureError::bad_record, at);
  }
  {
    Pcapng w = base();
    const std::size_t at = w.o.b.size();
    w.epb(0, 6, eth_udp(1, 2, payload_bytes(8, 1)));
    w.o.put32_at(w.o.b.size() - 4, 1000);  // trailing length differs from the leading one
    run("trailing length", w, CaptureError::bad_record, at);
  }
  {
    Pcapng w = base();
    const std::size_t at = w.o.b.size();
    w.epb(0, 6, eth_udp(1, 2, payload_bytes(8, 1)));
    w.o.put32_at(at + 4, 0xFFFFFFFCu);  // past the end
    run("length 0xFFFFFFFC", w, CaptureError::truncated, at);
  }
  {
    Pcapng w = base();
    const std::size_t at = w.o.b.size();
    w.epb(0, 6, eth_udp(1, 2, payload_bytes(8, 1)));
    w.o.put32_at(at + 20, 0xFFFFFFFFu);  // captured length past the block
    run("captured length", w, CaptureError::bad_record, at);
  }
  {
    Pcapng w = base();
    const std::size_t at = w.o.b.size();
    w.epb(0, 6, eth_udp(1, 2, payload_bytes(8, 1)));
    w.o.put32_at(at + 24, 3);  // original length below the captured length
    run("original length", w, CaptureError::bad_record, at);
  }
  {
    Pcapng w = base();
    const std::size_t at = w.o.b.size();
    w.epb(1, 6, eth_udp(1, 2, payload_bytes(8, 1)));  // only interface 0 exists
    run("interface 1", w, CaptureError::bad_record, at);
  }
  {
    Pcapng w = base();
    const std::size_t at = w.o.b.size();
    w.idb(1, 0, 6);
    w.o.put32_at(at + 8 + 8, big ? 0x00090020u : 0x00200009u);  // if_tsresol claims 32 bytes
    run("option past the block", w, CaptureError::bad_record, at);
  }
  {
    Pcapng w = base();
    const std::size_t at = w.o.b.size();
    w.idb(1, 0, 20);  // 10^-20 s: not representable in 64 bits
    run("tsresol 10^-20", w, CaptureError::bad_record, at);
  }
  {
    Pcapng w = base();
    const std::size_t at = w.o.b.size();
    w.shb(big);
    w.o.b[at + 8] ^= 0xFF;  // byte-order magic spoiled
    run("byte-order magic", w, CaptureError::bad_magic, at);
  }
  {
    Pcapng w = base();
    const std::size_t at = w.o.b.size();
    w.shb(big);
    w.spb(eth_udp(1, 2, payload_bytes(8, 1)));  // the new section has no interface yet
    run("SPB without interface", w, CaptureError::bad_record, at + 28);
  }
  {
    Pcapng w = base();
    const std::size_t at = w.o.b.size();
    w.epb(0, 6, Bytes(12, 0));
    w.o.put32_at(at + 4, 16);  // an EPB too short for its fixed fields
    w.o.put32_at(at + 12, 16);
    run("EPB of 16 bytes", w, CaptureError::bad_record, at);
  }
}

TEST_P(PcapngOrder, OtherLinkTypesAreSkippedNotFatal) {
  Pcapng w;
  w.shb(GetParam());
  w.idb(147, 0);  // LINKTYPE_USER0
  w.idb(1, 0);
  w.epb(0, 1, Bytes(30, 0xAB), 0, false);
  w.epb(1, 1, eth_udp(1, 2, payload_bytes(4, 1)));
  const File f = w.done();
  const Parsed p = parse_all(view(f.bytes));
  ASSERT_EQ(p.open, CaptureError::ok);
  EXPECT_EQ(p.last, CaptureStatus::end);
  EXPECT_EQ(p.datagrams.size(), 1u);
  EXPECT_EQ(p.stats.other_link, 1u);
}

INSTANTIATE_TEST_SUITE_P(ByteOrder, PcapngOrder, testing::Values(false, true),
                         [](const testing::TestParamInfo<bool>& i) { return i.param ? "Big" : "Little"; });

TEST(Pcapng, BadFirstSection) {
  Pcapng w;
  w.shb(false);
  File f = w.done();
  f.bytes[12] = 2;  // major version 2
  EXPECT_EQ(parse_all(view(f.bytes)).open, CaptureError::bad_magic);
  f = w.done();
  f.bytes[4] = 24;  // shorter than a section header can be
  f.bytes[24] = 24;
  EXPECT_EQ(parse_all(view(f.bytes)).open, CaptureError::bad_record);
  f = w.done();
  f.bytes[9] = 0;  // no byte-order magic
  EXPECT_EQ(parse_all(view(f.bytes)).open, CaptureError::bad_magic);
  // An empty pcapng (one section, no interfaces) ends cleanly.
  const Parsed p = parse_all(view(w.done().bytes));
  EXPECT_EQ(p.open, CaptureError::ok);
  EXPECT_EQ(p.last, CaptureStatus::end);
}

// ---- Frames -------------------------------------------------------------------------------------

TEST(Frame, LinkLayersVlanIpAndUdp) {
  const Bytes pl = payload_bytes(13, 9);
  const Bytes u = udp(10000, 2368, pl);
  struct Case {
    const char* what;
    std::uint32_t link;
    Bytes frame;
    FrameKind kind;
    std::uint8_t ip_version;
  };
  V4 with_options;
  with_options.option_words = 2;
  V4 mf;
  mf.flags_offset = 0x2000;
  V4 later_fragment;
  later_fragment.flags_offset = 0x0005;
  V4 ihl4;
  ihl4.ihl_override = 4;
  V4 short_total;
  short_total.total_override = 19;
  V4 tcp;
  tcp.proto = 6;
  const Bytes bad_udp_len = udp(10000, 2368, pl, 7);
  const Bytes long_udp_len = udp(10000, 2368, pl, static_cast<int>(8 + pl.size() + 1));
  Bytes eth_llc = ethernet(0x0026, Bytes(38, 0x42));  // 802.3 length field

  const std::vector<Case> cases = {
      {"ethernet", 1, ethernet(0x0800, ipv4(u)), FrameKind::udp, 4},
      {"802.1Q", 1, ethernet(0x0800, ipv4(u), {0x8100}), FrameKind::udp, 4},
      {"802.1ad + 802.1Q", 1, ethernet(0x0800, ipv4(u), {0x88A8, 0x8100}), FrameKind::udp, 4},
      {"three tags, IPv6", 1, ethernet(0x86DD, ipv6(17, u), {0x88A8, 0x8100, 0x8100}), FrameKind::udp, 6},
      {"SLL IPv6", 113, sll(0x86DD, ipv6(17, u)), FrameKind::udp, 6},
      {"SLL 802.1Q", 113, sll(0x8100, Bytes{0, 5, 0x08, 0x00}), FrameKind::truncated, 0},
      {"SLL2 IPv4", 276, sll2(0x0800, ipv4(u)), FrameKind::udp, 4},
      {"raw v4", 101, ipv4(u), FrameKind::udp, 4},
      {"raw v6 hop-by-hop, routing, destination", 101, ipv6(0, ext8(43, routing8(60, ext16(17, u)))), FrameKind::udp, 6},
      {"raw v6 AH", 229, ipv6(51, cat(Bytes{17, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1}, u)), FrameKind::udp, 6},
      {"IPv4 options", 228, ipv4(u, with_options), FrameKind::udp, 4},
      {"UDP shorter than the IPv4 payload", 228, ipv4(cat(u, Bytes{0xAA, 0xBB, 0xCC})), FrameKind::udp, 4},
      {"UDP shorter than the IPv6 payload", 229, ipv6(17, cat(u, Bytes{0xAA})), FrameKind::udp, 6},
      {"IPv4 DF only", 228, ipv4(u), FrameKind::udp, 4},
      {"IPv4 first fragment", 228, ipv4(u, mf), FrameKind::fragment, 0},
      {"IPv4 later fragment", 228, ipv4(u, later_fragment), FrameKind::fragment, 0},
      {"IPv6 fragment", 229, ipv6(0, ext8(44, fragment8(17, u))), FrameKind::fragment, 0},
      {"IPv4 TCP", 1, ethernet(0x0800, ipv4(Bytes(20, 0), tcp)), FrameKind::non_udp, 0},
      {"IPv6 ICMPv6 after options", 229, ipv6(60, ext8(58, Bytes(8, 0))), FrameKind::non_udp, 0},
      {"ARP", 1, eth_arp(), FrameKind::non_udp, 0},
      {"802.3 LLC", 1, eth_llc, FrameKind::non_udp, 0},
      {"null AF_UNSPEC", 0, null_link(0, false, ipv4(u)), FrameKind::non_udp, 0},
      {"IPv4 IHL 4", 228, ipv4(u, ihl4), FrameKind::malformed, 0},
      {"IPv4 total below IHL", 228, ipv4(u, short_total), FrameKind::malformed, 0},
      {"UDP length 7", 228, ipv4(bad_udp_len), FrameKind::malformed, 0},
      {"UDP length past IP", 228, ipv4(long_udp_len), FrameKind::malformed, 0},
      {"IP version 5", 101, Bytes{0x50, 0, 0, 0}, FrameKind::malformed, 0},
      {"IPv6 header in IPv4 link", 228, ipv6(17, u), FrameKind::malformed, 0},
      {"IPv6 extension past payload", 229, ipv6(60, Bytes{17, 3, 0, 0, 0, 0, 0, 0}), FrameKind::malformed, 0},
      {"short Ethernet", 1, Bytes(10, 0), FrameKind::truncated, 0},
      {"short SLL2", 276, Bytes(19, 0), FrameKind::truncated, 0},
      {"empty raw", 101, Bytes{}, FrameKind::truncated, 0},
      {"802.11", 105, ethernet(0x0800, ipv4(u)), FrameKind::unsupported_link, 0},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    UdpDatagram d;
    ASSERT_EQ(hesai::port::parse_frame(c.link, view(c.frame), d), c.kind);
    if (c.kind != FrameKind::udp) continue;
    EXPECT_EQ(payload_of(d), pl);
    EXPECT_EQ(d.src_port, 10000);
    EXPECT_EQ(d.dst_port, 2368);
    EXPECT_EQ(d.ip_version, c.ip_version);
    if (c.ip_version == 4) {
      EXPECT_EQ(Bytes(d.src_addr.begin(), d.src_addr.begin() + 4), src4);
      EXPECT_EQ(Bytes(d.dst_addr.begin(), d.dst_addr.begin() + 4), dst4);
      EXPECT_EQ(Bytes(d.src_addr.begin() + 4, d.src_addr.end()), Bytes(12, 0));
    } else {
      EXPECT_EQ(Bytes(d.src_addr.begin(), d.src_addr.end()), src6);
      EXPECT_EQ(Bytes(d.dst_addr.begin(), d.dst_addr.end()), dst6);
    }
  }
}

TEST(Frame, EveryCutOfAFrameIsTruncatedOrUdp) {
  const Bytes pl = payload_bytes(6, 1);
  const std::vector<std::pair<std::uint32_t, Bytes>> frames = {
      {1, ethernet(0x0800, ipv4(udp(1, 2, pl)), {0x8100, 0x8100})},
      {229, ipv6(0, ext8(60, ext16(17, udp(1, 2, pl))))},
      {113, sll(0x0800, ipv4(udp(1, 2, pl)))},
  };
  for (const auto& fr : frames) {
    for (std::size_t len = 0; len <= fr.second.size(); ++len) {
      SCOPED_TRACE(len);
      std::unique_ptr<std::uint8_t[]> cut(new std::uint8_t[len]);
      if (len > 0) std::memcpy(cut.get(), fr.second.data(), len);
      UdpDatagram d;
      const FrameKind k = hesai::port::parse_frame(fr.first, ByteView{cut.get(), len}, d);
      EXPECT_EQ(k, len == fr.second.size() ? FrameKind::udp : FrameKind::truncated);
    }
  }
}

// ---- Arbitrary bytes ----------------------------------------------------------------------------

// Mutated captures: whatever the bytes, the parser terminates, stays inside the input and keeps
// its counters consistent. (The libFuzzer harness runs the same entry points.)
TEST(CaptureParserRobustness, MutatedCaptures) {
  std::vector<File> seeds;
  seeds.push_back(pcap_file(false, true, 1, 0, {{1, 2, eth_udp(1, 2, payload_bytes(9, 1))},
                                                {1, 2, ethernet(0x86DD, ipv6(0, ext8(17, udp(1, 2, {1}))), {0x8100})}}));
  {
    Pcapng w;
    w.shb(true);
    w.idb(1, 0, 0x94);
    w.idb(276, 100, 9);
    w.epb(0, 5, eth_udp(1, 2, payload_bytes(9, 1)));
    w.epb(1, 5, sll2(0x0800, ipv4(udp(1, 2, payload_bytes(9, 1)))));
    w.spb(eth_udp(1, 2, payload_bytes(3, 1)));
    w.shb(false);
    w.idb(0, 0);
    w.epb(0, 5, null_link(2, false, ipv4(udp(1, 2, payload_bytes(9, 1)))));
    seeds.push_back(w.done());
  }
  std::uint32_t rng = 12345;
  auto next_rand = [&rng] {
    rng = rng * 1103515245u + 12345u;
    return rng >> 8;
  };
  std::size_t datagrams = 0;
  for (const File& seed : seeds) {
    for (int iter = 0; iter < 20000; ++iter) {
      Bytes b = seed.bytes;
      const std::uint32_t edits = 1 + next_rand() % 4;
      for (std::uint32_t e = 0; e < edits; ++e) {
        const std::size_t at = next_rand() % b.size();
        switch (next_rand() % 4) {
          case 0: b[at] = static_cast<std::uint8_t>(next_rand()); break;
          case 1: b[at] ^= static_cast<std::uint8_t>(1u << (next_rand() % 8)); break;
          case 2: b[at] = 0xFF; break;
          default: b.resize(at + 1); break;
        }
      }
      std::unique_ptr<std::uint8_t[]> exact(new std::uint8_t[b.size()]);
      std::memcpy(exact.get(), b.data(), b.size());
      const ByteView in{exact.get(), b.size()};
      const Parsed p = parse_all(in);
      ASSERT_NE(p.last, CaptureStatus::datagram) << "did not finish";
      EXPECT_EQ(p.stats.records, p.stats.datagrams + p.stats.skipped());
      EXPECT_EQ(p.stats.datagrams, p.datagrams.size());
      for (const UdpDatagram& d : p.datagrams) {
        ASSERT_GE(d.payload.data, in.data);
        ASSERT_LE(d.payload.size, in.size - static_cast<std::size_t>(d.payload.data - in.data));
        ASSERT_LT(d.file_offset, in.size);
      }
      datagrams += p.datagrams.size();
    }
  }
  EXPECT_GT(datagrams, 0u);  // the mutations leave plenty of readable files
}

// ---- CaptureFile --------------------------------------------------------------------------------

std::string temp_path(const char* name) {
  return testing::TempDir() + "hesai_capture_" + std::to_string(getpid()) + "_" + name;
}

TEST(CaptureFile, ReadsABundledCapture) {
  CaptureFile f;
  ASSERT_EQ(f.open(std::string(HESAI_DATA_DIR) + "/pandar64_dual.pcap"), CaptureError::ok) << f.message();
  EXPECT_EQ(f.bytes().size, 3014424u);
  UdpDatagram d;
  std::size_t n = 0;
  while (f.parser().next(d) == CaptureStatus::datagram) ++n;
  EXPECT_EQ(n, 2400u);
  EXPECT_EQ(f.parser().error(), CaptureError::ok);
  EXPECT_EQ(f.message(), "");
}

// The names are what messages print (README: "the message gives its byte offset"); they are the
// names these codes had when they were part of hesai::Error, kept so that messages do not change.
TEST(CaptureError, EveryCodeHasItsOwnName) {
  std::set<std::string> names;
  for (unsigned v = 0; v <= static_cast<unsigned>(hesai::port::kLastCaptureError); ++v) {
    const std::string n = hesai::port::capture_error_name(static_cast<CaptureError>(v));
    EXPECT_NE(n, "unknown") << v;
    EXPECT_TRUE(names.insert(n).second) << n;
  }
  EXPECT_EQ(names, (std::set<std::string>{"ok", "capture_bad_magic", "capture_truncated", "capture_bad_record",
                                          "capture_unsupported_link", "capture_io", "capture_not_open",
                                          "mcap_compressed_chunk", "mcap_chunk_crc_mismatch", "mcap_unknown_schema",
                                          "mcap_unknown_channel", "mcap_bad_encoding", "mcap_bad_cdr",
                                          "mcap_bad_packet_size", "mcap_no_pandar_scan", "mcap_cut"}));
  EXPECT_STREQ(hesai::port::capture_error_name(CaptureError::bad_magic), "capture_bad_magic");
  EXPECT_STREQ(hesai::port::capture_error_name(CaptureError::io), "capture_io");
  EXPECT_STREQ(hesai::port::capture_error_name(
                   static_cast<CaptureError>(static_cast<unsigned>(hesai::port::kLastCaptureError) + 1)),
               "unknown");
}

TEST(CaptureParser, NextBeforeOpenIsAnError) {
  CaptureParser parser;
  UdpDatagram d;
  EXPECT_EQ(parser.next(d), CaptureStatus::error);
  EXPECT_EQ(parser.error(), CaptureError::not_open);
}

TEST(CaptureFile, MissingFileGivesTheErrnoText) {
  CaptureFile f;
  const std::string path = "/nonexistent-hesai-dir/none.pcap";
  EXPECT_EQ(f.open(path), CaptureError::io);
  EXPECT_EQ(f.os_error(), ENOENT);
  const std::string m = f.message();
  EXPECT_NE(m.find(path), std::string::npos) << m;
  EXPECT_NE(m.find(std::strerror(ENOENT)), std::string::npos) << m;
  EXPECT_EQ(f.open(HESAI_DATA_DIR), CaptureError::io);  // a directory
  EXPECT_EQ(f.os_error(), EISDIR);
}

TEST(CaptureFile, NonCaptureAndEmptyFile) {
  CaptureFile f;
  const std::string csv = std::string(HESAI_DATA_DIR) + "/calibration/pandar64_firetimes.csv";
  EXPECT_EQ(f.open(csv), CaptureError::bad_magic);
  EXPECT_EQ(f.os_error(), 0);
  EXPECT_NE(f.message().find("capture_bad_magic at byte 0"), std::string::npos) << f.message();
  UdpDatagram d;
  EXPECT_EQ(f.parser().next(d), CaptureStatus::error);

  const std::string empty = temp_path("empty.pcap");
  { std::ofstream(empty, std::ios::binary); }
  EXPECT_EQ(f.open(empty), CaptureError::truncated);
  EXPECT_NE(f.message().find("empty file"), std::string::npos) << f.message();
  std::remove(empty.c_str());
}

// Resident kilobytes of the mapping that starts at `start`, as /proc/self/smaps counts them.
[[maybe_unused]] long mapping_rss_kb(const void* start) {
  std::ifstream smaps("/proc/self/smaps");
  char head[32];
  std::snprintf(head, sizeof head, "%lx-", reinterpret_cast<unsigned long>(start));
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    if (line.rfind(head, 0) == 0) inside = true;
    else if (inside && line.rfind("Rss:", 0) == 0) return std::stol(line.substr(4));
  }
  return -1;
}

// A 48 MB capture (16 copies of the bundled Pandar64 records) read through CaptureFile::next:
// the same datagrams as a parser over the bytes in memory, and at the end no more than two
// release steps of the file resident (without the release, all 48 MB would be).
TEST(CaptureFile, NextReleasesConsumedPages) {
  const Bytes one = read_file(std::string(HESAI_DATA_DIR) + "/pandar64_dual.pcap");
  Bytes big(one.begin(), one.begin() + 24);
  for (int i = 0; i < 16; ++i) big.insert(big.end(), one.begin() + 24, one.end());
  const std::string path = temp_path("big.pcap");
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(big.data()), static_cast<long>(big.size()));

  CaptureFile f;
  ASSERT_EQ(f.open(path), CaptureError::ok) << f.message();
  CaptureParser reference;
  ASSERT_EQ(reference.open(view(big)), CaptureError::ok);
  UdpDatagram d, r;
  std::size_t n = 0;
  while (f.next(d) == CaptureStatus::datagram) {
    ASSERT_EQ(reference.next(r), CaptureStatus::datagram);
    ASSERT_EQ(d.file_offset, r.file_offset);
    ASSERT_EQ(d.time_ns, r.time_ns);
    ASSERT_EQ(d.payload.size, r.payload.size);
    ASSERT_EQ(std::memcmp(d.payload.data, r.payload.data, d.payload.size), 0) << "datagram " << n;
    ++n;
  }
  EXPECT_EQ(reference.next(r), CaptureStatus::end);
  EXPECT_EQ(n, 16u * 2400u);
  EXPECT_EQ(f.parser().error(), CaptureError::ok);
#if !defined(HESAI_CLI_EMULATOR)  // under qemu-user /proc/self/smaps lists the host's addresses, not the guest's
  const long rss_kb = mapping_rss_kb(f.bytes().data);
  ASSERT_GE(rss_kb, 0) << "mapping not found in /proc/self/smaps";
  EXPECT_LE(rss_kb, static_cast<long>(2 * CaptureFile::kReleaseBytes / 1024)) << "of " << big.size() / 1024 << " kB";
#endif
  // Released pages read back from the file when touched again.
  EXPECT_EQ(std::memcmp(f.bytes().data, big.data(), big.size()), 0);
  f.close();
  std::remove(path.c_str());
}

// ---- tshark cross-check -------------------------------------------------------------------------

bool have_tshark() { return std::system("command -v tshark >/dev/null 2>&1") == 0; }

struct SharkRow {
  std::string sport, dport, length, time, payload;
};

// frame number -> fields, for every frame tshark reads.
std::map<std::size_t, SharkRow> run_tshark(const std::string& path) {
  const std::string cmd = "tshark -n -r '" + path +
                          "' -T fields -E separator=/t -e frame.number -e udp.srcport -e udp.dstport "
                          "-e udp.length -e frame.time_epoch -e udp.payload 2>/dev/null";
  std::map<std::size_t, SharkRow> rows;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (pipe == nullptr) return rows;
  std::string out;
  char buf[65536];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  pclose(pipe);
  std::istringstream lines(out);
  std::string line;
  while (std::getline(lines, line)) {
    std::vector<std::string> f;
    std::size_t start = 0;
    for (;;) {
      const std::size_t tab = line.find('\t', start);
      f.push_back(line.substr(start, tab == std::string::npos ? std::string::npos : tab - start));
      if (tab == std::string::npos) break;
      start = tab + 1;
    }
    f.resize(6);
    rows[std::stoul(f[0])] = SharkRow{f[1], f[2], f[3], f[4], f[5]};
  }
  return rows;
}

std::string hex(ByteView v) {
  static const char digits[] = "0123456789abcdef";
  std::string s;
  for (std::size_t i = 0; i < v.size; ++i) {
    s += digits[v[i] >> 4];
    s += digits[v[i] & 15];
  }
  return s;
}

// "1673400149.311270000" -> nanoseconds; "" (a frame without a timestamp, as a Simple Packet
// Block) -> 0.
std::uint64_t epoch_ns(const std::string& t) {
  if (t.empty()) return 0;
  const std::size_t dot = t.find('.');
  std::uint64_t ns = std::stoull(t.substr(0, dot)) * 1000000000u;
  if (dot != std::string::npos) {
    std::string frac = t.substr(dot + 1);
    frac.resize(9, '0');
    ns += std::stoull(frac);
  }
  return ns;
}

void cross_check(const std::string& path, std::size_t expected_datagrams) {
  SCOPED_TRACE(path);
  const std::map<std::size_t, SharkRow> rows = run_tshark(path);
  ASSERT_FALSE(rows.empty()) << "tshark read nothing";
  CaptureFile f;
  ASSERT_EQ(f.open(path), CaptureError::ok) << f.message();
  UdpDatagram d;
  std::size_t n = 0;
  std::size_t mismatches = 0;
  while (f.parser().next(d) == CaptureStatus::datagram) {
    ++n;
    const auto it = rows.find(d.record_index + 1u);
    ASSERT_NE(it, rows.end()) << "frame " << d.record_index + 1;
    const SharkRow& r = it->second;
    const bool same = r.sport == std::to_string(d.src_port) && r.dport == std::to_string(d.dst_port) &&
                      r.length == std::to_string(d.payload.size + 8) && epoch_ns(r.time) == d.time_ns &&
                      r.payload == hex(d.payload);
    if (!same && ++mismatches <= 5) {
      ADD_FAILURE() << "frame " << d.record_index + 1 << ": tshark " << r.sport << " " << r.dport << " "
                    << r.length << " " << r.time << ", parser " << d.src_port << " " << d.dst_port << " "
                    << d.payload.size + 8 << " " << d.time_ns;
    }
  }
  EXPECT_EQ(f.parser().error(), CaptureError::ok) << f.message();
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(n, expected_datagrams);
  std::size_t shark_udp = 0;
  for (const auto& kv : rows) shark_udp += kv.second.sport.empty() ? 0u : 1u;
  EXPECT_EQ(shark_udp, n) << "tshark sees UDP in frames the parser skipped";
  EXPECT_EQ(rows.size(), f.parser().stats().records);
}

TEST_P(BundledCapture, TsharkAgrees) {
  if (!have_tshark()) GTEST_SKIP() << "tshark is not on PATH";
  cross_check(std::string(HESAI_DATA_DIR) + "/" + GetParam().file, GetParam().packets);
}

TEST(Tshark, SyntheticPcapngAgrees) {
  if (!have_tshark()) GTEST_SKIP() << "tshark is not on PATH";
  Pcapng w;
  w.shb(false);
  w.idb(1, 0);             // Ethernet, microseconds
  w.idb(101, 0, 9);        // raw IP, nanoseconds
  w.idb(113, 0, 0x94);     // SLL, 2^-20 s
  w.epb(0, 1700000000123456u, ethernet(0x0800, ipv4(udp(10000, 2368, payload_bytes(100, 1))), {0x8100}));
  w.epb(0, 1700000000123457u, ethernet(0x86DD, ipv6(17, udp(10000, 2368, payload_bytes(50, 2))), {0x88A8, 0x8100}));
  w.epb(0, 1700000000123458u, eth_arp(), 0, false);
  w.epb(0, 1700000000123459u, eth_tcp(), 0, false);
  w.epb(1, 1700000000123456789u, ipv4(udp(2369, 2370, payload_bytes(33, 3))));
  w.epb(1, 1700000000123456790u, ipv6(0, ext8(60, ext16(17, udp(2369, 2370, payload_bytes(34, 4))))));
  w.epb(2, (std::uint64_t{1700000000} << 20) | (1u << 18), sll(0x0800, ipv4(udp(7000, 7001, payload_bytes(35, 5)))));
  w.spb(eth_udp(10000, 2368, payload_bytes(36, 6)));
  w.shb(true);
  w.idb(276, 0, 3);        // SLL2, milliseconds
  w.idb(228, 0);
  w.idb(0, 0);
  w.epb(0, 1700000000001u, sll2(0x86DD, ipv6(17, udp(10000, 2368, payload_bytes(37, 7)))));
  w.epb(1, 1700000000000002u, ipv4(udp(10000, 2368, payload_bytes(38, 8))));
  w.epb(2, 1700000000000003u, null_link(2, true, ipv4(udp(10000, 2368, payload_bytes(39, 9)))));
  const File f = w.done();
  const std::string path = temp_path("cross.pcapng");
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(f.bytes.data()), static_cast<std::streamsize>(f.bytes.size()));
  }
  cross_check(path, 9);  // 11 frames, ARP and TCP among them
  if (!HasFailure()) std::remove(path.c_str());
}

}  // namespace
