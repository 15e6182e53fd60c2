// Validation of Pandar40 (1256 bytes) and Pandar40P (1262/1266 bytes) packets.
#include "hesai/decoder.h"
#include "hesai/pandar40_packet.h"

namespace hesai {

namespace {
constexpr std::int64_t kUsPerHour = 3600LL * 1000000;
}

Error Decoder::validate_pandar40(ByteView p, PacketInfo& info) noexcept {
  using namespace pandar40;
  const bool is_40p = info.model == Model::pandar40p;
  info.blocks = kBlocks;
  info.dis_unit_mm = 4;  // the manuals fix 4 mm; these packets have no header

  for (std::size_t b = 0; b < kBlocks; ++b) {
    const std::uint8_t* block = p.data + b * kBlockBytes;
    if (block[0] != kPreamble0 || block[1] != kPreamble1) return Error::bad_magic;
  }
  info.high_temperature = p[kHighTemperature];
  info.motor_rpm = load_le16(p.data + kMotorSpeed);
  info.timestamp_us = load_le32(p.data + kTimestamp);
  info.return_mode = p[kReturnMode];
  info.factory_info = p[kFactoryInfo];
  if (is_40p && p.size == kPandar40PSequenceBytes) {
    info.has_sequence = true;
    info.sequence = load_le32(p.data + kSequence);
  }

  const auto mode = static_cast<ReturnMode>(info.return_mode);
  if (mode != ReturnMode::strongest && mode != ReturnMode::last && mode != ReturnMode::last_strongest)
    return Error::bad_return_mode;
  info.returns = mode == ReturnMode::last_strongest ? 2 : 1;

  for (std::size_t b = 0; b < kBlocks; ++b) {
    info.block_azimuth[b] = load_le16(p.data + b * kBlockBytes + kBlockAzimuth);
    if (info.block_azimuth[b] >= 36000) return Error::bad_azimuth;
  }
  if (info.returns == 2)
    for (std::size_t b = 0; b < kBlocks; b += 2)
      if (info.block_azimuth[b] != info.block_azimuth[b + 1]) return Error::dual_block_mismatch;

  if (is_40p) {
    // Date-time: year - 2000, month, day, hour, minute, second; timestamp: us within the second.
    const std::uint8_t* dt = p.data + kDateTime;
    info.date_time = DateTime{2000 + dt[0], dt[1], dt[2], dt[3], dt[4], dt[5]};
    if (!is_valid(info.date_time)) return Error::bad_date_time;
    if (info.timestamp_us > 999999) return Error::bad_timestamp;
    info.time_ns = unix_seconds(info.date_time) * 1000000000LL + static_cast<std::int64_t>(info.timestamp_us) * 1000;
    return Error::ok;
  }

  // Pandar40: the timestamp counts us from the top of the hour (the GPS packet sets it to
  // (minute x 60 + second) x 1e6 at each PPS); the date and hour come from the last GPS packet.
  const std::int64_t ts = info.timestamp_us;
  if (!has_gps_) {
    info.time_reference = TimeReference::hour_relative;
    info.time_ns = ts * 1000;
    return Error::ok;
  }
  DateTime hour = gps_time_;
  hour.minute = 0;
  hour.second = 0;
  std::int64_t hour_start_us = unix_seconds(hour) * 1000000;
  // A timestamp far below the GPS packet's own position in the hour belongs to the next hour:
  // the counter wrapped at the top of the hour before the next GPS packet arrived.
  const std::int64_t gps_us_in_hour = (gps_time_.minute * 60 + gps_time_.second) * 1000000LL;
  if (gps_us_in_hour - ts > kUsPerHour / 2) hour_start_us += kUsPerHour;
  info.date_time = gps_time_;
  info.time_ns = (hour_start_us + ts) * 1000;
  return Error::ok;
}

}  // namespace hesai
