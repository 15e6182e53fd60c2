// Validation of Pandar64 packets (1194 bytes, 1198 with UDP sequence).
#include "hesai/decoder.h"
#include "hesai/pandar64_packet.h"
#include "field_checks.h"

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

  if (const Error e = detail::pandar_return_mode(info); e != Error::ok) return e;
  if (const Error e = detail::motor_speed(info); e != Error::ok) return e;
  if (const Error e = detail::block_azimuths(p.data + kBody, kBlockBytes, info); e != Error::ok) return e;
  // Date & Time: year - 2000 (section 3.1.2.3); Timestamp: us within the second, 0..999999.
  return detail::tail_time(p.data + kDateTime, 2000, 999999, info);
}

}  // namespace hesai
