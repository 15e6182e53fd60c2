// PandarQT64, point cloud protocol 3.1: identification (version, laser and block numbers, and the
// length the flags imply), validation of every field with a published rule, and the walk over its
// four blocks. Layout: hesai/detail/qt64_packet.h; tables: hesai/detail/tables/qt64_tables.h. Sources: the
// vendor SDK (HesaiLidar_SDK_2.0 ea7f86f: udp_protocol_v3_1.h, udp3_1_parser.cc), tier4/nebula
// (606ac41f: pandar_qt64.hpp, hesai_packet.hpp), and the bundled capture data/pandar_qt64.pcap.
#include "hesai/decoder.h"
#include "hesai/detail/qt64_packet.h"
#include "hesai/detail/tables/qt64_tables.h"
#include "block_points.h"
#include "field_checks.h"
#include "sensor.h"
#include "sensor_rules.h"

namespace hesai {

namespace {
struct Qt64Tag;  // this file's SensorCode
constexpr auto kBlockNs = detail::block_ns(tables::qt64_block_start_us_single, tables::qt64_block_start_us_dual);
// SDK: 25 710 + {0, 166 670, 333 330, 500 000} ns by firing; dual return, two blocks a firing.
static_assert(kBlockNs[0][1] == 192380 && kBlockNs[0][3] == 525710 && kBlockNs[1][1] == 25710 &&
              kBlockNs[1][3] == 192380);
}  // namespace

using Qt64Code = SensorCode<Qt64Tag>;

template <>
void Qt64Code::design(Decoder& d) noexcept {
  set_design_tables(d, tables::qt64_elevation_deg, tables::qt64_azimuth_deg.data(), tables::qt64_firetime_us);
}

// With flags bit 0, at the end of the tail (no CRC covers it).
template <>
std::size_t Qt64Code::sequence_at(ByteView p) noexcept {
  return (p[qt64::kFlags] & qt64::kFlagSequence) ? qt64::kTail + qt64::kTailSequence : 0;
}

template <>
Error Qt64Code::identify(ByteView p, Model& model) noexcept {
  using namespace qt64;
  // identify() has checked EE FF and version 3.1 (bytes 2, 3): the descriptor's header.
  if (p.size < kHeaderEnd) return Error::bad_length;
  if (p[kLaserNum] != kChannels || p[kBlockNum] != kBlocks) return Error::unsupported_model;
  // SDK GetPacketSize: header + 4 blocks + tail, the u32 UDP sequence only with flags bit 0.
  if (p.size != ((p[kFlags] & kFlagSequence) ? kSequencePacketBytes : kPacketBytes)) return Error::flags_length_mismatch;
  model = Model::pandar_qt64;
  return Error::ok;
}

template <>
Error Qt64Code::validate(Decoder&, ByteView p, PacketInfo& info) noexcept {
  using namespace qt64;
  info.blocks = kBlocks;
  info.flags = p[kFlags];
  // The SDK names flags bit 1 "IMU" but gives no layout for it (GetPacketSize adds no bytes).
  if (info.flags & kFlagImu) return Error::unsupported_section;
  // Distance unit, mm (SDK GetDistUnit: byte / 1000 m; nebula get_dis_unit). The header's return
  // num (SDK "echo num") is not checked: the tail's return mode gives the returns per firing, as
  // the XT32M2X capture (6.1, same header) shows with return num 3 and a dual tail.
  info.dis_unit_mm = p[kDisUnit];
  if (info.dis_unit_mm == 0) return Error::bad_header;

  const std::uint8_t* tail = p.data + kTail;
  info.high_temperature = static_cast<std::uint8_t>(tail[kTailShutdown] & 1);  // SDK HasShutdown(): bit 0
  detail::read_tail(tail, {kTailReturnMode, kTailMotorSpeed, kTailTimestamp, kTailFactoryInfo, kTailSequence},
                    (info.flags & kFlagSequence) != 0, info);

  // Return mode: the modes nebula decodes for the QT64 (get_n_returns; its triple mode 0x3D
  // cannot fill 4 blocks). The SDK's tail names only 0x37, 0x38, 0x39, but the capture sends 0x3B
  // (first + last: block 1 of each pair is never farther than block 2 on any of its points).
  if (!detail::returns_of_mode(info.return_mode, info.returns)) return Error::bad_return_mode;
  if (const Error e = detail::motor_speed(info); e != Error::ok) return e;
  // Block azimuths, 0.01 degree, below 36000; the two blocks of a dual firing at one azimuth
  // (the capture: 120, 120, 180, 180 in its first packet).
  if (const Error e = detail::block_azimuths(p.data + kBody, kBlockBytes, info); e != Error::ok) return e;
  // Date & Time by the SDK's GetMicroLidarTimeU64 (year byte + 1900, + 100 below 70 as in
  // pandar_year; 0: Unix seconds); Timestamp: us within the second, which the SDK adds to the
  // whole seconds: 0..999999.
  const std::uint8_t* dt = tail + kTailDateTime;
  return detail::tail_time(detail::calendar_or_unix(dt, detail::pandar_year(dt[0])), 999999, info);
}

template <>
void Qt64Code::walk(const Decoder& d, const std::uint8_t* p, const PacketInfo& info, DecodeOutput& out) noexcept {
  using namespace qt64;
  // One firing sequence (the vendor's firetime file has one column); in dual return the two
  // blocks of a firing share its start time (tables/qt64_tables.h).
  const std::size_t dual = info.returns == 2 ? 1 : 0;
  kernels::BlockRef blocks[kBlocks];
  for (std::size_t b = 0; b < kBlocks; ++b)
    blocks[b] = {p + kBody + b * kBlockBytes + kBlockPoints, nullptr, kBlockNs[dual][b], 0};
  emit_blocks<kUnitBytes>(d, blocks, kBlocks, kChannels, info, out);
}

// EE FF, point cloud protocol 3.1 (bytes 2 and 3).
extern const SensorDescriptor kQt64Sensor;  // registry.cpp
const SensorDescriptor kQt64Sensor =
    Qt64Code::descriptor({0xEE, 0xFF, 0x03, 0x01}, 4, nullptr, /*firing_loops=*/1, /*min_distance=*/1);

}  // namespace hesai
