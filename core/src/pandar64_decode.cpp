// Validation of Pandar64 packets (1194 bytes, 1198 with UDP sequence).
#include "hesai/decoder.h"
#include "hesai/pandar64_packet.h"

namespace hesai {

Error Decoder::validate_pandar64(ByteView p, PacketInfo& info) noexcept {
  using namespace pandar64;
  info.blocks = kBlocks;
  info.dis_unit_mm = p[kDisUnit];
  if (info.dis_unit_mm == 0) return Error::bad_header;

  info.high_temperature = p[kHighTemperature];
  info.motor_rpm = load_le16(p.data + kMotorSpeed);
  info.timestamp_us = load_le32(p.data + kTimestamp);
  info.return_mode = p[kReturnMode];
  info.factory_info = p[kFactoryInfo];
  if (p.size == kSequencePacketBytes) {
    info.has_sequence = true;
    info.sequence = load_le32(p.data + kSequence);
  }

  const auto mode = static_cast<ReturnMode>(info.return_mode);
  if (mode != ReturnMode::strongest && mode != ReturnMode::last && mode != ReturnMode::last_strongest)
    return Error::bad_return_mode;
  info.returns = mode == ReturnMode::last_strongest ? 2 : 1;

  for (std::size_t b = 0; b < kBlocks; ++b) {
    info.block_azimuth[b] = load_le16(p.data + kBody + b * kBlockBytes);
    if (info.block_azimuth[b] >= 36000) return Error::bad_azimuth;
  }
  if (info.returns == 2)
    for (std::size_t b = 0; b < kBlocks; b += 2)
      if (info.block_azimuth[b] != info.block_azimuth[b + 1]) return Error::dual_block_mismatch;

  // Date & Time: year - 2000 (section 3.1.2.3); Timestamp: us within the second, 0..999999.
  const std::uint8_t* dt = p.data + kDateTime;
  info.date_time = DateTime{2000 + dt[0], dt[1], dt[2], dt[3], dt[4], dt[5]};
  if (!is_valid(info.date_time)) return Error::bad_date_time;
  if (info.timestamp_us > 999999) return Error::bad_timestamp;
  info.time_ns = unix_seconds(info.date_time) * 1000000000LL + static_cast<std::int64_t>(info.timestamp_us) * 1000;
  return Error::ok;
}

}  // namespace hesai
