// Capture files on disk: CaptureFile maps a pcap, pcapng or MCAP file read-only and feeds a
// CaptureParser (pcap, pcapng) or a McapParser (a rosbag2 MCAP of PandarScan messages), chosen
// by the file's magic; it hands the pages it has read back to the kernel as it goes, so its
// resident memory stays bounded whatever the file's size.
//
// The parser itself (CaptureParser, parse_frame, the error codes and the datagram type, with the
// formats and link types it reads) is in hesai_port/capture/capture_parser.h, included here: it allocates
// nothing and does no I/O, so a fuzzer, a test or firmware can use it without this file.
#pragma once

#include <string>

#include "hesai_port/capture/capture_parser.h"
#include "hesai_port/capture/mcap_parser.h"

namespace hesai::port {

/// A capture file mapped read-only into memory, with its parser.
/// Read it with next(): every kReleaseBytes consumed, the pages before the current record leave
/// the process (madvise MADV_DONTNEED), so a capture of any size is read in about that much
/// resident memory (a run of frames without a UDP datagram stays resident until the next one).
/// Released pages read back from the file if touched again: every ByteView stays valid.
class CaptureFile {
 public:
  CaptureFile() = default;
  ~CaptureFile();
  CaptureFile(const CaptureFile&) = delete;
  CaptureFile& operator=(const CaptureFile&) = delete;

  /// Maps `path` and opens the parser on it: McapParser when the file starts with the MCAP magic
  /// (or is a prefix of it), CaptureParser otherwise. CaptureError::io when the file cannot be
  /// opened or mapped (errno in os_error()), otherwise the parser's open() result. message() says why.
  [[nodiscard]] CaptureError open(const std::string& path);
  /// Unmaps the file.
  void close();
  /// The next UDP datagram (as parser().next()), releasing the pages already consumed.
  CaptureStatus next(UdpDatagram& out);
  /// Bytes consumed between two releases of pages.
  static constexpr std::size_t kReleaseBytes = std::size_t{8} << 20;

  /// A human-readable account of the last open() or next() failure ("" when none).
  std::string message() const;
  /// errno of the failed system call, 0 when open() did not fail in the OS.
  int os_error() const { return os_error_; }
  /// The whole file's bytes.
  ByteView bytes() const { return {static_cast<const std::uint8_t*>(map_), size_}; }
  /// The parser over a pcap or pcapng file; call parser().next() for datagrams.
  CaptureParser& parser() { return parser_; }
  const CaptureParser& parser() const { return parser_; }
  /// The parser over an MCAP file (format() == CaptureFormat::mcap).
  const McapParser& mcap_parser() const { return mcap_; }
  /// The open file's format (CaptureFormat::mcap for MCAP, else the CaptureParser's).
  CaptureFormat format() const { return is_mcap_ ? CaptureFormat::mcap : parser_.format(); }
  /// The error that stopped the last open() or next() in the parser (CaptureError::ok if none).
  CaptureError error() const { return is_mcap_ ? mcap_.error() : parser_.error(); }
  /// Counters since open().
  const CaptureStats& stats() const { return is_mcap_ ? mcap_.stats() : parser_.stats(); }
  const std::string& path() const { return path_; }

 private:
  void* map_ = nullptr;
  std::size_t size_ = 0;
  std::size_t released_ = 0;  // bytes at the start of the mapping handed back (a page multiple)
  int os_error_ = 0;
  std::string os_what_;
  std::string path_;
  CaptureParser parser_;
  McapParser mcap_;
  bool is_mcap_ = false;
};

}  // namespace hesai::port
