// Capture parsing: UDP datagrams out of classic pcap and pcapng files held in memory.
//
// CaptureParser reads a whole capture held in memory (a ByteView), so it runs the same over a
// mapped file, a test buffer or fuzzer input. It never allocates, never reads outside the view,
// and reports a damaged file as an error code with the byte offset of the damaged record.
// parse_frame unpacks one captured frame (link layer, IP, UDP) on its own, for live captures.
// Reading a file from disk is CaptureFile, in hesai_port/capture/capture.h (which includes this header).
//
// Formats (see the pcap and pcapng specifications, draft-ietf-opsawg-pcap / -pcapng):
//   - classic pcap, magic 0xA1B2C3D4 (microsecond) and 0xA1B23C4D (nanosecond), either byte order;
//   - pcapng: sections of either byte order, interfaces with their own link type, snap length,
//     if_tsresol and if_tsoffset; Enhanced, Simple and (obsolete) Packet Blocks; other blocks skipped.
// Link types: null/loopback (0), Ethernet (1) with stacked 802.1Q/802.1ad tags, raw IP (12, 101),
// LOOP (108), Linux SLL (113), raw IPv4 (228), raw IPv6 (229), Linux SLL2 (276).
// Frames are unpacked down to UDP over IPv4 or IPv6; fragments are skipped, not reassembled.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "hesai/bytes.h"

namespace hesai::port {

/// Why a capture cannot be read: the port's own codes (the freestanding core reads no files).
/// Names, as capture_error_name() gives them, are what messages print.
enum class [[nodiscard]] CaptureError : std::uint8_t {
  ok = 0,
  bad_magic,         ///< "capture_bad_magic": not a pcap or pcapng file, or an unsupported version
  truncated,         ///< "capture_truncated": a header, record or block ends past the end of the file
  bad_record,        ///< "capture_bad_record": a record or block length that cannot be (absurd, misaligned)
  unsupported_link,  ///< "capture_unsupported_link": a link type this reader does not unpack (classic pcap)
  io,                ///< "capture_io": the file cannot be opened, read or mapped (see CaptureFile::os_error())
  not_open,          ///< "capture_not_open": CaptureParser::next() before a successful open()
  // MCAP files (McapParser, hesai_port/capture/mcap_parser.h).
  mcap_compressed_chunk,  ///< "mcap_compressed_chunk": a chunk compressed (zstd, lz4): only uncompressed chunks are read
  mcap_chunk_crc,         ///< "mcap_chunk_crc_mismatch": a chunk's records do not match its uncompressed_crc
  mcap_unknown_schema,    ///< "mcap_unknown_schema": a channel names a schema id that no Schema record defined
  mcap_unknown_channel,   ///< "mcap_unknown_channel": a message on a channel id that no Channel record defined
  mcap_bad_encoding,      ///< "mcap_bad_encoding": a PandarScan channel whose message encoding is not "cdr"
  mcap_bad_cdr,           ///< "mcap_bad_cdr": a PandarScan message too short for its CDR, or not little-endian CDR
  mcap_bad_packet_size,   ///< "mcap_bad_packet_size": a PandarPacket whose size exceeds its 1500 data bytes
  mcap_no_pandar_scan,    ///< "mcap_no_pandar_scan": the data section ended without a PandarScan channel
  mcap_cut,               ///< "mcap_cut": the file ends at a record boundary without its Data End, Footer or closing magic
};

/// The last code, for loops over every code (keep it last when adding codes).
inline constexpr CaptureError kLastCaptureError = CaptureError::mcap_cut;

/// Stable lower-case name of a code, for messages and logs ("capture_bad_magic"); "unknown" for
/// a value that is not a code.
const char* capture_error_name(CaptureError e);

/// One UDP datagram of a capture. `payload` points into the parser's input.
struct UdpDatagram {
  ByteView payload;                    ///< UDP payload (the UDP length field minus 8 bytes)
  std::uint64_t time_ns = 0;           ///< capture time, nanoseconds since 1970-01-01 UTC
  std::uint16_t src_port = 0;          ///< UDP source port
  std::uint16_t dst_port = 0;          ///< UDP destination port
  std::uint8_t ip_version = 0;         ///< 4 or 6; 0 for MCAP (no addresses or ports)
  std::array<std::uint8_t, 16> src_addr{};  ///< source address; IPv4 in bytes 0..3, rest zero
  std::array<std::uint8_t, 16> dst_addr{};  ///< destination address; IPv4 in bytes 0..3, rest zero
  std::uint64_t file_offset = 0;       ///< byte offset of the record header (pcap), block (pcapng) or PandarPacket (MCAP)
  std::uint32_t record_index = 0;      ///< 0-based index among all packet records (frame number - 1)
  std::uint32_t interface_id = 0;      ///< pcapng interface within its section; 0 for pcap; the channel id for MCAP
};

/// Outcome of CaptureParser::next.
enum class CaptureStatus : std::uint8_t {
  datagram,  ///< a datagram was written to the output
  end,       ///< the file ended cleanly after its last record
  error,     ///< the file is damaged: see error() and error_offset(); next() keeps returning error
};

/// What a captured frame carries, as far as this reader is concerned.
enum class FrameKind : std::uint8_t {
  udp,               ///< a complete UDP datagram
  non_udp,           ///< a well-formed frame with something else (ARP, TCP, ICMP, 802.3 LLC, ...)
  fragment,          ///< an IPv4 or IPv6 fragment (fragments are not reassembled)
  truncated,         ///< the capture cut the frame before the end of its UDP datagram
  malformed,         ///< headers contradict themselves (IPv4 IHL < 5, lengths past the datagram)
  unsupported_link,  ///< a link type this reader does not unpack
};

/// Skipped and delivered frames of a parse. Invariant: records == datagrams + skipped().
struct CaptureStats {
  std::uint64_t records = 0;         ///< packet records read (pcap records; pcapng EPB, SPB, PB)
  std::uint64_t datagrams = 0;       ///< UDP datagrams returned by next()
  std::uint64_t non_udp = 0;         ///< FrameKind::non_udp frames skipped
  std::uint64_t fragments = 0;       ///< FrameKind::fragment frames skipped
  std::uint64_t truncated = 0;       ///< FrameKind::truncated frames skipped
  std::uint64_t malformed = 0;       ///< FrameKind::malformed frames skipped
  std::uint64_t other_link = 0;      ///< FrameKind::unsupported_link frames skipped (pcapng)
  std::uint64_t other_blocks = 0;    ///< pcapng blocks that carry no packet (statistics, names...)

  /// Packet records that did not give a datagram.
  std::uint64_t skipped() const { return non_udp + fragments + truncated + malformed + other_link; }
};

/// Whether this reader unpacks frames of the pcap/pcapng link type `link_type`.
bool link_type_supported(std::uint32_t link_type);

/// Unpacks one captured frame of link type `link_type` down to its UDP datagram. On
/// FrameKind::udp fills payload, ports, ip_version and addresses of `out` (other fields untouched).
/// Reads only inside `frame`; usable on its own for live captures.
FrameKind parse_frame(std::uint32_t link_type, ByteView frame, UdpDatagram& out);

/// File format of an open capture.
enum class CaptureFormat : std::uint8_t { none, pcap, pcapng, mcap };

/// Reads UDP datagrams from a capture file held in memory. No allocation, no I/O; the caller
/// keeps the bytes alive while datagrams are in use.
/// Safe on arbitrary input, so a fuzzer can drive it directly: `open(bytes)`, then `next()` until
/// it stops returning CaptureStatus::datagram. Invariants: every payload lies inside the input,
/// file_offset < input size, stats().records == stats().datagrams + stats().skipped(), and each
/// datagram consumes at least 12 input bytes (so the loop ends).
class CaptureParser {
 public:
  /// Most interfaces one pcapng section may describe.
  static constexpr std::size_t max_interfaces = 64;
  /// Largest packet record accepted (bytes captured), as libpcap's largest snap length.
  static constexpr std::uint32_t max_record_bytes = 256 * 1024;

  /// Starts reading `file`: checks the pcap global header or the first pcapng section header.
  /// CaptureError::ok, truncated, bad_magic, bad_record or unsupported_link (pcap); the same
  /// code stays in error().
  [[nodiscard]] CaptureError open(ByteView file);

  /// The next UDP datagram. Frames without one are counted in stats() and skipped.
  CaptureStatus next(UdpDatagram& out);

  /// The error that stopped the parse, CaptureError::ok if none.
  [[nodiscard]] CaptureError error() const { return error_; }
  /// Byte offset of the record, block or header where the error was found.
  std::uint64_t error_offset() const { return error_offset_; }
  /// Counters since open().
  const CaptureStats& stats() const { return stats_; }
  /// Format of the open file.
  CaptureFormat format() const { return format_; }
  /// Byte order of the pcap file or of the current pcapng section.
  bool big_endian() const { return big_endian_; }
  /// Timestamps in nanoseconds (pcap magic 0xA1B23C4D); pcap only.
  bool nanosecond_pcap() const { return nanosecond_; }
  /// Link type of a classic pcap file (LINKTYPE_* value).
  std::uint32_t pcap_link_type() const { return pcap_link_; }

 private:
  struct Interface {
    std::uint32_t link_type = 0;
    std::uint32_t snaplen = 0;
    std::uint8_t tsresol = 6;   // if_tsresol byte: bit 7 clear 10^-n, set 2^-n
    std::int64_t tsoffset = 0;  // if_tsoffset, seconds
  };
  // A packet record found by the format reader, before link-layer unpacking.
  struct Record {
    ByteView frame;
    std::uint64_t time_ns = 0;
    std::uint64_t offset = 0;
    std::uint32_t link_type = 0;
    std::uint32_t interface_id = 0;
  };
  enum class Step : std::uint8_t { record, end, error };

  Step next_pcap_record(Record& rec);
  Step next_pcapng_record(Record& rec);
  [[nodiscard]] CaptureError read_section_header(std::size_t at, std::size_t& length);
  [[nodiscard]] CaptureError read_interface(ByteView body);
  Step fail(CaptureError e, std::uint64_t offset);
  std::uint16_t u16(const std::uint8_t* p) const { return big_endian_ ? load_be16(p) : load_le16(p); }
  std::uint32_t u32(const std::uint8_t* p) const { return big_endian_ ? load_be32(p) : load_le32(p); }

  ByteView file_;
  std::size_t pos_ = 0;
  CaptureFormat format_ = CaptureFormat::none;
  bool big_endian_ = false;
  bool nanosecond_ = false;
  std::uint32_t pcap_link_ = 0;
  std::uint32_t pcap_snaplen_ = 0;
  std::array<Interface, max_interfaces> interfaces_{};
  std::size_t interface_count_ = 0;
  std::uint32_t record_index_ = 0;
  CaptureStats stats_{};
  CaptureError error_ = CaptureError::ok;
  std::uint64_t error_offset_ = 0;
};

}  // namespace hesai::port
