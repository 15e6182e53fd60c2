// MCAP files (https://mcap.dev/spec, major version 0), written as a stream.
//
// What a file holds, in order: the magic, a Header record, the data section (Chunk records,
// uncompressed, each followed by its Message Index records; Metadata records between chunks), a
// Data End record, the summary section (Schema, Channel, Statistics, Chunk Index and Metadata
// Index records, grouped by opcode), one Summary Offset record per group, the Footer and the
// magic again. Every CRC is filled in: each chunk's
// uncompressed_crc, the Data End's data_section_crc (over every byte before the Data End record,
// the leading magic and the Header included, as the reference TypeScript writer does) and the
// Footer's summary_crc.
//
// Memory: bounded whatever the length of the recording. Message bytes go to the file as they
// come (through the stdio buffer), chunk headers are rewritten in place when a chunk closes, so
// a message may be given in pieces and may be larger than a chunk. What is held: the schemas and
// channels, one (log_time, offset) pair per message of the open chunk, and one Chunk Index entry
// (about 100 bytes) per chunk written. So the destination must be seekable (a regular file or
// /dev/null): open() refuses a pipe with os_error() ESPIPE.
//
// Not thread-safe; not copyable. Failures are sticky: the first one is kept and reported by every
// later call and by close().
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "hesai_port/base/crc32_ieee.h"
#include "hesai_port/formats/writers.h"

namespace hesai {
namespace port {

/// Writes one MCAP file: open(), add_schema(), add_channel(), messages, close().
class McapWriter {
 public:
  /// A chunk is closed once its records reach this many bytes (after the message that crossed it).
  static constexpr std::uint64_t kChunkBytes = 1u << 20;

  McapWriter() = default;
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  /// Creates (truncates) `path`, writes the magic and the Header record.
  WriteResult open(const std::string& path, const std::string& profile, const std::string& library);
  /// Registers a schema; its record goes into the data section before the first channel that
  /// uses it, and into the summary. Returns its id (1, 2, ...).
  std::uint16_t add_schema(const std::string& name, const std::string& encoding, const std::string& data);
  /// Registers a channel on `schema_id` (0: none); written as add_schema(). Returns its id (0, 1, ...).
  std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                            const std::map<std::string, std::string>& metadata);
  /// Starts a Message record of `size` data bytes; give exactly that many with append(), then
  /// end_message(). Times in ns (the Header stamp's epoch).
  WriteResult begin_message(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time,
                            std::uint64_t publish_time, std::uint64_t size);
  WriteResult append(const void* data, std::size_t size);
  WriteResult end_message();
  /// begin_message(), append() and end_message() in one.
  WriteResult write_message(std::uint16_t channel_id, std::uint32_t sequence, std::uint64_t log_time,
                            std::uint64_t publish_time, const void* data, std::size_t size);
  /// Writes a Metadata record `name` with its key-value pairs into the data section (the open chunk,
  /// if any, is closed first: metadata lies outside chunks) and indexes it in the summary
  /// (Metadata Index), where readers such as rosbag2 look for it.
  WriteResult add_metadata(const std::string& name, const std::map<std::string, std::string>& metadata);
  /// Closes the open chunk, writes the Data End, the summary, the Footer and the magic, and closes
  /// the file. Reports the first failure of any call.
  WriteResult close();

  bool is_open() const { return file_ != nullptr; }
  std::uint64_t messages() const { return message_count_; }
  std::uint64_t chunks() const { return chunk_index_.size(); }

 private:
  struct Schema {
    std::uint16_t id;
    std::string name, encoding, data;
  };
  struct Channel {
    std::uint16_t id, schema_id;
    std::string topic, message_encoding;
    std::map<std::string, std::string> metadata;
  };
  struct MetadataIndex {
    std::uint64_t offset, length;
    std::string name;
  };
  struct ChunkIndex {
    std::uint64_t start_time, end_time, offset, length, records;
    std::map<std::uint16_t, std::uint64_t> message_index_offsets;
    std::uint64_t message_index_length;
  };

  void put(const void* data, std::size_t size);  // to the file at the end; CRCs follow
  void put_record(std::vector<std::uint8_t>& record);
  void open_chunk();
  void close_chunk();
  void fail(const char* what);
  bool ensure_channel_written(std::uint16_t channel_id);

  std::FILE* file_ = nullptr;
  std::string path_;
  WriteResult error_;
  std::uint64_t position_ = 0;   // bytes written so far (the file's end)
  std::uint32_t data_crc_ = 0;   // CRC of the bytes before the open chunk
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::vector<bool> schema_written_, channel_written_;
  // The open chunk.
  bool chunk_open_ = false;
  std::uint64_t chunk_start_ = 0;  // offset of its opcode
  std::uint32_t chunk_crc_ = 0;    // CRC of its records so far
  std::uint64_t chunk_first_ = 0, chunk_last_ = 0;  // log times; chunk_messages_ > 0
  std::uint64_t chunk_messages_ = 0;
  std::map<std::uint16_t, std::vector<std::uint64_t>> chunk_index_entries_;  // per channel: time, offset pairs
  // The message being written.
  std::uint64_t message_left_ = 0;
  bool in_message_ = false;
  // Statistics and the index.
  std::uint64_t message_count_ = 0, first_time_ = 0, last_time_ = 0;
  std::map<std::uint16_t, std::uint64_t> channel_counts_;
  std::vector<ChunkIndex> chunk_index_;
  std::vector<MetadataIndex> metadata_index_;
};

}  // namespace port
}  // namespace hesai
