// libFuzzer harness: McapParser over a whole MCAP file held in memory (PandarScan bags).
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz_common.h"
#include "hesai_port/capture/mcap_parser.h"

namespace {

using hesai::port::CaptureError;
using hesai::port::CaptureStatus;
using hesai::port::McapParser;

void check_named(CaptureError e) {
  hesai_fuzz::check(std::strcmp(hesai::port::capture_error_name(e), "unknown") != 0);
}

struct Summary {
  CaptureError open_error = CaptureError::ok;
  CaptureError error = CaptureError::ok;
  std::uint64_t error_offset = 0;
  std::uint64_t datagrams = 0;
  std::uint64_t payload_bytes = 0;
  std::uint64_t time_sum = 0;
  std::uint64_t other = 0;
};

Summary parse(hesai::ByteView file) {
  using hesai_fuzz::check;
  Summary s;
  static McapParser parser;  // 32 KiB of id tables: not on the stack
  s.open_error = parser.open(file);
  check_named(s.open_error);
  if (s.open_error != CaptureError::ok) {
    check(parser.error() == s.open_error);
    check(parser.error_offset() <= file.size);
    return s;
  }
  const std::uint8_t* begin = file.data;
  const std::uint8_t* end = file.data + file.size;
  hesai::port::UdpDatagram d;
  CaptureStatus st;
  std::uint64_t steps = 0;
  while ((st = parser.next(d)) == CaptureStatus::datagram) {
    check(++steps <= file.size / McapParser::packet_cdr_bytes);  // each packet takes 1512 input bytes
    check(d.payload.size <= McapParser::packet_data_bytes);
    check(d.payload.data >= begin && d.payload.data <= end &&
          d.payload.size <= static_cast<std::size_t>(end - d.payload.data));
    check(d.file_offset < file.size && begin + d.file_offset + 8 == d.payload.data);
    check(d.ip_version == 0 && d.src_port == 0 && d.dst_port == 0);
    ++s.datagrams;
    s.payload_bytes += d.payload.size;
    s.time_sum += d.time_ns;
    hesai::Model m;
    hesai::PacketKind kind;
    hesai_fuzz::check_named(hesai::identify(d.payload, m, kind));
  }
  s.error = parser.error();
  s.error_offset = parser.error_offset();
  s.other = parser.stats().other_blocks;
  check_named(s.error);
  check((st == CaptureStatus::error) == (s.error != CaptureError::ok));
  if (st == CaptureStatus::error) {
    check(s.error_offset <= file.size);
    if (s.error == CaptureError::mcap_compressed_chunk) {
      const hesai::ByteView c = parser.compression();
      check(c.size > 0 && c.data >= begin && c.size <= static_cast<std::size_t>(end - c.data));
    }
    hesai::port::UdpDatagram again;
    check(parser.next(again) == CaptureStatus::error);  // errors are sticky
  } else {
    hesai::port::UdpDatagram again;
    check(parser.next(again) == CaptureStatus::end);  // so is the end
  }
  const hesai::port::CaptureStats& stats = parser.stats();
  check(stats.records == stats.datagrams + stats.skipped() && stats.datagrams == s.datagrams);
  return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const hesai_fuzz::ExactCopy in(data, size);
  const Summary a = parse(in.view());
  const Summary b = parse(in.view());
  hesai_fuzz::check(a.open_error == b.open_error && a.error == b.error && a.error_offset == b.error_offset &&
                    a.datagrams == b.datagrams && a.payload_bytes == b.payload_bytes && a.time_sum == b.time_sum &&
                    a.other == b.other);
  return 0;
}
