// libFuzzer harness: a stream of packets. Input: one byte of cut angle (its value modulo 3 also
// picks the rotation: clockwise, counter-clockwise, or detected by a RotationDetector), then
// records of a u16 little-endian length and that many payload bytes (a short last record takes
// what is left). Each record goes through identify(), the decoder of its model (GPS packets
// update the Pandar40 decoder), the SequenceTracker, the FrameAssembler (every point by its own
// azimuth with the decoder's beam spread) and the QT128 SafetyMonitor.
#include <cstddef>
#include <cstdint>

#include "fuzz_common.h"
#include "hesai/bytes.h"
#include "hesai/frame.h"
#include "hesai/rotation.h"
#include "hesai/safety.h"
#include "hesai/sequence.h"

namespace {

struct Totals {
  std::uint64_t packets = 0, decoded = 0, points = 0, frames = 0, frame_points = 0, frame_blocks = 0;
  std::uint64_t last_id = 0;
  hesai::SequenceCounts seq;
  hesai::SafetyCounts safety;
};

void close_frames(hesai::FrameAssembler& frames, Totals& t) {
  using hesai_fuzz::check;
  hesai::FrameInfo f;
  while (frames.pop_closed(f)) {
    check(f.id == t.last_id + 1);  // ids close in order, none skipped
    check(f.packets > 0 ? f.first_packet <= f.last_packet : f.points == 0 && f.blocks == 0);
    check(f.first_azimuth_cdeg < 36000 && f.last_azimuth_cdeg < 36000);
    check(f.late_points <= f.points);
    check(!(f.lost_packets > 0) || f.loss);
    t.last_id = f.id;
    ++t.frames;
    t.frame_points += f.points;
    t.frame_blocks += f.blocks;
  }
}

Totals run(hesai::ByteView in) {
  using hesai_fuzz::check;
  Totals t;
  if (in.size == 0) return t;
  // One decoder per model, indexed by Model - 1.
  hesai::Decoder decoders[] = {hesai::Decoder(hesai::Model::pandar40),     hesai::Decoder(hesai::Model::pandar40p),
                               hesai::Decoder(hesai::Model::pandar64),     hesai::Decoder(hesai::Model::qt128c2x),
                               hesai::Decoder(hesai::Model::pandar_qt64),  hesai::Decoder(hesai::Model::pandar_xt16),
                               hesai::Decoder(hesai::Model::pandar_xt32),  hesai::Decoder(hesai::Model::pandar_xt32m2x)};
  static_assert(sizeof decoders / sizeof decoders[0] == hesai::kModelCount - 1, "a decoder for every model");
  static hesai::SequenceTracker tracker;
  tracker.reset();
  hesai::SafetyMonitor monitor;
  hesai::SafetyCounts summed;  // count_safety with the monitor's answers: must equal its own counts
  hesai::FrameAssembler frames;
  hesai::RotationDetector detector;
  check(frames.set_cut_deg(static_cast<float>(in[0]) * 360.0f / 256.0f) == hesai::Error::ok);
  const bool detect = in[0] % 3 == 2;
  const hesai::Rotation fixed = in[0] % 3 == 1 ? hesai::Rotation::counterclockwise : hesai::Rotation::clockwise;
  frames.set_rotation(fixed);
  for (hesai::Decoder& d : decoders) d.set_rotation(fixed);
  std::uint64_t blocks_given = 0;
  std::size_t off = 1;
  while (off < in.size) {
    std::size_t n = in.size - off;
    if (n >= 2) {
      n = hesai::load_le16(in.data + off);
      off += 2;
      if (n > in.size - off) n = in.size - off;
    } else {
      off = in.size - n;
    }
    const hesai::ByteView p = in.sub(off, n);
    off += n;
    ++t.packets;
    hesai::Model model = hesai::Model::unknown;
    hesai::PacketKind kind = hesai::PacketKind::point_cloud;
    const hesai::Error e = hesai::identify(p, model, kind);
    hesai_fuzz::check_named(e);
    if (e != hesai::Error::ok) continue;
    if (kind == hesai::PacketKind::gps) {
      check(model == hesai::Model::unknown);
      hesai::GpsPacket gps;
      if (hesai::parse_gps_packet(p, gps) == hesai::Error::ok) decoders[0].update_gps(gps);
      continue;
    }
    check(model != hesai::Model::unknown);
    hesai::Decoder& d = decoders[static_cast<std::size_t>(model) - 1];
    static hesai::PacketPoints points;
    hesai::PacketInfo info;
    if (hesai_fuzz::decode_checked(d, p) != hesai::Error::ok) continue;
    check(d.decode(p, info, points) == hesai::Error::ok);
    ++t.decoded;
    t.points += points.count;
    const bool stall = monitor.observe(info.safety, info.time_ns);
    check(!stall || monitor.stalled());
    hesai::count_safety(summed, info.safety, stall);
    if (detect && detector.observe(info)) {
      check(detector.known());
      frames.set_rotation(detector.rotation());
      for (hesai::Decoder& other : decoders) other.set_rotation(detector.rotation());
    }
    const hesai::AzimuthSpread spread = d.beam_spread();
    check(spread.min_deg <= spread.max_deg);
    check(frames.set_beam_spread(spread) == hesai::Error::ok);
    const std::uint32_t lost = info.has_sequence ? tracker.observe(info.sequence) : 0;
    frames.begin_packet(t.packets, lost);
    std::size_t next = 0;
    for (std::size_t b = 0; b < info.blocks; ++b) {
      if (frames.block(info.block_azimuth[b])) close_frames(frames, t);
      ++blocks_given;
      for (; next < points.count && points.points[next].block == b; ++next) {
        const std::uint64_t id = frames.point(points.points[next].azimuth_deg);
        check(id > t.last_id && frames.is_open());  // never a frame already closed
      }
    }
    check(next == points.count);
  }
  if (frames.finish()) close_frames(frames, t);
  check(!frames.is_open());
  check(frames.frames_dropped() == 0);
  check(t.frame_points == t.points);  // every point lands in exactly one frame
  check(t.frame_blocks == blocks_given);
  t.seq = tracker.counts();
  check(t.seq.stale <= t.seq.reordered && t.seq.packets <= t.decoded);
  t.safety = monitor.counts();
  std::uint64_t in_states = 0;
  for (std::uint64_t n : t.safety.states) in_states += n;
  check(in_states == t.safety.packets && t.safety.packets <= t.decoded);
  check(t.safety.current_fault + t.safety.past_fault + t.safety.reserved_fault_type <= t.safety.packets);
  check(t.safety.counter_stalls <= t.safety.packets && (t.safety.counter_stalls > 0 || !monitor.stalled()));
  check(t.safety.last_fault_id <= 15 && t.safety.last_fault_total <= 15);
  check(summed.packets == t.safety.packets && summed.states == t.safety.states &&
        summed.counter_stalls == t.safety.counter_stalls && summed.last_fault_code == t.safety.last_fault_code);
  return t;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const hesai_fuzz::ExactCopy in(data, size);
  const Totals a = run(in.view());
  const Totals b = run(in.view());
  hesai_fuzz::check(a.packets == b.packets && a.decoded == b.decoded && a.points == b.points &&
                    a.frames == b.frames && a.frame_points == b.frame_points && a.seq.lost == b.seq.lost &&
                    a.seq.duplicates == b.seq.duplicates && a.seq.reordered == b.seq.reordered &&
                    a.seq.resyncs == b.seq.resyncs && a.safety.packets == b.safety.packets &&
                    a.safety.counter_stalls == b.safety.counter_stalls && a.safety.states == b.safety.states);
  return 0;
}
