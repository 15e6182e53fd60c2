#include "hesai_port/pipeline/pipeline.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "hesai/calibration.h"
#include "hesai/ct.h"
#include "hesai/gps.h"

namespace hesai::port {

std::uint64_t source_key(const UdpDatagram& d) {
  // MCAP packets carry no address: each PandarScan channel (topic) is one sensor.
  if (d.ip_version == 0) return d.interface_id;
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the address, then the port
  for (std::uint8_t b : d.src_addr) h = (h ^ b) * 1099511628211ull;
  return h ^ d.src_port;
}

std::string source_text(const UdpDatagram& d, const CaptureFile& file) {
  char buf[64];
  if (d.ip_version == 4) {
    std::snprintf(buf, sizeof buf, "%u.%u.%u.%u:%u", d.src_addr[0], d.src_addr[1], d.src_addr[2], d.src_addr[3], d.src_port);
  } else if (d.ip_version == 6) {
    std::string a = "[";
    for (std::size_t i = 0; i < 16; i += 2) {
      std::snprintf(buf, sizeof buf, "%s%x", i ? ":" : "", (d.src_addr[i] << 8) | d.src_addr[i + 1]);
      a += buf;
    }
    return a + "]:" + std::to_string(d.src_port);
  } else {
    // A bag: the channel's topic, when it is printable and short enough to name a sensor.
    const ByteView topic =
        d.interface_id <= 0xFFFF ? file.mcap_parser().topic(static_cast<std::uint16_t>(d.interface_id)) : ByteView{};
    bool printable = topic.size > 0 && topic.size <= 200;
    for (std::size_t i = 0; printable && i < topic.size; ++i) printable = topic[i] > 0x20 && topic[i] < 0x7F;
    if (printable) return std::string(reinterpret_cast<const char*>(topic.data), topic.size);
    std::snprintf(buf, sizeof buf, "mcap channel %u", d.interface_id);
  }
  return buf;
}

Pipeline::Pipeline(const DecodeOptions& options, Sink* sink)
    : options_(options),
      sink_(sink),
      return_types_(sink != nullptr && sink->wants_return_types()),
      // The defaults keep every point: a distance is never negative nor 1e9 m.
      filtered_(options.min_range > 0 || options.max_range < 1e9f || options.frames.has_fov()) {}

Pipeline::~Pipeline() {
  secure_wipe(options_.session_key.data(), options_.session_key.size());
  for (auto& [key, s] : sources_) s.decoder->clear_session_key();
}

void Pipeline::start_session(const std::uint8_t key[32]) {
  session_ = true;
  options_.has_key = true;
  std::copy(key, key + 32, options_.session_key.begin());
  for (auto& [k, s] : sources_) {
    (void)s.decoder->set_session_key(key);  // only unsupported_feature, checked at creation
    s.decoder->set_allow_unsigned(options_.allow_unsigned);
    s.replay.reset();
  }
}

void Pipeline::allow_unsigned_for(Source& src, bool pre_session) {
  if (session_) src.decoder->set_allow_unsigned(options_.allow_unsigned || pre_session);
}

Pipeline::Source* Pipeline::source_for(std::uint64_t key, Model model) {
  auto it = sources_.find(key);
  if (it != sources_.end()) {
    if (it->second.decoder->model() == model) return &it->second;
    while (!it->second.held.empty())  // the old sensor's packets, in the direction assumed
      if (!release_held(it->second)) return nullptr;
    it->second.frames.finish();  // and its open frames, to the sink
    close_frames(it->second);
    it->second.decoder->clear_session_key();
    if (last_source_ == &it->second) last_source_ = nullptr;
    sources_.erase(it);  // another sensor now sends from this address: start over
  }
  Source s;
  s.key = key;
  s.order = sources_made_++;
  s.decoder = std::make_unique<Decoder>(model);
  if (!configure_decoder(*s.decoder)) return nullptr;
  s.frames = options_.frames;
  s.frames.set_rotation(options_.rotation);
  if (sink_) {
    const auto label = labels_.find(key);
    sink_->sensor_added(static_cast<std::uint32_t>(s.order),
                        label != labels_.end() ? label->second : "source " + std::to_string(s.order + 1));
  }
  return &sources_.emplace(key, std::move(s)).first->second;
}

void Pipeline::close_frames(Source& src) {
  FrameInfo f;
  while (src.frames.pop_closed(f)) {
    saturating_increment(stats_.frames);
    if (sink_) sink_->frame_closed(f, static_cast<std::uint32_t>(src.order));
  }
}

bool Pipeline::feed(ByteView payload, std::uint64_t source_key, bool pre_session) {
  saturating_increment(stats_.packets);
  Model model = Model::unknown;
  PacketKind kind = PacketKind::point_cloud;
  Error e = identify(payload, model, kind);
  if (e == Error::ok && kind == PacketKind::gps) {
    GpsPacket gps;
    e = parse_gps_packet(payload, gps);
    if (e != Error::ok) {
      count_error(stats_, e);
      ++rejections_[e];
      return true;
    }
    count_gps(stats_, gps);
    last_gps_ = gps;
    have_gps_ = true;
    for (auto& [key, s] : sources_) s.decoder->update_gps(gps);
    return true;
  }
  if (e != Error::ok) {
    count_error(stats_, e);
    ++rejections_[e];
    return true;
  }
  if (fixed_model_ != Model::unknown && model != fixed_model_) {
    ++foreign_model_packets_;  // not the sensor's model: not decoded, and the source stays as it is
    return true;
  }
  Source* src = source_for(source_key, model);
  if (src == nullptr) return false;

  allow_unsigned_for(*src, pre_session);
  PacketInfo info;
  e = decode(*src, payload, point_packet_index_, info);  // the index it gets once accepted
  if (e != Error::ok) {
    count_error(stats_, e);
    ++rejections_[e];
    return true;
  }
  if (info.signature == SignatureStatus::valid && !src->replay.accept(info)) {
    saturating_increment(stats_.replayed);  // signed, but seen before in this session: refused
    return true;
  }
  const std::uint64_t index = point_packet_index_++;
  if (options_.detect_rotation) {
    // --rotation auto: a packet is decoded for good only in a known direction. Until one is
    // known, packets are held (the oldest decoded as assumed when the hold is full); the packet
    // that decides releases them, each decoded again in the direction it decided.
    const bool decided = src->rotation.observe(info);
    if (!src->rotation.known()) {
      if (src->held.full() && !release_held(*src)) return false;
      if (src->held.push(payload, index | (pre_session ? kPreSessionTag : 0))) return true;
      // decode() accepted it, so it fits: not reached, but the packet is not lost either.
    } else if (decided) {
      const Rotation r = src->rotation.rotation();
      src->frames.set_rotation(r);
      if (r != src->decoder->rotation() || !src->held.empty()) {
        src->decoder->set_rotation(r);
        while (!src->held.empty())
          if (!release_held(*src)) return false;
        allow_unsigned_for(*src, pre_session);
        e = decode(*src, payload, index, info);
        if (e != Error::ok) {  // the packet decoded once: a fault of ours, but counted as bad input
          count_error(stats_, e);
          ++rejections_[e];
          return true;
        }
      }
    }
  }
  return process(*src, index, info);
}

Error Pipeline::decode(Source& src, ByteView payload, std::uint64_t index, PacketInfo& info) {
  // (The columns mode decodes every packet: its columnar decode is about what a survey costs.)
  if (columns_) return src.decoder->decode(payload, info, columns_->room(), column_count_);
  // A packet outside --packets gives the run its counts (points, unit scan) and the frames its
  // blocks at its spin rate's beam spread, as a decoded one does; its points are never made.
  if (!wanted(index)) {
    points_.count = 0;
    return src.decoder->survey(payload, info, scan_, surveyed_points_);
  }
  if (return_types_) return src.decoder->decode(payload, info, points_, scan_, compare_, options_.returns);
  return src.decoder->decode(payload, info, points_, scan_, options_.returns);
}

bool Pipeline::release_held(Source& src) {
  const ByteView payload = src.held.front();
  const std::uint64_t index = src.held.front_tag() & ~kPreSessionTag;
  allow_unsigned_for(src, (src.held.front_tag() & kPreSessionTag) != 0);
  PacketInfo info;
  const Error e = decode(src, payload, index, info);
  src.held.pop_front();
  if (e != Error::ok) {  // it decoded when it came: a fault of ours, but counted as bad input
    count_error(stats_, e);
    ++rejections_[e];
    return true;
  }
  return process(src, index, info);
}

bool Pipeline::process(Source& src, std::uint64_t index, const PacketInfo& info) {
  // The decoder's spread lies within (-180, 180] with min <= max: a refusal is a fault of ours.
  if (const Error e_spread = src.frames.set_beam_spread(src.decoder->beam_spread()); e_spread != Error::ok) {
    error_ = std::string("frame assembly refused the decoder's beam spread: ") + error_name(e_spread);
    return false;
  }
  last_source_ = &src;
  ++src.packets;
  count_model(stats_, info.model);
  switch (info.signature) {
    case SignatureStatus::valid: saturating_increment(stats_.signature_valid); break;
    case SignatureStatus::unverified: saturating_increment(stats_.signature_unverified); break;
    case SignatureStatus::accepted_unsigned:
      saturating_increment(stats_.signature_missing);
      saturating_increment(stats_.unsigned_accepted);
      break;
    case SignatureStatus::not_signed: break;
  }
  if (stats_.first_time_ns == 0) stats_.first_time_ns = info.time_ns;
  stats_.last_time_ns = info.time_ns;
  stats_.spin_rpm_last = info.motor_rpm;
  stats_.return_mode_last = info.return_mode;
  count_status(stats_, info);
  // The sensor's own monitor finds its stalls; the run's counters sum every sensor's sections.
  count_safety(stats_.safety, info.safety, src.safety.observe(info.safety, info.time_ns));

  // The health monitor watches every packet (clocks); it counts the losses of packets that carry
  // no UDP sequence. Only this source's counters move: add their change (below).
  src.health.set_rotation(src.decoder->rotation());
  const HealthCounts health_before = src.health.counts();
  const std::uint32_t health_lost_before = src.health.observe(info);
  const HealthCounts& health = src.health.counts();
  saturating_add(stats_.time_stalls, health.time_stalls - health_before.time_stalls);
  saturating_add(stats_.time_virtual, health.time_virtual - health_before.time_virtual);
  saturating_add(stats_.time_jumps, health.time_jumps - health_before.time_jumps);

  if (health.fov_gap && (!stats_.fov_gap || fov_source_ == &src)) {
    fov_source_ = &src;
    stats_.fov_gap = true;
    stats_.fov_gap_from = health.fov_gap_from;
    stats_.fov_gap_to = health.fov_gap_to;
  }
  src.health.observe_units(scan_);
  saturating_add(stats_.blockage_units, scan_.blockage_units);
  saturating_add(stats_.duplicate_returns, scan_.duplicate_returns);
  saturating_add(stats_.beyond_rated_range, scan_.beyond_rated_range);
  if (scan_.blockage_units != 0)
    for (std::size_t ch = 0; ch < kMaxChannels; ++ch) saturating_add(stats_.blockage_by_channel[ch], scan_.blockage_by_channel[ch]);

  std::uint32_t lost_before = 0;
  if (!info.has_sequence) {
    // `lost` can fall (a late packet, an FOV gap taken back): the change either way, saturating.
    lost_before = health_lost_before;
    saturating_follow(stats_.lost, health_before.lost, health.lost);
    saturating_follow(stats_.duplicates, health_before.duplicates, health.duplicates);
    saturating_follow(stats_.reordered, health_before.reordered, health.reordered);
    stats_.lost_by = stats_.lost_by | LostBy::azimuth_time;
    src.lost_by = src.lost_by | LostBy::azimuth_time;
  } else {
    stats_.lost_by = stats_.lost_by | LostBy::udp_sequence;
    src.lost_by = src.lost_by | LostBy::udp_sequence;
    // Only this source's counters move: add their change. `lost` can fall (a late packet): the
    // change either way, saturating.
    const SequenceCounts before = src.sequence.counts();
    lost_before = src.sequence.observe(info.sequence);
    const SequenceCounts& after = src.sequence.counts();
    saturating_follow(stats_.lost, before.lost, after.lost);
    saturating_follow(stats_.duplicates, before.duplicates, after.duplicates);
    saturating_follow(stats_.reordered, before.reordered, after.reordered);
    saturating_follow(stats_.sequence_resyncs, before.resyncs, after.resyncs);
  }

  if (columns_) {  // the columns mode: every point kept as decoded, no frames
    saturating_add(stats_.points, column_count_);
    if (wanted(index)) columns_->kept(column_count_, index, static_cast<std::uint32_t>(src.order), info);
    return true;
  }

  // Each point goes to the frame of its own azimuth, a block's points at once (FrameAssembler::
  // points(): one frame for the whole block unless it straddles a cut); frames close when the
  // blocks have moved far enough past their end that no later point can reach them.
  // `points` counts every point decoded: with --returns distinct, the repeated ones left out too;
  // and those of the packets outside --packets, surveyed (all their points: Returns::all).
  const bool keep = wanted(index);
  if (!keep)
    saturating_add(stats_.points, surveyed_points_);
  else if (options_.returns == Returns::distinct)
    saturating_add(stats_.points, scan_.duplicate_returns);
  FrameAssembler& frames = src.frames;
  frames.begin_packet(index, lost_before);
  std::size_t next = 0;
  for (std::size_t b = 0; b < info.blocks; ++b) {
    if (frames.block(info.block_azimuth[b])) {
      flush_points();  // every point of a frame before its frame_closed()
      close_frames(src);
    }
    if (!keep) continue;  // no point was made
    const std::size_t first = next;
    while (next < points_.count && points_.points[next].block == b) ++next;
    saturating_add(stats_.points, next - first);
    if (next > first) assign_frames(src, index, info, first, next);
  }
  flush_points();
  return true;
}

void Pipeline::assign_frames(Source& src, std::uint64_t index, const PacketInfo& info, std::size_t first,
                             std::size_t end) {
  const Point* p = points_.points.data();
  std::uint64_t* ids = sink_ ? ids_.data() : nullptr;  // stats needs no point's frame
  const Point* kept = p + first;  // the block's kept points, in order
  NebulaReturnType* types = return_types_ ? types_.data() + first : nullptr;
  std::size_t n = end - first;
  if (filtered_) {  // gathered after those of the packet's earlier blocks: one run where one frame
    Point* g = gathered_.data() + gathered_n_;
    NebulaReturnType* gt = gathered_types_.data() + gathered_n_;
    n = 0;
    for (std::size_t i = first; i < end; ++i) {
      if (p[i].distance_m < options_.min_range || p[i].distance_m > options_.max_range) continue;
      if (!src.frames.in_fov(p[i].azimuth_deg)) continue;
      g[n++] = p[i];
    }
    kept = g;
    types = return_types_ ? gt : nullptr;
    gathered_n_ += n;
  }
  const std::uint64_t id = src.frames.points(&kept->azimuth_deg, n, sizeof(Point), ids);
  if (!sink_) return;
  if (types != nullptr) {
    if (first == 0) type_of_ = PacketReturnTypes(info);  // the packet's first block of points
    type_of_.of_block(compare_, kept, n, types);
  }
  const auto sensor = static_cast<std::uint32_t>(src.order);
  if (id != 0) {
    run_points(kept, types, n, id, index, sensor);
    return;
  }
  // The block straddles a cut: a run a change of frame.
  for (std::size_t k = 0; k < n;) {
    std::size_t e = k + 1;
    while (e < n && ids_[e] == ids_[k]) ++e;
    run_points(kept + k, types ? types + k : nullptr, e - k, ids_[k], index, sensor);
    k = e;
  }
}

void Pipeline::run_points(const Point* points, const NebulaReturnType* types, std::size_t count, std::uint64_t frame,
                          std::uint64_t packet, std::uint32_t sensor) {
  if (count == 0) return;
  if (run_.count != 0 && run_.frame == frame && run_.packet == packet && run_.points + run_.count == points) {
    run_.count += count;  // the next points of the same arrays (types follow the points)
    return;
  }
  if (run_.count != 0) sink_->points(run_);
  run_ = PointRun{points, types, count, frame, packet, sensor};
}

void Pipeline::flush_points() {
  if (run_.count != 0) sink_->points(run_);
  run_.count = 0;
  gathered_n_ = 0;  // no run points into gathered_ any more
}

std::vector<SensorReport> Pipeline::sensors() const {
  std::vector<std::pair<std::uint64_t, SensorReport>> ordered;
  for (const auto& [key, s] : sources_) {
    if (s.packets == 0) continue;
    SensorReport r;
    const auto label = labels_.find(key);
    r.source = label != labels_.end() ? label->second : "source " + std::to_string(s.order + 1);
    r.model = s.decoder->model();
    r.packets = s.packets;
    r.lost_by = s.lost_by;
    r.health = s.health.counts();
    // A sensor whose packets carry no sequence counts by its monitor; one whose packets do, by the sequence.
    r.lost = s.lost_by == LostBy::azimuth_time ? r.health.lost : s.sequence.counts().lost;
    ordered.emplace_back(s.order, std::move(r));
  }
  std::sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<SensorReport> out;
  for (auto& [order, r] : ordered) out.push_back(std::move(r));
  return out;
}

std::string Pipeline::rotation_text() const {
  if (last_source_ == nullptr) return "";
  const bool cw = last_source_->decoder->rotation() == Rotation::clockwise;
  const std::string name = cw ? "clockwise" : "counterclockwise";
  if (!options_.detect_rotation) return name + " (set)";
  return last_source_->rotation.known() ? name + " (detected)" : name + " (assumed: not detected)";
}

void Pipeline::finish() {
  for (auto& [key, s] : sources_) {
    // The direction never became known: the held packets are decoded in the assumed one.
    while (!s.held.empty()) (void)release_held(s);
    s.frames.finish();
    close_frames(s);
  }
}

}  // namespace hesai::port
