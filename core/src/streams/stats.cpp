#include "hesai/stats.h"

#include <cstddef>

#include "hesai/saturating.h"

namespace hesai {

void count_error(Stats& stats, Error error) noexcept {
  switch (error) {
    case Error::ok:
      return;
    case Error::crc_body:
    case Error::crc_functional_safety:
    case Error::crc_tail:
      saturating_increment(stats.crc_errors);
      return;
    case Error::signature_invalid:
      saturating_increment(stats.signature_invalid);
      return;
    case Error::signature_missing:
      saturating_increment(stats.signature_missing);
      saturating_increment(stats.unsigned_rejected);
      return;
    case Error::unsupported_version:
    case Error::unsupported_model:
    case Error::unsupported_section:
    case Error::channel_config_required:  // the packet may be sound: this decoder cannot map its units
    case Error::channel_config_mismatch:
      saturating_increment(stats.unsupported);
      return;
    default:  // every other code, including codes added later
      saturating_increment(stats.malformed);
      return;
  }
}

const char* lost_by_name(LostBy by) noexcept {
  switch (by) {
    case LostBy::none: return "none";
    case LostBy::udp_sequence: return "udp_sequence";
    case LostBy::azimuth_time: return "azimuth_time";
    case LostBy::mixed: return "mixed";
  }
  return "none";
}

void count_status(Stats& stats, const PacketInfo& info) noexcept {
  if (info.high_temperature != 0) saturating_increment(stats.high_temperature);
}

bool gps_unlocked(const GpsPacket& gps) noexcept { return !gps.pps_locked || gps.location_status == 0; }

bool gps_position_invalid(const GpsPacket& gps) noexcept {
  return gps.location_status == 'V' || gps.location_status == '0';
}

void count_gps(Stats& stats, const GpsPacket& gps) noexcept {
  saturating_increment(stats.gps_packets);
  if (gps_unlocked(gps)) saturating_increment(stats.gps_unlocked);
  if (gps_position_invalid(gps)) saturating_increment(stats.gps_position_invalid);
}

void count_model(Stats& stats, Model model) noexcept {
  std::size_t i = static_cast<std::size_t>(model);
  if (i >= stats.models.size()) i = static_cast<std::size_t>(Model::unknown);
  saturating_increment(stats.models[i]);
}

}  // namespace hesai
