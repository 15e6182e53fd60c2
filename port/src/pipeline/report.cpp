#include "hesai_port/pipeline/report.h"

#include <ctime>

#include "hesai/decoder.h"
#include "hesai/safety.h"
#include "hesai_port/base/text.h"

namespace hesai::port {

namespace {
void add(std::string& out, const char* key, std::uint64_t v, bool comma = true) {
  out += "\"";
  out += key;
  out += "\":" + std::to_string(v) + (comma ? "," : "");
}
// 0.01 degree as degrees with two decimals.
std::string degrees(std::uint16_t cdeg) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%u.%02u", static_cast<unsigned>(cdeg / 100), static_cast<unsigned>(cdeg % 100));
  return buf;
}
// [start, end] in degrees, or null.
std::string fov_json(bool has, std::uint16_t from, std::uint16_t to) {
  return has ? "[" + degrees(from) + "," + degrees(to) + "]" : "null";
}

// The most channels of the models the run saw (the length of blockage_by_channel).
std::size_t channels_seen(const Stats& s) {
  std::size_t n = 0;
  for (std::size_t m = 1; m < kModelCount; ++m)
    if (s.models[m] != 0 && channel_count(static_cast<Model>(m)) > n) n = channel_count(static_cast<Model>(m));
  return n;
}

// The stream-health keys that the run (Stats) and each sensor (HealthCounts) share, lost_by to
// fov_gap_deg, with `channels` entries of blockage_by_channel; no comma after the last.
template <typename Counts>
void health_json(std::string& out, LostBy lost_by, const Counts& c, std::size_t channels) {
  out += "\"lost_by\":\"" + std::string(lost_by_name(lost_by)) + "\",";
  add(out, "time_stalls", c.time_stalls);
  add(out, "time_virtual", c.time_virtual);
  add(out, "time_jumps", c.time_jumps);
  add(out, "blockage_units", c.blockage_units);
  out += "\"blockage_by_channel\":[";
  for (std::size_t ch = 0; ch < channels; ++ch) out += (ch ? "," : "") + std::to_string(c.blockage_by_channel[ch]);
  out += "],";
  add(out, "duplicate_returns", c.duplicate_returns);
  add(out, "beyond_rated_range", c.beyond_rated_range);
  out += "\"fov_gap_deg\":" + fov_json(c.fov_gap, c.fov_gap_from, c.fov_gap_to);
}

std::string sensor_json(const SensorReport& r) {
  // The source is a peer's address or a bag's topic, which may hold '"' or '\\': escaped.
  std::string out = "{\"source\":" + json_string(r.source) + ",\"model\":\"" + model_name(r.model) + "\",";
  add(out, "packets", r.packets);
  add(out, "lost", r.lost);
  health_json(out, r.lost_by, r.health, channel_count(r.model));
  return out + "}";
}
}  // namespace

std::string stats_json(const Stats& s, const std::vector<SensorReport>& sensors) {
  std::string out = "{";
  add(out, "packets", s.packets);
  out += "\"models\":{";
  bool first = true;
  for (std::size_t m = 1; m < kModelCount; ++m) {
    if (s.models[m] == 0) continue;
    if (!first) out += ",";
    first = false;
    out += "\"" + std::string(model_name(static_cast<Model>(m))) + "\":" + std::to_string(s.models[m]);
  }
  out += "},";
  add(out, "points", s.points);
  add(out, "frames", s.frames);
  add(out, "crc_errors", s.crc_errors);
  add(out, "signature_valid", s.signature_valid);
  add(out, "signature_invalid", s.signature_invalid);
  add(out, "signature_missing", s.signature_missing);
  add(out, "unsigned_accepted", s.unsigned_accepted);
  add(out, "unsigned_rejected", s.unsigned_rejected);
  add(out, "signature_unverified", s.signature_unverified);
  add(out, "replayed", s.replayed);
  add(out, "malformed", s.malformed);
  add(out, "unsupported", s.unsupported);
  add(out, "lost", s.lost);
  add(out, "duplicates", s.duplicates);
  add(out, "reordered", s.reordered);
  add(out, "sequence_resyncs", s.sequence_resyncs);
  health_json(out, s.lost_by, s, channels_seen(s));
  out += ",";
  add(out, "ip_fragments", s.ip_fragments);
  add(out, "gps_packets", s.gps_packets);
  out += "\"first_time_ns\":" + std::to_string(s.first_time_ns) + ",";
  out += "\"last_time_ns\":" + std::to_string(s.last_time_ns) + ",";
  add(out, "high_temperature", s.high_temperature);
  add(out, "gps_unlocked", s.gps_unlocked);
  add(out, "gps_position_invalid", s.gps_position_invalid);
  const SafetyCounts& fs = s.safety;
  add(out, "fs_packets", fs.packets);
  out += "\"fs_states\":{";
  for (std::size_t st = 0; st < kLidarStateCount; ++st)
    add(out, lidar_state_name(static_cast<std::uint8_t>(st)), fs.states[st], st + 1 < kLidarStateCount);
  out += "},";
  add(out, "fs_current_fault", fs.current_fault);
  add(out, "fs_past_fault", fs.past_fault);
  add(out, "fs_reserved_fault_type", fs.reserved_fault_type);
  add(out, "fs_last_fault_code", fs.last_fault_code);
  add(out, "fs_last_fault_id", fs.last_fault_id);
  add(out, "fs_last_fault_total", fs.last_fault_total);
  add(out, "fs_counter_stalls", fs.counter_stalls, false);
  if (sensors.size() > 1) {
    out += ",\"sensors\":[";
    for (std::size_t i = 0; i < sensors.size(); ++i) out += (i ? "," : "") + sensor_json(sensors[i]);
    out += "]";
  }
  return out + "}";
}

std::string utc_string(std::int64_t ns) {
  const std::time_t secs = static_cast<std::time_t>(ns / 1000000000);
  std::tm t{};
  gmtime_r(&secs, &t);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d.%09lldZ", t.tm_year + 1900, t.tm_mon + 1, t.tm_mday,
                t.tm_hour, t.tm_min, t.tm_sec, static_cast<long long>(ns % 1000000000));
  return buf;
}

std::string stats_text(const Pipeline& p) {
  const Stats& s = p.stats();
  std::string out;
  // The value at column 24, or one space after a longer key.
  auto line = [&](const std::string& k, const std::string& v) {
    out += "  " + k + std::string(k.size() < 22 ? 22 - k.size() : 1, ' ') + v + "\n";
  };
  line("packets", std::to_string(s.packets));
  for (std::size_t m = 1; m < kModelCount; ++m)
    if (s.models[m]) line(std::string("  ") + model_name(static_cast<Model>(m)), std::to_string(s.models[m]));
  line("gps_packets", std::to_string(s.gps_packets));
  line("points", std::to_string(s.points));
  line("frames", std::to_string(s.frames));
  if (s.first_time_ns) {
    line("first_time", utc_string(s.first_time_ns));
    line("last_time", utc_string(s.last_time_ns));
  }
  line("spin_rate", std::to_string(s.spin_rpm_last) + " rpm");
  if (!p.rotation_text().empty()) line("rotation", p.rotation_text());
  line("return_mode", std::string(return_mode_name(s.return_mode_last)));
  line("crc_errors", std::to_string(s.crc_errors));
  line("signature_valid", std::to_string(s.signature_valid));
  line("signature_invalid", std::to_string(s.signature_invalid));
  line("signature_missing", std::to_string(s.signature_missing));
  line("unsigned_accepted", std::to_string(s.unsigned_accepted));
  line("unsigned_rejected", std::to_string(s.unsigned_rejected));
  line("signature_unverified", std::to_string(s.signature_unverified));
  line("replayed", std::to_string(s.replayed));
  line("malformed", std::to_string(s.malformed));
  line("unsupported", std::to_string(s.unsupported));
  line("lost", std::to_string(s.lost));
  if (s.lost_by == LostBy::azimuth_time)
    line("lost_by", "azimuth_time (the packets carry no UDP sequence: counted from the block azimuth and the packet time)");
  else if (s.lost_by == LostBy::mixed)
    line("lost_by", "mixed (udp_sequence for the sensors that send one, azimuth_time for the others)");
  else if (s.lost_by == LostBy::udp_sequence)
    line("lost_by", "udp_sequence");
  line("duplicates", std::to_string(s.duplicates));
  line("reordered", std::to_string(s.reordered));
  if (s.sequence_resyncs) line("sequence_resyncs", std::to_string(s.sequence_resyncs));
  line("time_stalls", std::to_string(s.time_stalls));
  line("time_virtual", std::to_string(s.time_virtual));
  if (s.time_jumps) line("time_jumps", std::to_string(s.time_jumps));
  line("blockage_units", std::to_string(s.blockage_units));
  if (s.blockage_units) {
    std::string by;
    for (std::size_t ch = 0; ch < kMaxChannels; ++ch)
      if (s.blockage_by_channel[ch]) by += (by.empty() ? "" : ", ") + ("channel " + std::to_string(ch + 1)) + ": " + std::to_string(s.blockage_by_channel[ch]);
    line("blockage_by_channel", by);
  }
  line("duplicate_returns", std::to_string(s.duplicate_returns));
  line("beyond_rated_range", std::to_string(s.beyond_rated_range));
  if (s.fov_gap)
    line("fov_gap_deg", degrees(s.fov_gap_from) + " to " + degrees(s.fov_gap_to) +
                            " (no packets there on every rotation: an azimuth FOV, not counted as lost)");
  line("ip_fragments", std::to_string(s.ip_fragments));
  if (s.ip_fragments)
    out += "  warning: " + std::to_string(s.ip_fragments) +
           " IP fragments were skipped (not reassembled): the datagrams they carried are missing from every count\n";
  if (s.time_virtual)
    out += "  warning: " + std::to_string(s.time_virtual) +
           " packets are dated in the year 2000: their times are the unit's free-running clock, not PTP or GPS time\n";
  line("high_temperature", std::to_string(s.high_temperature));
  line("gps_unlocked", std::to_string(s.gps_unlocked));
  if (s.gps_position_invalid) line("gps_position_invalid", std::to_string(s.gps_position_invalid));
  const SafetyCounts& fs = s.safety;
  if (fs.packets) {
    line("fs_packets", std::to_string(fs.packets));
    for (std::size_t st = 0; st < kLidarStateCount; ++st)
      if (fs.states[st]) line(std::string("  ") + lidar_state_name(static_cast<std::uint8_t>(st)), std::to_string(fs.states[st]));
    line("fs_current_fault", std::to_string(fs.current_fault));
    line("fs_past_fault", std::to_string(fs.past_fault));
    if (fs.reserved_fault_type) line("fs_reserved_fault_type", std::to_string(fs.reserved_fault_type));
    if (fs.last_fault_id)
      line("fs_last_fault", "code " + std::to_string(fs.last_fault_code) + ", " + std::to_string(fs.last_fault_id) +
                                " of " + std::to_string(fs.last_fault_total));
    line("fs_counter_stalls", std::to_string(fs.counter_stalls));
  }
  for (const auto& [e, n] : p.rejections()) line(std::string("  rejected ") + error_name(e), std::to_string(n));
  return out;
}

}  // namespace hesai::port
