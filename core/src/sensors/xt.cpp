// PandarXT16, PandarXT32 and PandarXT32M2X, point cloud protocol 6.1: identification (laser and
// block numbers, the length they imply), validation and the walk over their blocks.
// Layout: hesai/detail/xt_packet.h; tables: hesai/detail/tables/xt_tables.h. Sources: the vendor SDK
// (HesaiLidar_SDK_2.0, ea7f86f: udp_protocol_v6_1.h, UdpParser/src/udp6_1_parser.cc) and
// tier4/nebula (606ac41f: pandar_xt16.hpp, pandar_xt32.hpp, pandar_xt32m.hpp, hesai_common.hpp),
// confirmed on the bundled captures. Not implemented: the SDK's optional optical-centre distance
// correction (distance_correction_flag, off by default in the SDK) and its XTM1 spot correction.
#include "hesai/decoder.h"
#include "hesai/detail/tables/xt_tables.h"
#include "hesai/detail/xt_packet.h"
#include "block_points.h"
#include "field_checks.h"
#include "sensor.h"
#include "sensor_rules.h"

namespace hesai {

namespace {

struct XtFamily;  // this file's SensorCode

constexpr std::int32_t kFiringPeriodNs = detail::round_to_int(tables::xt_firing_period_us * 1000.0);
static_assert(kFiringPeriodNs == 50000);

/// The return modes of the XT family and the returns per firing each puts in a packet (0: not an
/// XT mode). nebula hesai_common.hpp (return_mode_from_int_hesai, the XT models): last 0x38,
/// strongest 0x37, last + strongest 0x39, first 0x33, first + last 0x3B, first + strongest 0x3C;
/// the SDK's udp6_1_parser.cc also decodes triple return, 0x3D (RETURN_MODE_MULTI_TRIPLE,
/// first + last + strongest, three blocks per firing), offered by the XT32M2X.
std::uint8_t xt_returns(std::uint8_t byte) {
  switch (static_cast<ReturnMode>(byte)) {
    case ReturnMode::first:
    case ReturnMode::strongest:
    case ReturnMode::last: return 1;
    case ReturnMode::last_strongest:
    case ReturnMode::first_last:
    case ReturnMode::first_strongest: return 2;
    case ReturnMode::first_last_strongest: return 3;
    case ReturnMode::second:
    case ReturnMode::first_second:
    case ReturnMode::strongest_second_strongest: break;  // QT128 modes
  }
  return 0;
}

}  // namespace

using XtCode = SensorCode<XtFamily>;

// Every design azimuth offset of the XT family is 0 (xt_tables.h).
template <>
void XtCode::design(Decoder& d) noexcept {
  switch (d.model()) {
    case Model::pandar_xt16: set_design_tables(d, tables::xt16_elevation_deg, nullptr, tables::xt16_firetime_us); break;
    case Model::pandar_xt32: set_design_tables(d, tables::xt32_elevation_deg, nullptr, tables::xt32_firetime_us); break;
    default: set_design_tables(d, tables::xt32m2x_elevation_deg, nullptr, tables::xt32m2x_firetime_us); break;
  }
}

// With flags bit 0, at the end of the tail (protocol 6.1 has no CRC).
template <>
std::size_t XtCode::sequence_at(ByteView p) noexcept {
  using namespace xt;
  return (p[kFlags] & kFlagSequence) ? tail_offset(p[kLaserNum], p[kBlockNum]) + kTailSequence : 0;
}

template <>
Error XtCode::identify(ByteView p, Model& model) noexcept {
  using namespace xt;
  if (p.size < kHeaderEnd) return Error::bad_length;
  // The three models of protocol 6.1 by laser and block numbers (udp_protocol_v6_1.h gives them
  // as header fields; nebula's packet types fix them per model: PacketXT16 8 x 16,
  // PacketXT32 8 x 32, PacketXT32M2X 6 x 32).
  const std::uint8_t lasers = p[kLaserNum];
  const std::uint8_t blocks = p[kBlockNum];
  Model m = Model::unknown;
  if (lasers == 16 && blocks == 8) m = Model::pandar_xt16;
  else if (lasers == 32 && blocks == 8) m = Model::pandar_xt32;
  else if (lasers == 32 && blocks == 6) m = Model::pandar_xt32m2x;
  else return Error::unsupported_model;
  // One length per model: the tail always holds the UDP sequence (SDK GetPacketSize, nebula's
  // packet types), 568, 1080 and 820 bytes as the captures send them.
  if (p.size != packet_bytes(lasers, blocks)) return Error::bad_length;
  model = m;
  return Error::ok;
}

template <>
Error XtCode::validate(Decoder&, ByteView p, PacketInfo& info) noexcept {
  using namespace xt;
  // identify() has checked magic, version, laser and block numbers and the length.
  const std::size_t lasers = p[kLaserNum];
  info.blocks = p[kBlockNum];
  info.flags = p[kFlags];
  info.dis_unit_mm = p[kDisUnit];  // 4 mm on the XT16 and XT32 captures, 5 mm on the XT32M2X's
  if (info.dis_unit_mm == 0) return Error::bad_header;

  const std::uint8_t* tail = p.data + tail_offset(lasers, info.blocks);
  info.high_temperature = static_cast<std::uint8_t>(tail[kTailShutdown] & 1);  // SDK HasShutdown(): bit 0, as 3.1
  detail::read_tail(tail, {kTailReturnMode, kTailMotorSpeed, kTailTimestamp, kTailFactoryInfo, kTailSequence},
                    (info.flags & kFlagSequence) != 0, info);
  // The returns per firing follow the tail's return mode, not the header's echo num (the XT32M2X
  // capture: header 3, tail 0x3C dual, block azimuths in pairs, timestamps 150 us = 3 firings
  // apart). A packet holds whole firings: triple return only with 6 blocks.
  info.returns = xt_returns(info.return_mode);
  if (info.returns == 0 || info.blocks % info.returns != 0) return Error::bad_return_mode;
  if (const Error e = detail::motor_speed(info); e != Error::ok) return e;
  if (const Error e = detail::block_azimuths(p.data + kBody, block_bytes(lasers), info); e != Error::ok) return e;
  // Date & Time: the SDK's GetMicroLidarTimeU64 reads the year byte as tm_year with 100 added
  // below 70 (the Pandar rule, detail::pandar_year; the captures send 119 = 2019), or, with a
  // year byte of 0, Unix seconds big-endian in bytes 2..5. Timestamp: us within the second.
  const std::uint8_t* dt = tail + kTailDateTime;
  const DateTime t = detail::calendar_or_unix(dt, detail::pandar_year(dt[0]));
  return detail::tail_time(t, 999999, info);
}

template <>
void XtCode::walk(const Decoder& d, const std::uint8_t* p, const PacketInfo& info, DecodeOutput& out) noexcept {
  using namespace xt;
  const std::size_t lasers = p[kLaserNum];
  const std::size_t blocks = info.blocks;
  const std::size_t stride = block_bytes(lasers);
  // Block b starts (B - 1 - b) / returns firings before t0 (xt_tables.h, SDK udp6_1_parser.cc).
  // nebula's pandar_xt32m.hpp counts from 8 blocks for the XT32M2X in single and dual return
  // too, which would put its first firing on the previous packet's last one (150 us before t0
  // in dual); the SDK's header block count matches the capture's 150 us packet spacing.
  // Counted down without a division per block: a firing every `returns` blocks.
  kernels::BlockRef refs[8];  // 8 (XT16, XT32) or 6 (XT32M2X), as identify_xt accepts
  auto firings_after = static_cast<std::int32_t>((blocks - 1) / info.returns);
  std::size_t left_in_firing = (blocks - 1) % info.returns + 1;
  for (std::size_t b = 0; b < blocks; ++b) {
    refs[b] = {p + kBody + b * stride + kBlockPoints, nullptr, -kFiringPeriodNs * firings_after, 0};
    if (--left_in_firing == 0) --firings_after, left_in_firing = info.returns;
  }
  emit_blocks<kUnitBytes>(d, refs, blocks, lasers, info, out);
}

// EE FF, point cloud protocol 6.1 (bytes 2 and 3).
extern const SensorDescriptor kXtSensor;  // registry.cpp
const SensorDescriptor kXtSensor =
    XtCode::descriptor({0xEE, 0xFF, 0x06, 0x01}, 4, nullptr, /*firing_loops=*/1, /*min_distance=*/1);

}  // namespace hesai
