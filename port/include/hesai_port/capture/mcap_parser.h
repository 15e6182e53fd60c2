// MCAP input: the UDP payloads of a rosbag2 MCAP file of nebula's pandar_msgs/msg/PandarScan.
//
// McapParser reads a whole MCAP file held in memory (a ByteView) and hands out each PandarPacket
// of each PandarScan message as a UdpDatagram, as CaptureParser does for pcap. It never
// allocates, never reads outside the view, and reports a damaged file as a CaptureError code with
// the byte offset of the damaged record. CaptureFile (hesai_port/capture/capture.h) picks it by the magic.
//
// What is read (https://mcap.dev/spec, major version 0): the magic, a Header record first, then
// the data section up to the Data End record (or the Footer). The file must then end in a Footer
// record and the closing magic: a file that ends at a record boundary before them was cut (a
// recorder killed, a copy stopped short) and stops with mcap_cut once every packet before the cut
// has been handed out, so that the damage is reported, not read as a whole bag. Schema, Channel and Message records at the top level or inside Chunk records whose
// compression is "" (none); a chunk's uncompressed_crc is checked unless it is 0 (not computed).
// Other records (message and chunk indexes, attachments, metadata, statistics, unknown opcodes)
// are skipped. The summary section is not read: every record it repeats is in the data section.
//
// Messages: those of a channel whose schema is named pandar_msgs/msg/PandarScan are decoded; its
// message encoding must be "cdr". Messages of other channels are skipped and counted in
// stats().other_blocks; a file with no PandarScan channel at all is mcap_no_pandar_scan.
//
// The message definitions (tier4/nebula, src/nebula_hesai/pandar_msgs/msg/):
//   PandarScan.msg:   std_msgs/Header header, PandarPacket[] packets
//   PandarPacket.msg: builtin_interfaces/Time stamp, uint8[1500] data (a fixed array), uint32 size
// in ROS 2's CDR (XCDR1, the 4-byte encapsulation header 00 01 00 00 for little-endian, then
// every primitive aligned to its size from the byte after that header):
//   header.stamp.sec int32, header.stamp.nanosec uint32, header.frame_id (uint32 length with the
//   NUL, the characters, the NUL), align 4, uint32 packet count, then 1512 bytes per packet:
//   stamp.sec int32, stamp.nanosec uint32, data[1500], size uint32 (always 4-aligned: 8 + 1500).
// A packet's first `size` bytes are its datagram, its stamp the receive time (time_ns).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/bytes.h"
#include "hesai_port/capture/capture_parser.h"

namespace hesai::port {

/// Reads the PandarPackets of an MCAP file held in memory. Safe on arbitrary input: `open(bytes)`,
/// then `next()` until it stops returning CaptureStatus::datagram. Invariants: every payload lies
/// inside the input, file_offset < input size, stats().records == stats().datagrams +
/// stats().skipped() (every packet record gives a datagram), and each datagram consumes at least
/// 1512 input bytes (so the loop ends). Not thread-safe; about 32 KiB (the id tables).
class McapParser {
 public:
  /// The MCAP magic, at the start and the end of every file.
  static constexpr std::array<std::uint8_t, 8> magic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
  /// The bytes of PandarPacket.data (uint8[1500]).
  static constexpr std::size_t packet_data_bytes = 1500;
  /// One PandarPacket in CDR: stamp (8), data, size (4).
  static constexpr std::size_t packet_cdr_bytes = 8 + packet_data_bytes + 4;

  /// Whether `file` starts with the MCAP magic, or is a non-empty prefix of it (a cut file).
  static bool looks_like_mcap(ByteView file);

  /// Starts reading `file`: checks the magic and the Header record. CaptureError::ok,
  /// bad_magic, truncated or bad_record; the same code stays in error().
  [[nodiscard]] CaptureError open(ByteView file);
  /// The next PandarPacket as a datagram.
  CaptureStatus next(UdpDatagram& out);

  /// The error that stopped the parse, CaptureError::ok if none.
  [[nodiscard]] CaptureError error() const { return error_; }
  /// Byte offset of the record where the error was found.
  std::uint64_t error_offset() const { return error_offset_; }
  /// The topic of PandarScan channel `id` (its bytes as in the file), for channel ids below
  /// kTopicIds (rosbag2 numbers channels from 0); empty for others and before their Channel record.
  ByteView topic(std::uint16_t id) const { return id < kTopicIds ? topics_[id] : ByteView{}; }
  static constexpr std::size_t kTopicIds = 256;
  /// Top-level records read whole, the Header the first: for mcap_cut, the record the file was
  /// cut after.
  std::uint32_t records_whole() const { return records_whole_; }
  /// The compression named by the chunk of a mcap_compressed_chunk error (its bytes as in the file).
  ByteView compression() const { return compression_; }
  /// records: packets read; datagrams: packets returned; other_blocks: messages of other channels.
  const CaptureStats& stats() const { return stats_; }

 private:
  static constexpr std::size_t id_words = 65536 / 64;
  using IdSet = std::array<std::uint64_t, id_words>;
  static bool has(const IdSet& s, std::uint16_t id) { return ((s[id >> 6] >> (id & 63u)) & 1u) != 0; }
  static void set(IdSet& s, std::uint16_t id, bool on);

  enum class Step : std::uint8_t { more, datagram, end, error };
  Step fail(CaptureError e, std::uint64_t offset);
  CaptureStatus stop(CaptureError e, std::uint64_t offset);  // fail() for next()
  // One record (opcode, its body, the file offset of its opcode); `in_chunk` inside a chunk.
  Step record(std::uint8_t op, ByteView body, std::uint64_t at, bool in_chunk);
  Step schema(ByteView body, std::uint64_t at);
  Step channel(ByteView body, std::uint64_t at);
  Step message(ByteView body, std::uint64_t at);
  Step chunk(ByteView body, std::uint64_t at);
  Step next_packet(UdpDatagram& out);
  bool closed() const;  // the file ends in a Footer and the closing magic
  std::uint64_t offset_of(const std::uint8_t* p) const { return static_cast<std::uint64_t>(p - file_.data); }

  ByteView file_;
  std::size_t pos_ = 0;          // next top-level record
  bool done_ = false;            // the data section has ended
  bool opened_ = false;
  // The chunk being read: its records and the next one.
  ByteView chunk_records_;
  std::size_t chunk_pos_ = 0;
  bool in_chunk_ = false;
  // The PandarScan message being read: its packets and how many are left.
  ByteView packets_;
  std::uint32_t packets_left_ = 0;
  std::uint16_t message_channel_ = 0;
  // Schema ids seen, those named PandarScan; channel ids seen, those on a PandarScan schema.
  IdSet schemas_{};
  IdSet scan_schemas_{};
  IdSet channels_{};
  IdSet scan_channels_{};
  bool any_scan_channel_ = false;
  std::array<ByteView, kTopicIds> topics_{};  // of the PandarScan channels
  std::uint32_t record_index_ = 0;
  std::uint32_t records_whole_ = 0;  // top-level records read, the Header included
  bool ended_by_footer_ = false;     // the data section ended at a Footer (no Data End)
  CaptureStats stats_{};
  CaptureError error_ = CaptureError::ok;
  std::uint64_t error_offset_ = 0;
  ByteView compression_;
};

}  // namespace hesai::port
