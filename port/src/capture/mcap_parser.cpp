// MCAP input: PandarScan messages of a rosbag2 MCAP file to datagrams (McapParser).
// Pure: no allocation, no I/O, reads only inside the view (fuzzed through fuzz_mcap).
#include "hesai_port/capture/mcap_parser.h"

#include <cstring>

#include "hesai_port/base/crc32_ieee.h"

namespace hesai::port {
namespace {

// Record opcodes (MCAP spec, "Records").
constexpr std::uint8_t op_header = 0x01;
constexpr std::uint8_t op_footer = 0x02;
constexpr std::uint8_t op_schema = 0x03;
constexpr std::uint8_t op_channel = 0x04;
constexpr std::uint8_t op_message = 0x05;
constexpr std::uint8_t op_chunk = 0x06;
constexpr std::uint8_t op_data_end = 0x0F;

constexpr std::size_t footer_body = 8 + 8 + 4;  // summary_start, summary_offset_start, summary_crc

constexpr std::size_t record_prefix = 9;  // opcode(1), length(8)
// Message record before its data: channel_id(2), sequence(4), log_time(8), publish_time(8).
constexpr std::size_t message_fixed = 2 + 4 + 8 + 8;

// CDR encapsulation header of little-endian plain CDR (RTPS CDR_LE), then two option bytes.
constexpr std::uint8_t cdr_le[2] = {0x00, 0x01};
constexpr std::size_t cdr_header = 4;

constexpr char pandar_scan[] = "pandar_msgs/msg/PandarScan";
constexpr char cdr_encoding[] = "cdr";
constexpr std::uint64_t ns_per_s = 1000000000u;

static_assert(McapParser::packet_cdr_bytes == 1512, "PandarPacket: stamp 8, data 1500, size 4");
static_assert((8 + McapParser::packet_data_bytes) % 4 == 0, "size is 4-aligned without padding");

bool equals(ByteView v, const char* s) {
  const std::size_t n = std::strlen(s);
  return v.size == n && std::memcmp(v.data, s, n) == 0;
}

// An MCAP string or byte array: uint32 length, then the bytes.
bool prefixed(ByteReader& r, ByteView& out) {
  std::uint32_t n = 0;
  return r.le32(n) && r.bytes(n, out);
}

}  // namespace

bool McapParser::looks_like_mcap(ByteView file) {
  if (file.size == 0) return false;
  const std::size_t n = file.size < magic.size() ? file.size : magic.size();
  return std::memcmp(file.data, magic.data(), n) == 0;
}

void McapParser::set(IdSet& s, std::uint16_t id, bool on) {
  const std::uint64_t bit = std::uint64_t{1} << (id & 63u);
  s[id >> 6] = on ? (s[id >> 6] | bit) : (s[id >> 6] & ~bit);
}

McapParser::Step McapParser::fail(CaptureError e, std::uint64_t offset) {
  error_ = e;
  error_offset_ = offset;
  return Step::error;
}

CaptureStatus McapParser::stop(CaptureError e, std::uint64_t offset) {
  fail(e, offset);
  return CaptureStatus::error;
}

CaptureError McapParser::open(ByteView file) {
  file_ = file;
  pos_ = 0;
  done_ = false;
  opened_ = false;
  chunk_records_ = {};
  chunk_pos_ = 0;
  in_chunk_ = false;
  packets_ = {};
  packets_left_ = 0;
  message_channel_ = 0;
  schemas_.fill(0);
  scan_schemas_.fill(0);
  channels_.fill(0);
  scan_channels_.fill(0);
  any_scan_channel_ = false;
  topics_.fill(ByteView{});
  record_index_ = 0;
  records_whole_ = 0;
  ended_by_footer_ = false;
  stats_ = CaptureStats{};
  error_ = CaptureError::ok;
  error_offset_ = 0;
  compression_ = {};

  if (file.size < magic.size()) {
    fail(looks_like_mcap(file) || file.size == 0 ? CaptureError::truncated : CaptureError::bad_magic, 0);
    return error_;
  }
  if (std::memcmp(file.data, magic.data(), magic.size()) != 0) {
    fail(CaptureError::bad_magic, 0);
    return error_;
  }
  // The Header record comes first: opcode, length, profile and library strings.
  const std::size_t at = magic.size();
  if (file.size - at < record_prefix) {
    fail(CaptureError::truncated, at);
    return error_;
  }
  const std::uint64_t len = load_le64(file.data + at + 1);
  if (len > file.size - at - record_prefix) {
    fail(CaptureError::truncated, at);
    return error_;
  }
  ByteReader r(file.sub(at + record_prefix, static_cast<std::size_t>(len)));
  ByteView profile;
  ByteView library;
  if (file[at] != op_header || !prefixed(r, profile) || !prefixed(r, library)) {
    fail(CaptureError::bad_record, at);
    return error_;
  }
  pos_ = at + record_prefix + static_cast<std::size_t>(len);
  records_whole_ = 1;
  opened_ = true;
  return CaptureError::ok;
}

CaptureStatus McapParser::next(UdpDatagram& out) {
  if (error_ != CaptureError::ok) return CaptureStatus::error;
  if (!opened_) return stop(CaptureError::not_open, 0);
  for (;;) {
    Step step = Step::more;
    if (packets_left_ > 0) {
      step = next_packet(out);
    } else if (done_) {
      return CaptureStatus::end;
    } else if (in_chunk_) {
      if (chunk_pos_ == chunk_records_.size) {
        in_chunk_ = false;
        continue;
      }
      const std::uint8_t* p = chunk_records_.data + chunk_pos_;
      const std::size_t left = chunk_records_.size - chunk_pos_;
      if (left < record_prefix) return stop(CaptureError::bad_record, offset_of(p));
      const std::uint64_t len = load_le64(p + 1);
      if (len > left - record_prefix) return stop(CaptureError::bad_record, offset_of(p));
      chunk_pos_ += record_prefix + static_cast<std::size_t>(len);
      step = record(p[0], ByteView(p + record_prefix, static_cast<std::size_t>(len)), offset_of(p), true);
    } else if (pos_ == file_.size) {
      // No Data End or Footer: the file was cut at a record boundary (what was read stands).
      return stop(CaptureError::mcap_cut, pos_);
    } else {
      const std::size_t at = pos_;
      if (file_.size - at < record_prefix) return stop(CaptureError::truncated, at);
      const std::uint64_t len = load_le64(file_.data + at + 1);
      if (len > file_.size - at - record_prefix) return stop(CaptureError::truncated, at);
      pos_ = at + record_prefix + static_cast<std::size_t>(len);
      ++records_whole_;
      step = record(file_[at], file_.sub(at + record_prefix, static_cast<std::size_t>(len)), at, false);
    }
    switch (step) {
      case Step::more: break;
      case Step::datagram: return CaptureStatus::datagram;
      case Step::error: return CaptureStatus::error;
      case Step::end:
        done_ = true;
        if (!closed()) return stop(CaptureError::mcap_cut, file_.size);
        if (!any_scan_channel_) return stop(CaptureError::mcap_no_pandar_scan, pos_);
        return CaptureStatus::end;
    }
  }
}

bool McapParser::closed() const {
  // The file's last bytes: a Footer record (opcode, length 20, its body), then the magic. After a
  // Data End a summary section may come between; after the Footer, only the magic.
  const std::size_t tail = record_prefix + footer_body + magic.size();
  if (file_.size < tail || file_.size - pos_ < (ended_by_footer_ ? magic.size() : tail)) return false;
  if (ended_by_footer_ && file_.size - pos_ != magic.size()) return false;
  const std::uint8_t* footer = file_.data + file_.size - tail;
  return std::memcmp(file_.data + file_.size - magic.size(), magic.data(), magic.size()) == 0 &&
         footer[0] == op_footer && load_le64(footer + 1) == footer_body;
}

McapParser::Step McapParser::record(std::uint8_t op, ByteView body, std::uint64_t at, bool in_chunk) {
  switch (op) {
    case op_schema: return schema(body, at);
    case op_channel: return channel(body, at);
    case op_message: return message(body, at);
    case op_chunk: return in_chunk ? fail(CaptureError::bad_record, at) : chunk(body, at);
    case op_header: return fail(CaptureError::bad_record, at);  // only the first record
    case op_data_end:
    case op_footer:
      if (in_chunk) return fail(CaptureError::bad_record, at);
      ended_by_footer_ = op == op_footer;
      return Step::end;
    default: return Step::more;  // indexes, attachments, metadata, statistics, unknown opcodes
  }
}

McapParser::Step McapParser::schema(ByteView body, std::uint64_t at) {
  ByteReader r(body);
  std::uint16_t id = 0;
  ByteView name;
  ByteView encoding;
  ByteView data;
  if (!r.le16(id) || !prefixed(r, name) || !prefixed(r, encoding) || !prefixed(r, data) || id == 0) {
    return fail(CaptureError::bad_record, at);  // id 0 is reserved for "no schema"
  }
  set(schemas_, id, true);
  set(scan_schemas_, id, equals(name, pandar_scan));
  return Step::more;
}

McapParser::Step McapParser::channel(ByteView body, std::uint64_t at) {
  ByteReader r(body);
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;
  ByteView topic;
  ByteView encoding;
  ByteView metadata;
  if (!r.le16(id) || !r.le16(schema_id) || !prefixed(r, topic) || !prefixed(r, encoding) ||
      !prefixed(r, metadata)) {
    return fail(CaptureError::bad_record, at);
  }
  if (schema_id != 0 && !has(schemas_, schema_id)) return fail(CaptureError::mcap_unknown_schema, at);
  const bool scan = schema_id != 0 && has(scan_schemas_, schema_id);
  if (scan && !equals(encoding, cdr_encoding)) return fail(CaptureError::mcap_bad_encoding, at);
  set(channels_, id, true);
  set(scan_channels_, id, scan);
  if (id < kTopicIds) topics_[id] = scan ? topic : ByteView{};
  any_scan_channel_ = any_scan_channel_ || scan;
  return Step::more;
}

McapParser::Step McapParser::message(ByteView body, std::uint64_t at) {
  if (body.size < message_fixed) return fail(CaptureError::bad_record, at);
  const std::uint16_t channel_id = load_le16(body.data);
  if (!has(channels_, channel_id)) return fail(CaptureError::mcap_unknown_channel, at);
  if (!has(scan_channels_, channel_id)) {
    ++stats_.other_blocks;
    return Step::more;
  }
  const ByteView data = body.sub(message_fixed, body.size - message_fixed);
  if (data.size < cdr_header || data[0] != cdr_le[0] || data[1] != cdr_le[1]) {
    return fail(CaptureError::mcap_bad_cdr, at);
  }
  // Alignment counts from the byte after the encapsulation header.
  const ByteView cdr = data.sub(cdr_header, data.size - cdr_header);
  ByteReader r(cdr);
  std::uint32_t frame_id_len = 0;
  std::uint32_t count = 0;
  if (!r.skip(8) || !r.le32(frame_id_len) || !r.skip(frame_id_len) || !r.seek((r.position() + 3) & ~std::size_t{3}) ||
      !r.le32(count) || count > r.remaining() / packet_cdr_bytes) {
    return fail(CaptureError::mcap_bad_cdr, at);
  }
  packets_ = cdr.sub(r.position(), std::size_t{count} * packet_cdr_bytes);
  packets_left_ = count;
  message_channel_ = channel_id;
  return Step::more;
}

McapParser::Step McapParser::next_packet(UdpDatagram& out) {
  const std::uint8_t* p = packets_.data;
  const std::uint32_t size = load_le32(p + 8 + packet_data_bytes);
  if (size > packet_data_bytes) return fail(CaptureError::mcap_bad_packet_size, offset_of(p));
  const auto sec = static_cast<std::int32_t>(load_le32(p));
  const std::uint32_t nanosec = load_le32(p + 4);
  UdpDatagram d;
  d.payload = ByteView(p + 8, size);
  // builtin_interfaces/Time: seconds may be negative (before 1970); wraps as the pcap times do.
  d.time_ns = static_cast<std::uint64_t>(static_cast<std::int64_t>(sec)) * ns_per_s + nanosec;
  d.file_offset = offset_of(p);
  d.record_index = record_index_++;
  d.interface_id = message_channel_;
  out = d;
  packets_ = packets_.sub(packet_cdr_bytes, packets_.size - packet_cdr_bytes);
  --packets_left_;
  ++stats_.records;
  ++stats_.datagrams;
  return Step::datagram;
}

McapParser::Step McapParser::chunk(ByteView body, std::uint64_t at) {
  ByteReader r(body);
  std::uint64_t start_time = 0;
  std::uint64_t end_time = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint32_t uncompressed_crc = 0;
  ByteView compression;
  std::uint64_t records_len = 0;
  if (!r.le64(start_time) || !r.le64(end_time) || !r.le64(uncompressed_size) || !r.le32(uncompressed_crc) ||
      !prefixed(r, compression) || !r.le64(records_len) || records_len > r.remaining()) {
    return fail(CaptureError::bad_record, at);
  }
  if (compression.size != 0) {
    compression_ = compression;
    return fail(CaptureError::mcap_compressed_chunk, at);
  }
  const ByteView records = body.sub(r.position(), static_cast<std::size_t>(records_len));
  if (uncompressed_size != records_len) return fail(CaptureError::bad_record, at);
  if (uncompressed_crc != 0 && crc32_ieee(records.data, records.size) != uncompressed_crc) {
    return fail(CaptureError::mcap_chunk_crc, at);
  }
  chunk_records_ = records;
  chunk_pos_ = 0;
  in_chunk_ = true;
  return Step::more;
}

}  // namespace hesai::port
