#include "sinks.h"

#include <cerrno>
#include <cstring>
#include <sys/stat.h>

#include <algorithm>
#include <utility>

#include "hesai_port/formats/pointcloud2.h"

namespace hesai::cli {

OutputSink::OutputSink(const OutputOptions& o) : options_(o) {
  if (o.format == "pcd") format_ = Format::pcd;
  else if (o.format == "ply") format_ = Format::ply;
  else if (o.format == "png") format_ = Format::png;
  else if (o.format == "mcap") format_ = Format::mcap;
  else format_ = Format::csv;  // options.cpp accepts no other
}

int OutputSink::open(std::string& error) {
  const bool to_stdout = options_.out.empty() || options_.out == "-";
  if (options_.format == "png") {
    port::PngOptions png;
    png.range_m = options_.png_range_m;
    png.color_by = options_.png_height ? port::ColorBy::height : port::ColorBy::intensity;
    if (!png_.reset(png, &error)) return kExitUsage;
  }
  if (options_.format == "mcap") return open_mcap(error);
  if (options_.per_frame) {
    if (to_stdout) {
      error = "--per-frame needs --out DIRECTORY";
      return kExitUsage;
    }
    if (mkdir(options_.out.c_str(), 0777) != 0 && errno != EEXIST) {
      error = "cannot create directory '" + options_.out + "': " + std::strerror(errno);
      return kExitInput;
    }
    return kExitOk;
  }
  if (options_.format != "csv" && to_stdout) {
    error = "--format " + options_.format + " needs --out FILE";
    return kExitUsage;
  }
  port::WriteResult r;
  if (options_.format == "csv") {
    r = to_stdout ? csv_.open(stdout, "stdout") : csv_.open(options_.out);
    csv_open_ = r.ok();
  } else if (options_.format == "pcd" || options_.format == "ply") {
    r = stream_.open(options_.out, options_.format == "pcd" ? port::CloudFormat::pcd : port::CloudFormat::ply);
  }
  if (!r) {
    error = r.message();
    return r.os_error() == ESPIPE ? kExitUsage : kExitInput;
  }
  if ((csv_open_ || stream_.is_open()) && !to_stdout) files_.push_back(options_.out);  // one PNG: at close
  return kExitOk;
}

std::string OutputSink::frame_path(std::uint64_t id) const {
  char name[64];
  std::snprintf(name, sizeof name, "/frame_%06llu.%s", static_cast<unsigned long long>(id), options_.format.c_str());
  return options_.out + name;
}

OutputSink::Frame& OutputSink::open_frame(std::uint64_t id) {
  const auto [it, fresh] = open_.try_emplace(id);
  if (fresh && format_ == Format::png) it->second.png = png_;  // empty, with the options
  // MCAP: room for as many points as the largest frame so far (grown a point at a time, a frame's
  // 40-byte points were copied about twice over).
  // The storage of the last frame written is taken over: no fresh pages (and their faults) a frame.
  if (fresh && format_ == Format::mcap) {
    it->second.points = std::move(spare_points_);
    spare_points_ = std::vector<Point>();
    it->second.points.clear();
    it->second.points.reserve(mcap_frame_points_);
  }
  return it->second;
}

namespace {
// The channel's offered_qos_profiles (the ros2 profile's one required metadata key), empty: the QoS
// YAML changed between rosbag2 versions (integers up to Humble, names since Jazzy, read by the
// version of a rosbag2 metadata record this file does not have), and every version reads an empty
// value as "not recorded" and plays back with its default profile.
constexpr const char* kQosProfiles = "";
}  // namespace

int OutputSink::open_mcap(std::string& error) {
  if (options_.per_frame) {
    error = "--format mcap writes one file of one message per frame: drop --per-frame";
    return kExitUsage;
  }
  if (options_.out.empty() || options_.out == "-") {
    error = "--format mcap needs --out FILE";
    return kExitUsage;
  }
  const port::WriteResult r = mcap_.open(options_.out, "ros2", "hesai");
  if (!r) {
    error = r.message();
    return r.os_error() == ESPIPE ? kExitUsage : kExitInput;
  }
  const std::uint16_t schema =
      mcap_.add_schema(port::kPointCloud2Schema, port::kRos2MsgEncoding, port::pointcloud2_definition());
  mcap_channel_ = mcap_.add_channel(schema, options_.topic, port::kCdrEncoding, {{"offered_qos_profiles", kQosProfiles}});
  files_.push_back(options_.out);
  return kExitOk;
}

void OutputSink::write_mcap_frame(std::uint64_t id, const std::vector<Point>& points) {
  if (points.empty() || !mcap_.is_open()) return;  // no point, no stamp: no message
  mcap_frame_points_ = std::max(mcap_frame_points_, points.size());
  // header.stamp: the frame's earliest point, so that every time_stamp offset is >= 0.
  std::int64_t stamp = points[0].time_ns;
  for (const Point& p : points) stamp = std::min(stamp, p.time_ns);
  const std::vector<std::uint8_t> head =
      port::pointcloud2_head(stamp, options_.frame_id, static_cast<std::uint32_t>(points.size()));
  const auto t = static_cast<std::uint64_t>(stamp);
  port::WriteResult r = mcap_.begin_message(mcap_channel_, static_cast<std::uint32_t>(id), t, t,
                                            port::pointcloud2_size(head.size(), points.size()));
  if (r) r = mcap_.append(head.data(), head.size());
  std::uint8_t block[2048 * port::kPointStep];
  for (std::size_t i = 0; r && i < points.size();) {
    std::size_t n = 0;
    for (; n < 2048 && i < points.size(); ++n, ++i) port::encode_point(points[i], stamp, block + n * port::kPointStep);
    r = mcap_.append(block, n * port::kPointStep);
  }
  if (r) r = mcap_.append(&port::kPointCloud2Tail, 1);
  if (r) r = mcap_.end_message();
  if (!r && deferred_error_.empty()) deferred_error_ = r.message();
}

void OutputSink::points(const OutPoint* pts, std::size_t count) {
  points_written_ += count;
  if (format_ == Format::mcap || options_.per_frame) {
    // Near a cut the points of two frames interleave: each goes to its own frame (looked up when
    // the frame changes; no frame closes during this call, so the pointer stays valid).
    Frame* f = nullptr;
    std::uint64_t id = 0;
    for (std::size_t i = 0; i < count; ++i) {
      if (f == nullptr || pts[i].frame != id) {
        id = pts[i].frame;
        f = &open_frame(id);
      }
      if (format_ == Format::png) {
        f->png.add(pts[i].point);
        continue;
      }
      f->points.push_back(pts[i].point);
      if (format_ == Format::csv) f->packets.push_back(pts[i].packet);
    }
    return;
  }
  // The one file: the points of each run of one frame (a packet's, but where it straddles a cut)
  // go to the writer in one call.
  for (std::size_t i = 0; i < count;) {
    std::size_t end = i + 1;
    while (end < count && pts[end].frame == pts[i].frame && pts[end].packet == pts[i].packet) ++end;
    run_.clear();
    for (std::size_t k = i; k < end; ++k) run_.push_back(pts[k].point);
    switch (format_) {
      case Format::png: png_.add(run_.data(), run_.size()); break;
      case Format::csv:
        if (csv_open_) {
          const port::WriteResult r =
              csv_.write(run_.data(), run_.size(), static_cast<std::uint32_t>(pts[i].frame), pts[i].packet);
          if (!r && deferred_error_.empty()) deferred_error_ = r.message();
        }
        break;
      case Format::pcd:
      case Format::ply: stream_.write(run_.data(), run_.size()); break;
      case Format::mcap: break;
    }
    i = end;
  }
}

void OutputSink::frame_closed(const FrameInfo& frame) {
  if (options_.format == "mcap") {
    const auto it = open_.find(frame.id);
    if (it == open_.end()) return;  // no point was kept
    write_mcap_frame(frame.id, it->second.points);
    if (it->second.points.capacity() > spare_points_.capacity()) spare_points_ = std::move(it->second.points);
    open_.erase(it);
    return;
  }
  if (!options_.per_frame) return;
  const Frame f = std::move(open_frame(frame.id));  // empty when no point was kept
  open_.erase(frame.id);
  std::string error;
  if (options_.format == "csv") {
    // Rows of one frame into its own CSV file.
    port::CsvWriter w;
    const std::string path = frame_path(frame.id);
    port::WriteResult r = w.open(path);
    for (std::size_t i = 0; r && i < f.points.size(); ++i)
      r = w.write(f.points[i], static_cast<std::uint32_t>(frame.id), f.packets[i]);
    if (r) r = w.close();
    if (!r && deferred_error_.empty()) deferred_error_ = r.message();
    if (r) files_.push_back(path);
  } else if (!write_cloud(frame_path(frame.id), f.points, f.png, error) && deferred_error_.empty()) {
    deferred_error_ = error;
  }
}

bool OutputSink::write_cloud(const std::string& path, const std::vector<Point>& points, const port::BirdseyeView& png,
                             std::string& error) {
  port::WriteResult r;
  if (options_.format == "pcd") r = port::write_pcd(path, points);
  if (options_.format == "ply") r = port::write_ply(path, points);
  if (options_.format == "png") r = port::write_png(path, png);
  if (!r) {
    error = r.message();
    return false;
  }
  files_.push_back(path);
  return true;
}

bool OutputSink::close(std::string& error) {
  if (mcap_.is_open()) {
    for (const auto& [id, frame] : open_) write_mcap_frame(id, frame.points);  // frames never closed
    open_.clear();
    const port::WriteResult r = mcap_.close();
    if (!r && deferred_error_.empty()) deferred_error_ = r.message();
  } else if (csv_open_ || stream_.is_open()) {
    const port::WriteResult r = csv_open_ ? csv_.close() : stream_.close();
    if (!r && deferred_error_.empty()) deferred_error_ = r.message();
  } else if (!options_.per_frame && !write_cloud(options_.out, {}, png_, error)) {
    return false;
  }
  if (!deferred_error_.empty()) {
    error = deferred_error_;
    return false;
  }
  return true;
}

}  // namespace hesai::cli
