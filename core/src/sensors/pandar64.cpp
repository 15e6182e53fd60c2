// Pandar64 (1194-byte packets, 1198 with UDP sequence): identification, validation and the
// walk over its six blocks. Layout: hesai/detail/pandar64_packet.h; tables: hesai/detail/tables/pandar64_tables.h.
#include "hesai/decoder.h"
#include "hesai/detail/pandar64_packet.h"
#include "hesai/detail/tables/block_times.h"
#include "hesai/detail/tables/pandar64_tables.h"
#include "block_points.h"
#include "field_checks.h"
#include "sensor.h"
#include "sensor_rules.h"

namespace hesai {

namespace {
struct Pandar64Tag;  // this file's SensorCode
constexpr auto kBlockNs = detail::block_ns(tables::pandar64_block_end_us_single, tables::pandar64_block_end_us_dual);
// Pandar64 App. B.3: block 1 of 6 ends at t0 - 42.58 - 55.56 x 5 us, or x 2 in dual return.
static_assert(kBlockNs[0][0] == -320380 && kBlockNs[1][0] == -153700);

// Appendix D as Point::intensity holds it under Reflectivity::nonlinear: the actual reflectivity
// in percent, rounded to the nearest integer (halves up), as the default linear mapping's byte is
// one percent a step. 255, for which the manual gives no value, stays 255 (no mapped value
// reaches it: the largest, for 254, is 242).
constexpr std::array<std::uint8_t, 256> nonlinear_percent() {
  std::array<std::uint8_t, 256> t{};
  for (std::size_t i = 0; i < 255; ++i)
    t[i] = static_cast<std::uint8_t>(tables::pandar64_nonlinear_reflectivity_pct[i] + 0.5);
  t[255] = 255;
  return t;
}
constexpr std::array<std::uint8_t, 256> kNonlinearPercent = nonlinear_percent();
}  // namespace

using Pandar64Code = SensorCode<Pandar64Tag>;

template <>
void Pandar64Code::design(Decoder& d) noexcept {
  set_design_tables(d, tables::pandar64_channel_angles, tables::pandar64_firetime_us, tables::pandar64_firetime_us);
}

template <>
std::size_t Pandar64Code::sequence_at(ByteView p) noexcept {
  return p.size == pandar64::kSequencePacketBytes ? pandar64::kSequence : 0;
}

template <>
Error Pandar64Code::identify(ByteView p, Model& model) noexcept {
  if (p.size != pandar64::kPacketBytes && p.size != pandar64::kSequencePacketBytes) return Error::bad_length;
  model = Model::pandar64;
  return Error::ok;
}

template <>
Error Pandar64Code::validate(Decoder&, ByteView p, PacketInfo& info) noexcept {
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
  // Date & Time (section 3.1.2.3; the year byte by the SDK's rule, see pandar_year); Timestamp:
  // us within the second, 0..999999.
  const std::uint8_t* dt = p.data + kDateTime;
  return detail::tail_time(detail::tail_date_time(detail::pandar_year(dt[0]), dt), 999999, info);
}

template <>
void Pandar64Code::walk(const Decoder& d, const std::uint8_t* p, const PacketInfo& info, DecodeOutput& out) noexcept {
  using namespace pandar64;
  const std::size_t dual = info.returns == 2 ? 1 : 0;
  const std::size_t first = out.count;
  kernels::BlockRef blocks[kBlocks];
  for (std::size_t b = 0; b < kBlocks; ++b)
    blocks[b] = {p + kBody + b * kBlockBytes + kBlockPoints, nullptr, kBlockNs[dual][b], 0};
  emit_blocks<kPointBytes>(d, blocks, kBlocks, kChannels, info, out);
  if (d.reflectivity_ == Reflectivity::nonlinear) out.map_intensity(first, kNonlinearPercent.data());
}

Error Decoder::set_reflectivity(Reflectivity mapping) noexcept {
  // Only the Pandar64 manual gives a nonlinear mapping (Appendix D).
  if (mapping != Reflectivity::raw && model_ != Model::pandar64) return Error::invalid_argument;
  reflectivity_ = mapping;
  return Error::ok;
}

// EE FF, then 64 lasers and 6 blocks where the other EE FF headers name their protocol version.
static_assert(pandar64::kLaserNum == 2 && pandar64::kBlockNum == 3);
extern const SensorDescriptor kPandar64Sensor;  // registry.cpp
const SensorDescriptor kPandar64Sensor =
    Pandar64Code::descriptor({pandar64::kMagic0, pandar64::kMagic1, 0x40, 0x06}, 4, nullptr,
                             /*firing_loops=*/1, /*min_distance=*/1);

}  // namespace hesai
