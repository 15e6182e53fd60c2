// Pandar40 (1256-byte packets) and Pandar40P (1262, or 1266 with UDP sequence): identification,
// validation (and the Pandar40's hour-relative time) and the walk over their ten blocks.
// Layout: hesai/detail/pandar40_packet.h; tables: hesai/detail/tables/pandar40_tables.h.
#include "hesai/decoder.h"
#include "hesai/detail/pandar40_packet.h"
#include "hesai/detail/tables/block_times.h"
#include "hesai/detail/tables/pandar40_tables.h"
#include "block_points.h"
#include "field_checks.h"
#include "sensor.h"
#include "sensor_rules.h"

namespace hesai {

namespace {
struct Pandar40Family;  // this file's SensorCode
constexpr std::int64_t kUsPerHour = 3600LL * 1000000;
constexpr auto kBlockNs = detail::block_ns(tables::pandar40_block_end_us_single, tables::pandar40_block_end_us_dual);
}  // namespace

using Pandar40Code = SensorCode<Pandar40Family>;

template <>
void Pandar40Code::design(Decoder& d) noexcept {
  set_design_tables(d, tables::pandar40_channel_angles, tables::pandar40_firetime_us, tables::pandar40_firetime_us);
}

// Pandar40P in its longer length only.
template <>
std::size_t Pandar40Code::sequence_at(ByteView p) noexcept {
  return p.size == pandar40::kPandar40PSequenceBytes ? pandar40::kSequence : 0;
}

template <>
Error Pandar40Code::identify(ByteView p, Model& model) noexcept {
  switch (p.size) {
    case pandar40::kPandar40Bytes: model = Model::pandar40; return Error::ok;
    case pandar40::kPandar40PBytes:
    case pandar40::kPandar40PSequenceBytes: model = Model::pandar40p; return Error::ok;
    default: return Error::bad_length;
  }
}

template <>
Error Pandar40Code::validate(Decoder& d, ByteView p, PacketInfo& info) noexcept {
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

  if (const Error e = detail::pandar_return_mode(info); e != Error::ok) return e;
  if (const Error e = detail::motor_speed(info); e != Error::ok) return e;
  if (const Error e = detail::block_azimuths(p.data + kBlockAzimuth, kBlockBytes, info); e != Error::ok) return e;

  // Pandar40P: date-time (the year byte by the SDK's rule, see pandar_year); timestamp in us
  // within the second.
  if (is_40p) {
    const std::uint8_t* dt = p.data + kDateTime;
    return detail::tail_time(detail::tail_date_time(detail::pandar_year(dt[0]), dt), 999999, info);
  }

  // Pandar40: the timestamp counts us from the top of the hour (the GPS packet sets it to
  // (minute x 60 + second) x 1e6 at each PPS); the date and hour come from the last GPS packet.
  const std::int64_t ts = info.timestamp_us;
  if (!d.has_gps_) {
    info.time_reference = TimeReference::hour_relative;
    info.time_ns = ts * 1000;
    return Error::ok;
  }
  const DateTime& gps_time = d.gps_time_;
  DateTime hour = gps_time;
  hour.minute = 0;
  hour.second = 0;
  std::int64_t hour_start_us = unix_seconds(hour) * 1000000;
  // A timestamp far below the GPS packet's own position in the hour belongs to the next hour:
  // the counter wrapped at the top of the hour before the next GPS packet arrived.
  const std::int64_t gps_us_in_hour = (gps_time.minute * 60 + gps_time.second) * 1000000LL;
  if (gps_us_in_hour - ts > kUsPerHour / 2) hour_start_us += kUsPerHour;
  info.date_time = gps_time;
  info.time_ns = (hour_start_us + ts) * 1000;
  return Error::ok;
}

template <>
void Pandar40Code::walk(const Decoder& d, const std::uint8_t* p, const PacketInfo& info, DecodeOutput& out) noexcept {
  using namespace pandar40;
  const std::size_t dual = info.returns == 2 ? 1 : 0;
  kernels::BlockRef blocks[kBlocks];
  for (std::size_t b = 0; b < kBlocks; ++b) blocks[b] = {p + b * kBlockBytes + kBlockPoints, nullptr, kBlockNs[dual][b], 0};
  emit_blocks<kPointBytes>(d, blocks, kBlocks, kChannels, info, out);
}

// No header: the first block's preamble, FF EE (GPS packets, 512 bytes, start so too; identify()
// tells them apart first).
extern const SensorDescriptor kPandar40Sensor;  // registry.cpp
const SensorDescriptor kPandar40Sensor =
    Pandar40Code::descriptor({pandar40::kPreamble0, pandar40::kPreamble1, 0, 0}, 2, nullptr,
                             /*firing_loops=*/1, /*min_distance=*/1);

}  // namespace hesai
