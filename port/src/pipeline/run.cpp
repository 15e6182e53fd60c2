#include "hesai_port/pipeline/run.h"

namespace hesai::port {

bool CaptureFeed::next() {
  if (ended_) return false;
  UdpDatagram d;
  const CaptureStatus st = file_.next(d);
  if (st == CaptureStatus::datagram) {
    ++datagrams_;
    offset_ = d.file_offset;
    const std::uint64_t key = source_key(d);
    if (!pipeline_.has_label(key)) pipeline_.label_source(key, source_text(d, file_));
    pipeline_.set_receive_time(d.time_ns);
    if (pipeline_.feed(d.payload, key)) return true;
    status_ = Status::usage(pipeline_.error());  // a configuration error: the run stops here, unfinished
    ended_ = true;
    return false;
  }
  if (st == CaptureStatus::error) status_ = Status::input(file_.message());
  pipeline_.finish();
  ended_ = true;
  return false;
}

double CaptureFeed::fraction() const {
  const std::size_t total = file_.bytes().size;
  return total == 0 ? 1.0 : static_cast<double>(offset_) / static_cast<double>(total);
}

Status run_capture(CaptureFile& file, Pipeline& pipeline, const std::function<void(const CaptureFeed&)>& progress) {
  CaptureFeed feed(file, pipeline);
  while (feed.next())
    if (progress && (feed.datagrams() & 0x3FFF) == 0) progress(feed);
  return feed.status();
}

}  // namespace hesai::port
