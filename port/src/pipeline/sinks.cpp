#include "hesai_port/pipeline/sinks.h"

#include <cerrno>
#include <cstring>
#include <sys/stat.h>

#include <algorithm>
#include <utility>

#include "hesai_port/formats/pointcloud2.h"

namespace hesai::port {

namespace {
// The channel's offered_qos_profiles (the ros2 profile's one required metadata key), empty: the QoS
// YAML changed between rosbag2 versions (integers up to Humble, names since Jazzy), and every
// version reads an empty value as "not recorded" and plays back with its default profile.
constexpr const char* kQosProfiles = "";

// A writer's failure: an output that cannot be a pipe (ESPIPE: PCD, PLY and MCAP rewrite their
// header) is the request's fault, any other the output's.
Status write_status(const WriteResult& r) {
  return r.os_error() == ESPIPE ? Status::usage(r.message()) : Status::input(r.message());
}
}  // namespace

std::string with_sensor(const std::string& text, const std::string& token) {
  std::string out = text;
  const std::string key = "{sensor}";
  for (std::size_t at = out.find(key); at != std::string::npos; at = out.find(key, at + token.size()))
    out.replace(at, key.size(), token);
  return out;
}

OutputSink::OutputSink(const OutputOptions& o) : options_(o) {
  if (o.format == "pcd") format_ = Format::pcd;
  else if (o.format == "ply") format_ = Format::ply;
  else if (o.format == "png") format_ = Format::png;
  else if (o.format == "mcap") format_ = Format::mcap;
  else format_ = Format::csv;  // options.cpp accepts no other
}

Status OutputSink::open() {
  const bool to_stdout = options_.out.empty() || options_.out == "-";
  if (options_.format == "png") {
    PngOptions png;
    png.range_m = options_.png_range_m;
    png.color_by = options_.png_height ? ColorBy::height : ColorBy::intensity;
    std::string error;
    if (!png_.reset(png, &error)) return Status::usage(error);
  }
  if (options_.format == "mcap") return open_mcap();
  if (options_.per_frame) {
    if (to_stdout) return Status::usage("--per-frame needs --out DIRECTORY");
    if (mkdir(options_.out.c_str(), 0777) != 0 && errno != EEXIST)
      return Status::input("cannot create directory '" + options_.out + "': " + std::strerror(errno));
    return {};
  }
  if (options_.format != "csv" && to_stdout) return Status::usage("--format " + options_.format + " needs --out FILE");
  WriteResult r;
  if (options_.format == "csv") {
    r = to_stdout ? csv_.open(stdout, "stdout") : csv_.open(options_.out);
    csv_open_ = r.ok();
  } else if (options_.format == "pcd" || options_.format == "ply") {
    r = stream_.open(options_.out, options_.format == "pcd" ? CloudFormat::pcd : CloudFormat::ply);
  }
  if (!r) return write_status(r);
  if ((csv_open_ || stream_.is_open()) && !to_stdout) files_.push_back(options_.out);  // one PNG: at close
  return {};
}

std::string OutputSink::frame_path(FrameKey key) const {
  char number[32];
  std::snprintf(number, sizeof number, "_%06llu.", static_cast<unsigned long long>(key.second));
  return options_.out + "/frame_" + sensor(key.first).token + number + options_.format;
}

OutputSink::Frame& OutputSink::open_frame(FrameKey key) {
  const auto [it, fresh] = open_.try_emplace(key);
  if (fresh && format_ == Format::png) it->second.png = png_;  // empty, with the options
  // MCAP: room for as many points as the largest frame so far (grown, a frame's records would be
  // copied about twice over). The storage of the last frame written is taken over: no fresh pages
  // (and their faults) a frame.
  if (fresh && format_ == Format::mcap) {
    it->second.cloud = std::move(spare_cloud_);
    spare_cloud_ = PointCloud2Data();
    it->second.cloud.clear();
    it->second.cloud.reserve(mcap_frame_points_);
  }
  return it->second;
}

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_token_char(char c) { return is_digit(c) || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }

// `text` made a ROS 2 name token: other characters as '_', no "__", not empty, no leading digit.
std::string as_token(const std::string& text) {
  std::string t;
  for (const char c : text) {
    const char k = is_token_char(c) ? c : '_';
    if (k == '_' && !t.empty() && t.back() == '_') continue;
    t += k;
  }
  while (!t.empty() && t.back() == '_') t.pop_back();
  if (!t.empty() && t[0] == '_') t.erase(0, 1);
  if (t.empty()) return "sensor";
  return is_digit(t[0]) ? "s_" + t : t;
}

// The token of a label (see sinks.h); `port` gets the UDP port of an address label.
std::string label_token(const std::string& label, std::string& port) {
  port.clear();
  const std::size_t colon = label.rfind(':');
  if (colon != std::string::npos && colon + 1 < label.size()) {
    const std::string address = label.substr(0, colon);
    const std::string p = label.substr(colon + 1);
    const bool numeric_port = p.find_first_not_of("0123456789") == std::string::npos;
    if (numeric_port && !address.empty() && address.find_first_not_of("0123456789.") == std::string::npos) {
      port = p;
      std::string t = "ip_" + address;
      std::replace(t.begin(), t.end(), '.', '_');
      return t;
    }
    if (numeric_port && address.size() > 2 && address.front() == '[' && address.back() == ']') {
      port = p;
      std::string t = "ip6";
      for (const char c : address.substr(1, address.size() - 2)) t += c == ':' ? (t.back() == '_' ? "0_" : "_") : std::string(1, c);
      return as_token(t);
    }
  }
  // A bag's topic: its last token; anything else as it reads.
  const std::size_t slash = label.rfind('/');
  return as_token(slash == std::string::npos ? label : label.substr(slash + 1));
}

// A CSV field: quoted (RFC 4180) when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string q = "\"";
  for (const char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

const OutputSink::SensorOut& OutputSink::sensor(std::uint32_t s) const {
  static const SensorOut unnamed{"", "sensor", 0, ""};
  return s < sensors_.size() ? sensors_[s] : unnamed;
}

void OutputSink::sensor_added(std::uint32_t s, const std::string& label) {
  if (sensors_.size() <= s) sensors_.resize(s + 1);
  SensorOut& out = sensors_[s];
  out.label = csv_field(label);
  std::string port;
  std::string token = label_token(label, port);
  auto taken = [&](const std::string& t) {
    for (std::size_t i = 0; i < sensors_.size(); ++i)
      if (i != s && sensors_[i].token == t) return true;
    return false;
  };
  if (taken(token) && !port.empty()) token += "_" + port;
  if (taken(token)) token += "_" + std::to_string(s + 1);
  out.token = token;
  if (!mcap_.is_open()) return;
  std::string why;
  const std::string topic = ros2_topic(with_sensor(options_.topic, token), why);
  if (topic.empty()) {
    if (deferred_error_.empty())
      deferred_error_ = "--topic '" + options_.topic + "' for sensor " + label + " is not a ROS 2 topic name: " + why;
    return;
  }
  const auto known = mcap_topics_.find(topic);
  out.channel = known != mcap_topics_.end()
                    ? known->second
                    : mcap_topics_[topic] = mcap_.add_channel(mcap_schema_, topic, kCdrEncoding,
                                                              {{"offered_qos_profiles", kQosProfiles}});
  out.frame_id = with_sensor(options_.frame_id, token);
}

Status OutputSink::open_mcap() {
  if (options_.per_frame) return Status::usage("--format mcap writes one file of one message per frame: drop --per-frame");
  if (options_.out.empty() || options_.out == "-") return Status::usage("--format mcap needs --out FILE");
  const WriteResult r = mcap_.open(options_.out, "ros2", "hesai");
  if (!r) return write_status(r);
  mcap_schema_ = mcap_.add_schema(kPointCloud2Schema, kRos2MsgEncoding, pointcloud2_definition());
  files_.push_back(options_.out);
  return {};
}

void OutputSink::write_mcap_frame(FrameKey key, PointCloud2Data& cloud) {
  if (cloud.size() == 0 || !mcap_.is_open()) return;  // no point, no stamp: no message
  const SensorOut& s = sensor(key.first);
  if (s.frame_id.empty()) return;  // its topic was refused (deferred_error_)
  mcap_frame_points_ = std::max(mcap_frame_points_, cloud.size());
  // header.stamp: the frame's earliest point, so that every time_stamp offset is >= 0.
  const std::vector<std::uint8_t> head =
      pointcloud2_head(cloud.stamp_ns(), s.frame_id, static_cast<std::uint32_t>(cloud.size()));
  // log_time (and publish_time): when the frame was complete, the receive time of the datagram
  // that closed it, never before the previous message's, so the file is in log-time order across
  // sensors whose clocks differ.
  last_log_ns_ = std::max(last_log_ns_, receive_ns_);
  const std::uint64_t t = last_log_ns_;
  WriteResult r = mcap_.begin_message(s.channel, static_cast<std::uint32_t>(key.second), t, t,
                                      pointcloud2_size(head.size(), cloud.size()));
  if (r) r = mcap_.append(head.data(), head.size());
  // The records a slice at a time, each finished (its time_stamp) just before it is written.
  constexpr std::size_t kSlice = 8192;  // records: 256 KiB
  for (std::size_t i = 0; r && i < cloud.size(); i += kSlice) {
    const std::size_t end = std::min(cloud.size(), i + kSlice);
    r = mcap_.append(cloud.finish(end) + i * kPointStep, (end - i) * kPointStep);
  }
  if (r) r = mcap_.append(&kPointCloud2Tail, 1);
  if (r) r = mcap_.end_message();
  if (!r && deferred_error_.empty()) deferred_error_ = r.message();
}

void OutputSink::points(const PointRun& run) {
  points_written_ += run.count;
  const FrameKey key{run.sensor, run.frame};
  if (format_ == Format::mcap) {
    open_frame(key).cloud.add(run.points, run.return_types, run.count);
    return;
  }
  if (options_.per_frame) {
    Frame& f = open_frame(key);
    if (format_ == Format::png) {
      f.png.add(run.points, run.count);
      return;
    }
    f.points.insert(f.points.end(), run.points, run.points + run.count);
    if (format_ == Format::csv) f.packets.insert(f.packets.end(), run.count, run.packet);
    return;
  }
  // The one file: a run's points go to the writer in one call, read where the pipeline has them.
  switch (format_) {
    case Format::png: png_.add(run.points, run.count); break;
    case Format::csv:
      if (csv_open_) {
        const WriteResult r = csv_.write(run.points, run.count, static_cast<std::uint32_t>(run.frame), run.packet,
                                         sensor(run.sensor).label);
        if (!r && deferred_error_.empty()) deferred_error_ = r.message();
      }
      break;
    case Format::pcd:
    case Format::ply: stream_.write(run.points, run.count); break;
    case Format::mcap: break;
  }
}

void OutputSink::frame_closed(const FrameInfo& frame, std::uint32_t sensor_index) {
  const FrameKey key{sensor_index, frame.id};
  if (format_ == Format::mcap) {
    const auto it = open_.find(key);
    if (it == open_.end()) return;  // no point was kept
    write_mcap_frame(key, it->second.cloud);
    if (it->second.cloud.capacity() > spare_cloud_.capacity()) spare_cloud_ = std::move(it->second.cloud);
    open_.erase(it);
    return;
  }
  if (!options_.per_frame) return;
  const Frame f = std::move(open_frame(key));  // empty when no point was kept
  open_.erase(key);
  std::string error;
  if (options_.format == "csv") {
    // Rows of one frame into its own CSV file.
    CsvWriter w;
    const std::string path = frame_path(key);
    const std::string& label = sensor(sensor_index).label;
    WriteResult r = w.open(path);
    for (std::size_t i = 0; r && i < f.points.size(); ++i)
      r = w.write(f.points[i], static_cast<std::uint32_t>(frame.id), f.packets[i], label);
    if (r) r = w.close();
    if (!r && deferred_error_.empty()) deferred_error_ = r.message();
    if (r) files_.push_back(path);
  } else if (!write_cloud(frame_path(key), f.points, f.png, error) && deferred_error_.empty()) {
    deferred_error_ = error;
  }
}

bool OutputSink::write_cloud(const std::string& path, const std::vector<Point>& points, const BirdseyeView& png,
                             std::string& error) {
  WriteResult r;
  if (options_.format == "pcd") r = write_pcd(path, points);
  if (options_.format == "ply") r = write_ply(path, points);
  if (options_.format == "png") r = write_png(path, png);
  if (!r) {
    error = r.message();
    return false;
  }
  files_.push_back(path);
  return true;
}

Status OutputSink::close() {
  std::string error;
  if (mcap_.is_open()) {
    for (auto& [key, frame] : open_) write_mcap_frame(key, frame.cloud);  // frames never closed
    open_.clear();
    // The rosbag2 metadata record, as rosbag2's MCAP storage plugin writes it (the distribution
    // under ROS_DISTRO), so that `ros2 bag info` names it.
    (void)mcap_.add_metadata("rosbag2", {{"ROS_DISTRO", options_.ros_distro}});
    const WriteResult r = mcap_.close();
    if (!r && deferred_error_.empty()) deferred_error_ = r.message();
  } else if (csv_open_ || stream_.is_open()) {
    const WriteResult r = csv_open_ ? csv_.close() : stream_.close();
    if (!r && deferred_error_.empty()) deferred_error_ = r.message();
  } else if (!options_.per_frame && !write_cloud(options_.out, {}, png_, error)) {
    return Status::input(error);
  }
  if (!deferred_error_.empty()) return Status::input(deferred_error_);
  return {};
}

}  // namespace hesai::port
