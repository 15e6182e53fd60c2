// libFuzzer harness: CaptureParser over a whole pcap/pcapng file held in memory.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "fuzz_common.h"
#include "hesai_port/capture/capture.h"

namespace {

// A capture error code must have a name.
void check_named(hesai::port::CaptureError e) {
  hesai_fuzz::check(std::strcmp(hesai::port::capture_error_name(e), "unknown") != 0);
}

struct Summary {
  hesai::port::CaptureError open_error = hesai::port::CaptureError::ok;
  hesai::port::CaptureError error = hesai::port::CaptureError::ok;
  std::uint64_t error_offset = 0;
  std::uint64_t datagrams = 0;
  std::uint64_t payload_bytes = 0;
  std::uint64_t last_time_ns = 0;
  hesai::port::CaptureStats stats;
};

Summary parse(hesai::ByteView file) {
  using hesai_fuzz::check;
  Summary s;
  hesai::port::CaptureParser parser;
  s.open_error = parser.open(file);
  check_named(s.open_error);
  if (s.open_error != hesai::port::CaptureError::ok) {
    check(parser.error() == s.open_error);
    return s;
  }
  const std::uint8_t* begin = file.data;
  const std::uint8_t* end = file.data + file.size;
  hesai::port::UdpDatagram d;
  hesai::port::CaptureStatus st;
  std::uint64_t steps = 0;
  while ((st = parser.next(d)) == hesai::port::CaptureStatus::datagram) {
    check(++steps <= file.size / 12 + 1);  // each datagram consumes at least 12 bytes
    check(d.payload.size == 0 || (d.payload.data >= begin && d.payload.data <= end &&
                                  d.payload.size <= static_cast<std::size_t>(end - d.payload.data)));
    check(d.file_offset < file.size);
    check(d.ip_version == 4 || d.ip_version == 6);
    ++s.datagrams;
    s.payload_bytes += d.payload.size;
    s.last_time_ns = d.time_ns;
    hesai::Model m;
    hesai::PacketKind kind;
    hesai_fuzz::check_named(hesai::identify(d.payload, m, kind));
  }
  s.error = parser.error();
  s.error_offset = parser.error_offset();
  s.stats = parser.stats();
  check_named(s.error);
  check((st == hesai::port::CaptureStatus::error) == (s.error != hesai::port::CaptureError::ok));
  if (st == hesai::port::CaptureStatus::error) {
    check(s.error_offset <= file.size);
    hesai::port::UdpDatagram again;
    check(parser.next(again) == hesai::port::CaptureStatus::error);  // errors are sticky
  }
  check(s.stats.records == s.stats.datagrams + s.stats.skipped());
  check(s.stats.datagrams == s.datagrams);
  return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const hesai_fuzz::ExactCopy in(data, size);
  const Summary a = parse(in.view());
  const Summary b = parse(in.view());
  hesai_fuzz::check(a.open_error == b.open_error && a.error == b.error && a.error_offset == b.error_offset &&
                    a.datagrams == b.datagrams && a.payload_bytes == b.payload_bytes &&
                    a.last_time_ns == b.last_time_ns && a.stats.records == b.stats.records &&
                    a.stats.other_blocks == b.stats.other_blocks);
  return 0;
}
