#include "hesai_port/formats/mcap.h"

#include <array>
#include <cerrno>
#include <cstring>

namespace hesai {
namespace port {

namespace {

// Little-endian record bytes.
class Bytes {
 public:
  explicit Bytes(std::vector<std::uint8_t>& out) : out_(out) {}
  Bytes& u8(std::uint8_t v) {
    out_.push_back(v);
    return *this;
  }
  Bytes& u16(std::uint16_t v) { return le(v, 2); }
  Bytes& u32(std::uint32_t v) { return le(v, 4); }
  Bytes& u64(std::uint64_t v) { return le(v, 8); }
  Bytes& str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    out_.insert(out_.end(), s.begin(), s.end());
    return *this;
  }
  // A record: opcode and a length, patched by end().
  Bytes& begin(std::uint8_t opcode) {
    u8(opcode);
    start_ = out_.size();
    return u64(0);
  }
  void end() { put_le(out_.data() + start_, out_.size() - start_ - 8, 8); }
  // A map or array: its byte length, patched by end_list().
  std::size_t begin_list() {
    u32(0);
    return out_.size();
  }
  void end_list(std::size_t at) { put_le(out_.data() + at - 4, out_.size() - at, 4); }
  static void put_le(std::uint8_t* p, std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
  }

 private:
  Bytes& le(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    return *this;
  }
  std::vector<std::uint8_t>& out_;
  std::size_t start_ = 0;
};

constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
enum Op : std::uint8_t {
  kHeader = 0x01, kFooter = 0x02, kSchema = 0x03, kChannel = 0x04, kMessage = 0x05, kChunk = 0x06,
  kMessageIndex = 0x07, kChunkIndex = 0x08, kStatistics = 0x0B, kMetadata = 0x0C, kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E, kDataEnd = 0x0F,
};
// Chunk record up to its records: opcode, length, start and end time, uncompressed size and CRC,
// the empty compression string, the records' length.
constexpr std::size_t kChunkHead = 1 + 8 + 8 + 8 + 8 + 4 + 4 + 8;

std::string os_text(const char* what, const std::string& path, int err) {
  return std::string(what) + " '" + path + "': " + std::strerror(err);
}

}  // namespace

McapWriter::~McapWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

void McapWriter::fail(const char* what) {
  if (!error_.ok()) return;
  const int err = errno;
  error_ = WriteResult::failure(os_text(what, path_, err), err);
}

void McapWriter::put(const void* data, std::size_t size) {
  if (!error_.ok() || size == 0) return;
  if (std::fwrite(data, 1, size, file_) != size) return fail("cannot write");
  position_ += size;
  if (chunk_open_) chunk_crc_ = crc32_ieee(data, size, chunk_crc_);
  else data_crc_ = crc32_ieee(data, size, data_crc_);
}

void McapWriter::put_record(std::vector<std::uint8_t>& record) {
  put(record.data(), record.size());
  record.clear();
}

WriteResult McapWriter::open(const std::string& path, const std::string& profile, const std::string& library) {
  path_ = path;
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) {
    fail("cannot open");
    return error_;
  }
  std::setvbuf(file_, nullptr, _IOFBF, 1u << 20);  // before any other operation on the stream
  if (ftello(file_) < 0) {
    const int err = errno;
    error_ = WriteResult::failure("cannot write '" + path + "': " + std::strerror(err) +
                                      " (MCAP chunk headers are written when each chunk ends: give a file)",
                                  err);
    std::fclose(file_);
    file_ = nullptr;
    return error_;
  }
  std::vector<std::uint8_t> r(kMagic, kMagic + 8);
  Bytes b(r);
  b.begin(kHeader).str(profile).str(library).end();
  put_record(r);
  return error_;
}

std::uint16_t McapWriter::add_schema(const std::string& name, const std::string& encoding, const std::string& data) {
  const auto id = static_cast<std::uint16_t>(schemas_.size() + 1);
  schemas_.push_back({id, name, encoding, data});
  schema_written_.push_back(false);
  return id;
}

std::uint16_t McapWriter::add_channel(std::uint16_t schema_id, const std::string& topic,
                                      const std::string& message_encoding,
                                      const std::map<std::string, std::string>& metadata) {
  const auto id = static_cast<std::uint16_t>(channels_.size());
  channels_.push_back({id, schema_id, topic, message_encoding, metadata});
  channel_written_.push_back(false);
  return id;
}

namespace {
void schema_record(Bytes& b, std::uint16_t id, const std::string& name, const std::string& encoding,
                   const std::string& data) {
  b.begin(kSchema).u16(id).str(name).str(encoding).str(data).end();
}
void channel_record(Bytes& b, std::uint16_t id, std::uint16_t schema_id, const std::string& topic,
                    const std::string& encoding, const std::map<std::string, std::string>& metadata) {
  b.begin(kChannel).u16(id).u16(schema_id).str(topic).str(encoding);
  const std::size_t at = b.begin_list();
  for (const auto& [k, v] : metadata) b.str(k).str(v);
  b.end_list(at);
  b.end();
}
}  // namespace

bool McapWriter::ensure_channel_written(std::uint16_t channel_id) {
  if (channel_id >= channels_.size()) return false;
  if (channel_written_[channel_id]) return true;
  const Channel& c = channels_[channel_id];
  std::vector<std::uint8_t> r;
  Bytes b(r);
  if (c.schema_id != 0) {
    if (c.schema_id > schemas_.size()) return false;
    const Schema& s = schemas_[c.schema_id - 1u];
    if (!schema_written_[c.schema_id - 1u]) schema_record(b, s.id, s.name, s.encoding, s.data);
    schema_written_[c.schema_id - 1u] = true;
  }
  channel_record(b, c.id, c.schema_id, c.topic, c.message_encoding, c.metadata);
  put_record(r);
  channel_written_[channel_id] = true;
  return true;
}

void McapWriter::open_chunk() {
  // The head is rewritten when the chunk closes; its bytes join the data CRC then.
  const std::uint8_t zeros[kChunkHead] = {};
  if (!error_.ok()) return;
  if (std::fwrite(zeros, 1, kChunkHead, file_) != kChunkHead) return fail("cannot write");
  chunk_start_ = position_;
  position_ += kChunkHead;
  chunk_open_ = true;
  chunk_crc_ = 0;
  chunk_messages_ = 0;
  chunk_first_ = chunk_last_ = 0;
  chunk_index_entries_.clear();
}

void McapWriter::close_chunk() {
  if (!chunk_open_) return;
  chunk_open_ = false;
  const std::uint64_t records = position_ - chunk_start_ - kChunkHead;
  std::vector<std::uint8_t> head;
  Bytes b(head);
  b.u8(kChunk).u64(kChunkHead - 9 + records).u64(chunk_first_).u64(chunk_last_).u64(records).u32(chunk_crc_);
  b.str("").u64(records);
  if (error_.ok() && (fseeko(file_, static_cast<off_t>(chunk_start_), SEEK_SET) != 0 ||
                      std::fwrite(head.data(), 1, head.size(), file_) != head.size() ||
                      fseeko(file_, static_cast<off_t>(position_), SEEK_SET) != 0))
    fail("cannot write");
  data_crc_ = crc32_ieee(head.data(), head.size(), data_crc_);
  data_crc_ = crc32_ieee_combine(data_crc_, chunk_crc_, records);

  ChunkIndex index{chunk_first_, chunk_last_, chunk_start_, kChunkHead + records, records, {}, 0};
  const std::uint64_t index_start = position_;
  std::vector<std::uint8_t> r;
  Bytes m(r);
  for (const auto& [channel, entries] : chunk_index_entries_) {
    index.message_index_offsets[channel] = position_;
    m.begin(kMessageIndex).u16(channel);
    const std::size_t at = m.begin_list();
    for (const std::uint64_t v : entries) m.u64(v);
    m.end_list(at);
    m.end();
    put_record(r);
  }
  index.message_index_length = position_ - index_start;
  chunk_index_.push_back(std::move(index));
  chunk_index_entries_.clear();
}

WriteResult McapWriter::begin_message(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time,
                                      std::uint64_t publish_time, std::uint64_t size) {
  if (file_ == nullptr && error_.ok()) error_ = WriteResult::failure("MCAP writer: not open");
  if (in_message_ && error_.ok()) error_ = WriteResult::failure("MCAP writer: a message is still open");
  if (!error_.ok()) return error_;
  if (!chunk_open_) open_chunk();
  if (!ensure_channel_written(channel_id)) {
    error_ = WriteResult::failure("MCAP writer: no channel " + std::to_string(channel_id));
    return error_;
  }
  std::vector<std::uint64_t>& entries = chunk_index_entries_[channel_id];
  entries.push_back(log_time);
  entries.push_back(position_ - chunk_start_ - kChunkHead);  // the record's offset in the chunk's records
  if (chunk_messages_ == 0 || log_time < chunk_first_) chunk_first_ = log_time;
  if (chunk_messages_ == 0 || log_time > chunk_last_) chunk_last_ = log_time;
  ++chunk_messages_;
  if (message_count_ == 0 || log_time < first_time_) first_time_ = log_time;
  if (message_count_ == 0 || log_time > last_time_) last_time_ = log_time;
  ++message_count_;
  ++channel_counts_[channel_id];

  std::vector<std::uint8_t> r;
  Bytes b(r);
  b.u8(kMessage).u64(2 + 4 + 8 + 8 + size).u16(channel_id).u32(sequence).u64(log_time).u64(publish_time);
  put_record(r);
  in_message_ = true;
  message_left_ = size;
  return error_;
}

WriteResult McapWriter::append(const void* data, std::size_t size) {
  if (!in_message_ || size > message_left_) {
    if (error_.ok()) error_ = WriteResult::failure("MCAP writer: more message bytes than announced");
    return error_;
  }
  put(data, size);
  message_left_ -= size;
  return error_;
}

WriteResult McapWriter::end_message() {
  if ((!in_message_ || message_left_ != 0) && error_.ok())
    error_ = WriteResult::failure("MCAP writer: fewer message bytes than announced");
  in_message_ = false;
  if (error_.ok() && position_ - chunk_start_ - kChunkHead >= kChunkBytes) close_chunk();
  return error_;
}

WriteResult McapWriter::write_message(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time,
                                      std::uint64_t publish_time, const void* data, std::size_t size) {
  if (begin_message(channel_id, sequence, log_time, publish_time, size)) {
    (void)append(data, size);
    (void)end_message();
  }
  return error_;
}

WriteResult McapWriter::add_metadata(const std::string& name, const std::map<std::string, std::string>& metadata) {
  if (file_ == nullptr && error_.ok()) error_ = WriteResult::failure("MCAP writer: not open");
  if (in_message_ && error_.ok()) error_ = WriteResult::failure("MCAP writer: metadata inside a message");
  if (!error_.ok()) return error_;
  close_chunk();
  std::vector<std::uint8_t> r;
  Bytes b(r);
  b.begin(kMetadata).str(name);
  const std::size_t at = b.begin_list();
  for (const auto& [k, v] : metadata) b.str(k).str(v);
  b.end_list(at);
  b.end();
  metadata_index_.push_back({position_, r.size(), name});
  put_record(r);
  return error_;
}

WriteResult McapWriter::close() {
  if (file_ == nullptr) return error_;
  if (in_message_ && error_.ok()) error_ = WriteResult::failure("MCAP writer: closed inside a message");
  close_chunk();
  std::vector<std::uint8_t> r;
  Bytes b(r);
  b.begin(kDataEnd).u32(data_crc_).end();
  put_record(r);

  // The summary, grouped by opcode, and where each group lies.
  const std::uint64_t summary_start = position_;
  std::vector<std::uint8_t> s;
  Bytes sb(s);
  struct Group {
    std::uint8_t opcode;
    std::uint64_t start, length;
  };
  std::vector<Group> groups;
  auto group = [&](std::uint8_t opcode, std::size_t from) {
    if (s.size() > from) groups.push_back({opcode, summary_start + from, s.size() - from});
  };
  std::size_t from = s.size();
  for (const Schema& x : schemas_) schema_record(sb, x.id, x.name, x.encoding, x.data);
  group(kSchema, from);
  from = s.size();
  for (const Channel& c : channels_) channel_record(sb, c.id, c.schema_id, c.topic, c.message_encoding, c.metadata);
  group(kChannel, from);
  from = s.size();
  sb.begin(kStatistics).u64(message_count_).u16(static_cast<std::uint16_t>(schemas_.size()));
  sb.u32(static_cast<std::uint32_t>(channels_.size())).u32(0).u32(static_cast<std::uint32_t>(metadata_index_.size()));
  sb.u32(static_cast<std::uint32_t>(chunk_index_.size()));
  sb.u64(first_time_).u64(last_time_);
  std::size_t at = sb.begin_list();
  for (const auto& [channel, count] : channel_counts_) sb.u16(channel).u64(count);
  sb.end_list(at);
  sb.end();
  group(kStatistics, from);
  from = s.size();
  for (const ChunkIndex& c : chunk_index_) {
    sb.begin(kChunkIndex).u64(c.start_time).u64(c.end_time).u64(c.offset).u64(c.length);
    at = sb.begin_list();
    for (const auto& [channel, offset] : c.message_index_offsets) sb.u16(channel).u64(offset);
    sb.end_list(at);
    sb.u64(c.message_index_length).str("").u64(c.records).u64(c.records);
    sb.end();
  }
  group(kChunkIndex, from);
  from = s.size();
  for (const MetadataIndex& m : metadata_index_) sb.begin(kMetadataIndex).u64(m.offset).u64(m.length).str(m.name).end();
  group(kMetadataIndex, from);
  const std::uint64_t summary_offset_start = summary_start + s.size();
  for (const Group& g : groups) sb.begin(kSummaryOffset).u8(g.opcode).u64(g.start).u64(g.length).end();
  sb.u8(kFooter).u64(8 + 8 + 4).u64(summary_start).u64(summary_offset_start);
  sb.u32(crc32_ieee(s.data(), s.size()));
  s.insert(s.end(), kMagic, kMagic + 8);
  put_record(s);

  if (std::fflush(file_) != 0) fail("cannot write");
  if (std::fclose(file_) != 0) fail("cannot close");
  file_ = nullptr;
  return error_;
}

}  // namespace port
}  // namespace hesai
