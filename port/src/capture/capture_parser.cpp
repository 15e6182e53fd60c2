// Capture files held in memory: pcap and pcapng record walking (CaptureParser).
// Pure: no allocation, no I/O, reads only inside the view (fuzzed through fuzz_capture, proved
// allocation-free by tests/alloc/capture_alloc.cpp). Frames are unpacked by parse_frame
// (capture_frame.cpp); the file mapping is CaptureFile (capture_file.cpp).
#include "hesai_port/capture/capture_parser.h"

#include <cstring>

namespace hesai::port {
namespace {

// ---- File formats ---------------------------------------------------------------------------

// Classic pcap: 24-byte global header (magic, major, minor, reserved1, reserved2, snaplen,
// link type), then records of a 16-byte header (ts_sec, ts_frac, incl_len, orig_len) and data.
constexpr std::uint32_t pcap_magic_us = 0xA1B2C3D4u;
constexpr std::uint32_t pcap_magic_ns = 0xA1B23C4Du;
constexpr std::size_t pcap_header_size = 24;
constexpr std::size_t pcap_off_major = 4;
constexpr std::size_t pcap_off_snaplen = 16;
constexpr std::size_t pcap_off_link = 20;
constexpr std::size_t pcap_record_header_size = 16;
static_assert(pcap_off_link + 4 == pcap_header_size, "pcap global header is 24 bytes");

// pcapng: blocks of type(4), total length(4), body, total length(4).
constexpr std::uint32_t block_shb = 0x0A0D0D0Au;  // Section Header Block (palindromic)
constexpr std::uint32_t block_idb = 1;            // Interface Description Block
constexpr std::uint32_t block_pb = 2;             // Packet Block (obsolete)
constexpr std::uint32_t block_spb = 3;            // Simple Packet Block
constexpr std::uint32_t block_epb = 6;            // Enhanced Packet Block
constexpr std::uint32_t byte_order_magic = 0x1A2B3C4Du;
constexpr std::size_t block_overhead = 12;        // type, length, trailing length
constexpr std::size_t shb_min_size = 28;          // + BOM(4), major(2), minor(2), section length(8)
constexpr std::size_t idb_body_min = 8;           // link type(2), reserved(2), snaplen(4)
constexpr std::size_t epb_body_min = 20;          // interface(4), ts high(4), ts low(4), caplen(4), len(4)
constexpr std::size_t pb_body_min = 20;           // interface(2), drops(2), ts high, ts low, caplen, len
constexpr std::size_t spb_body_min = 4;           // original length(4)
static_assert(shb_min_size == block_overhead + 16, "SHB fixed part");

constexpr std::uint16_t opt_endofopt = 0;
constexpr std::uint16_t opt_if_tsresol = 9;
constexpr std::uint16_t opt_if_tsoffset = 14;

constexpr std::size_t min_size(std::size_t a, std::size_t b) { return a < b ? a : b; }


// if_tsresol: bit 7 clear, units of 10^-n s; set, units of 2^-n s.
constexpr bool tsresol_valid(std::uint8_t r) { return (r & 0x80) ? (r & 0x7F) <= 63 : r <= 19; }

constexpr std::uint64_t power_of_10(unsigned n) {
  std::uint64_t v = 1;
  for (unsigned i = 0; i < n; ++i) v *= 10;
  return v;
}
constexpr std::uint64_t ns_per_s = 1000000000u;

// Timestamp in interface units to nanoseconds (truncating; wraps modulo 2^64 past year 2554).
constexpr std::uint64_t units_to_ns(std::uint64_t ts, std::uint8_t resol) {
  if ((resol & 0x80) == 0) {
    return resol <= 9 ? ts * power_of_10(9u - resol) : ts / power_of_10(resol - 9u);
  }
  const unsigned n = resol & 0x7Fu;
  if (n == 0) return ts * ns_per_s;
  const std::uint64_t sec = ts >> n;
  const std::uint64_t frac = ts & ((std::uint64_t{1} << n) - 1);
  // frac < 2^34 keeps frac * 10^9 (< 2^30) below 2^64; finer units drop their lowest bits first.
  const std::uint64_t frac_ns = n <= 34 ? (frac * ns_per_s) >> n : ((frac >> (n - 34)) * ns_per_s) >> 34;
  return sec * ns_per_s + frac_ns;
}
static_assert(units_to_ns(1, 6) == 1000, "microseconds");
static_assert(units_to_ns(1, 9) == 1, "nanoseconds");
static_assert(units_to_ns(1234567, 12) == 1234, "picoseconds truncate");
static_assert(units_to_ns((5u << 20) | (1u << 19), 0x94) == 5500000000u, "2^-20 s units");
static_assert(units_to_ns(std::uint64_t{3} << 62, 0xBF) == 1500000000u, "2^-63 s units");

}  // namespace

// ---- CaptureParser ------------------------------------------------------------------------------

CaptureError CaptureParser::open(ByteView file) {
  file_ = file;
  pos_ = 0;
  format_ = CaptureFormat::none;
  big_endian_ = false;
  nanosecond_ = false;
  pcap_link_ = 0;
  pcap_snaplen_ = 0;
  interface_count_ = 0;
  record_index_ = 0;
  stats_ = CaptureStats{};
  error_ = CaptureError::ok;
  error_offset_ = 0;

  auto failed = [this](CaptureError e, std::uint64_t at) {
    fail(e, at);
    return e;
  };
  if (file.size < 4) {
    // Too short to tell: a prefix of a known magic is a cut file, anything else is not a capture.
    static constexpr std::uint32_t magics[] = {pcap_magic_us, pcap_magic_ns, block_shb};
    for (std::uint32_t m : magics) {
      std::uint8_t le[4];
      std::uint8_t be[4];
      store_le32(le, m);
      store_be32(be, m);
      if (file.size == 0 || std::memcmp(le, file.data, file.size) == 0 ||
          std::memcmp(be, file.data, file.size) == 0) {
        return failed(CaptureError::truncated, 0);
      }
    }
    return failed(CaptureError::bad_magic, 0);
  }

  if (load_le32(file.data) == block_shb) {
    format_ = CaptureFormat::pcapng;
    std::size_t length = 0;
    const CaptureError e = read_section_header(0, length);
    if (e != CaptureError::ok) return failed(e, 0);
    pos_ = length;
    return CaptureError::ok;
  }

  const std::uint32_t le = load_le32(file.data);
  const std::uint32_t be = load_be32(file.data);
  if (le == pcap_magic_us || le == pcap_magic_ns) {
    big_endian_ = false;
    nanosecond_ = le == pcap_magic_ns;
  } else if (be == pcap_magic_us || be == pcap_magic_ns) {
    big_endian_ = true;
    nanosecond_ = be == pcap_magic_ns;
  } else {
    return failed(CaptureError::bad_magic, 0);
  }
  format_ = CaptureFormat::pcap;
  if (file.size < pcap_header_size) return failed(CaptureError::truncated, 0);
  if (u16(file.data + pcap_off_major) != 2) return failed(CaptureError::bad_magic, pcap_off_major);
  pcap_snaplen_ = u32(file.data + pcap_off_snaplen);
  // Bits 16..31 of the link-type field carry FCS information, not the link type.
  pcap_link_ = u32(file.data + pcap_off_link) & 0xFFFFu;
  if (!link_type_supported(pcap_link_)) return failed(CaptureError::unsupported_link, pcap_off_link);
  pos_ = pcap_header_size;
  return CaptureError::ok;
}

CaptureParser::Step CaptureParser::fail(CaptureError e, std::uint64_t offset) {
  error_ = e;
  error_offset_ = offset;
  return Step::error;
}

CaptureStatus CaptureParser::next(UdpDatagram& out) {
  if (error_ != CaptureError::ok) return CaptureStatus::error;
  if (format_ == CaptureFormat::none) {
    fail(CaptureError::not_open, 0);  // next() before a successful open()
    return CaptureStatus::error;
  }
  for (;;) {
    Record rec;
    const Step step = format_ == CaptureFormat::pcap ? next_pcap_record(rec) : next_pcapng_record(rec);
    if (step == Step::end) return CaptureStatus::end;
    if (step == Step::error) return CaptureStatus::error;
    ++stats_.records;
    const std::uint32_t index = record_index_++;
    UdpDatagram d;
    switch (parse_frame(rec.link_type, rec.frame, d)) {
      case FrameKind::udp:
        d.time_ns = rec.time_ns;
        d.file_offset = rec.offset;
        d.record_index = index;
        d.interface_id = rec.interface_id;
        out = d;
        ++stats_.datagrams;
        return CaptureStatus::datagram;
      case FrameKind::non_udp: ++stats_.non_udp; break;
      case FrameKind::fragment: ++stats_.fragments; break;
      case FrameKind::truncated: ++stats_.truncated; break;
      case FrameKind::malformed: ++stats_.malformed; break;
      case FrameKind::unsupported_link: ++stats_.other_link; break;
    }
  }
}

CaptureParser::Step CaptureParser::next_pcap_record(Record& rec) {
  if (pos_ == file_.size) return Step::end;
  const std::size_t at = pos_;
  if (file_.size - at < pcap_record_header_size) return fail(CaptureError::truncated, at);
  const std::uint8_t* h = file_.data + at;
  const std::uint32_t ts_sec = u32(h);
  const std::uint32_t ts_frac = u32(h + 4);
  const std::uint32_t incl_len = u32(h + 8);
  const std::uint32_t orig_len = u32(h + 12);
  if (incl_len > max_record_bytes || (pcap_snaplen_ != 0 && incl_len > pcap_snaplen_) ||
      orig_len < incl_len) {
    return fail(CaptureError::bad_record, at);
  }
  if (incl_len > file_.size - at - pcap_record_header_size) return fail(CaptureError::truncated, at);
  rec.frame = file_.sub(at + pcap_record_header_size, incl_len);
  rec.time_ns = std::uint64_t{ts_sec} * ns_per_s + (nanosecond_ ? ts_frac : std::uint64_t{ts_frac} * 1000u);
  rec.offset = at;
  rec.link_type = pcap_link_;
  rec.interface_id = 0;
  pos_ = at + pcap_record_header_size + incl_len;
  return Step::record;
}

CaptureError CaptureParser::read_section_header(std::size_t at, std::size_t& length) {
  if (file_.size - at < block_overhead) return CaptureError::truncated;
  const std::uint8_t* b = file_.data + at;
  if (load_le32(b + 8) == byte_order_magic) {
    big_endian_ = false;
  } else if (load_be32(b + 8) == byte_order_magic) {
    big_endian_ = true;
  } else {
    return CaptureError::bad_magic;
  }
  const std::uint32_t len = u32(b + 4);
  if (len < shb_min_size || len % 4 != 0) return CaptureError::bad_record;
  if (len > file_.size - at) return CaptureError::truncated;
  if (u32(b + len - 4) != len) return CaptureError::bad_record;
  if (u16(b + 12) != 1) return CaptureError::bad_magic;  // major version 1 is the only one
  interface_count_ = 0;
  length = len;
  return CaptureError::ok;
}

CaptureError CaptureParser::read_interface(ByteView body) {
  if (body.size < idb_body_min) return CaptureError::bad_record;
  if (interface_count_ == max_interfaces) return CaptureError::bad_record;
  Interface ifc;
  ifc.link_type = u16(body.data);
  ifc.snaplen = u32(body.data + 4);
  // Options: code(2), length(2), value padded to 4. The body is a multiple of 4 long.
  std::size_t off = idb_body_min;
  while (body.size - off >= 4) {
    const std::uint16_t code = u16(body.data + off);
    const std::size_t len = u16(body.data + off + 2);
    off += 4;
    if (code == opt_endofopt) break;
    if (len > body.size - off) return CaptureError::bad_record;
    if (code == opt_if_tsresol) {
      if (len != 1 || !tsresol_valid(body[off])) return CaptureError::bad_record;
      ifc.tsresol = body[off];
    } else if (code == opt_if_tsoffset) {
      if (len != 8) return CaptureError::bad_record;
      const std::uint64_t v = big_endian_ ? load_be64(body.data + off) : load_le64(body.data + off);
      ifc.tsoffset = static_cast<std::int64_t>(v);
    }
    off += min_size((len + 3) & ~std::size_t{3}, body.size - off);
  }
  interfaces_[interface_count_++] = ifc;
  return CaptureError::ok;
}

CaptureParser::Step CaptureParser::next_pcapng_record(Record& rec) {
  for (;;) {
    if (pos_ == file_.size) return Step::end;
    const std::size_t at = pos_;
    if (file_.size - at < block_overhead) return fail(CaptureError::truncated, at);
    const std::uint8_t* b = file_.data + at;
    const std::uint32_t type = u32(b);
    if (type == block_shb) {
      std::size_t length = 0;
      const CaptureError e = read_section_header(at, length);
      if (e != CaptureError::ok) return fail(e, at);
      pos_ = at + length;
      continue;
    }
    const std::uint32_t len = u32(b + 4);
    if (len < block_overhead || len % 4 != 0) return fail(CaptureError::bad_record, at);
    if (len > file_.size - at) return fail(CaptureError::truncated, at);
    if (u32(b + len - 4) != len) return fail(CaptureError::bad_record, at);
    const ByteView body = file_.sub(at + 8, len - block_overhead);
    pos_ = at + len;

    std::uint32_t if_id = 0;
    std::uint64_t ts = 0;
    std::uint32_t cap = 0;
    std::uint32_t orig = 0;
    std::size_t data_off = 0;
    bool has_time = true;
    if (type == block_epb || type == block_pb) {
      if (body.size < epb_body_min) return fail(CaptureError::bad_record, at);
      static_assert(epb_body_min == pb_body_min, "same fixed part after the interface field");
      if_id = type == block_epb ? u32(body.data) : u16(body.data);
      ts = (std::uint64_t{u32(body.data + 4)} << 32) | u32(body.data + 8);
      cap = u32(body.data + 12);
      orig = u32(body.data + 16);
      data_off = epb_body_min;
      if (cap > body.size - data_off) return fail(CaptureError::bad_record, at);
    } else if (type == block_spb) {
      if (body.size < spb_body_min) return fail(CaptureError::bad_record, at);
      orig = u32(body.data);
      data_off = spb_body_min;
      // The captured length is not stored: the original length cut to the snap length and the block.
      cap = static_cast<std::uint32_t>(min_size(orig, body.size - data_off));
      if (interface_count_ > 0 && interfaces_[0].snaplen != 0 && cap > interfaces_[0].snaplen) {
        cap = interfaces_[0].snaplen;
      }
      has_time = false;
    } else if (type == block_idb) {
      const CaptureError e = read_interface(body);
      if (e != CaptureError::ok) return fail(e, at);
      continue;
    } else {
      ++stats_.other_blocks;
      continue;
    }

    if (if_id >= interface_count_) return fail(CaptureError::bad_record, at);
    const Interface& ifc = interfaces_[if_id];
    if (cap > max_record_bytes || (ifc.snaplen != 0 && cap > ifc.snaplen) || orig < cap) {
      return fail(CaptureError::bad_record, at);
    }
    rec.frame = body.sub(data_off, cap);
    rec.time_ns = has_time ? units_to_ns(ts, ifc.tsresol) +
                                 static_cast<std::uint64_t>(ifc.tsoffset) * ns_per_s
                           : 0;
    rec.offset = at;
    rec.link_type = ifc.link_type;
    rec.interface_id = if_id;
    return Step::record;
  }
}

const char* capture_error_name(CaptureError e) {
  switch (e) {
    case CaptureError::ok: return "ok";
    case CaptureError::bad_magic: return "capture_bad_magic";
    case CaptureError::truncated: return "capture_truncated";
    case CaptureError::bad_record: return "capture_bad_record";
    case CaptureError::unsupported_link: return "capture_unsupported_link";
    case CaptureError::io: return "capture_io";
    case CaptureError::not_open: return "capture_not_open";
    case CaptureError::mcap_compressed_chunk: return "mcap_compressed_chunk";
    case CaptureError::mcap_chunk_crc: return "mcap_chunk_crc_mismatch";
    case CaptureError::mcap_unknown_schema: return "mcap_unknown_schema";
    case CaptureError::mcap_unknown_channel: return "mcap_unknown_channel";
    case CaptureError::mcap_bad_encoding: return "mcap_bad_encoding";
    case CaptureError::mcap_bad_cdr: return "mcap_bad_cdr";
    case CaptureError::mcap_bad_packet_size: return "mcap_bad_packet_size";
    case CaptureError::mcap_no_pandar_scan: return "mcap_no_pandar_scan";
    case CaptureError::mcap_cut: return "mcap_cut";
  }
  return "unknown";
}

}  // namespace hesai::port
