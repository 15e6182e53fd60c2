// Field checks shared by the models' validators (internal to the core).
#pragma once

#include <cstddef>
#include <cstdint>

#include "hesai/decoder.h"

namespace hesai::detail {

/// Pandar40/40P/64 return modes: 0x37 strongest, 0x38 last, 0x39 last + strongest (dual).
[[nodiscard]] inline Error pandar_return_mode(PacketInfo& info) {
  const auto mode = static_cast<ReturnMode>(info.return_mode);
  if (mode != ReturnMode::strongest && mode != ReturnMode::last && mode != ReturnMode::last_strongest)
    return Error::bad_return_mode;
  info.returns = mode == ReturnMode::last_strongest ? 2 : 1;
  return Error::ok;
}

/// The return modes of the QT128C2X manual (Section 3.1.2, Tail) and of the PandarQT64 (nebula's
/// hesai_packet.hpp get_n_returns, the modes one or two returns a firing): 0x33 first, 0x34
/// second, 0x37 strongest, 0x38 last give one return a firing; 0x39 last + strongest, 0x3A first
/// + second, 0x3B first + last, 0x3C first + strongest, 0x3E strongest + second strongest give
/// two, in adjacent blocks. False for any other byte.
[[nodiscard]] inline bool returns_of_mode(std::uint8_t byte, std::uint8_t& returns) {
  switch (static_cast<ReturnMode>(byte)) {
    case ReturnMode::first:
    case ReturnMode::second:
    case ReturnMode::strongest:
    case ReturnMode::last: returns = 1; return true;
    case ReturnMode::last_strongest:
    case ReturnMode::first_second:
    case ReturnMode::first_last:
    case ReturnMode::first_strongest:
    case ReturnMode::strongest_second_strongest: returns = 2; return true;
    case ReturnMode::first_last_strongest: break;  // triple: the PandarXT32M2X only (xt.cpp)
  }
  return false;
}

/// The manuals' spin rates are 600 and 1200 rpm; 1500 leaves room for a motor settling. Beyond
/// it the field is corrupt (and the firing-time correction, a short series, would lose accuracy).
inline constexpr std::uint16_t kMaxMotorRpm = 1500;
[[nodiscard]] inline Error motor_speed(const PacketInfo& info) {
  return info.motor_rpm > kMaxMotorRpm ? Error::bad_motor_speed : Error::ok;
}

/// Reads the block azimuths (u16 LE at `first`, then every `stride` bytes): each below 360.00
/// degrees, and the blocks of one firing (two in dual return, three in triple) at one azimuth.
[[nodiscard]] inline Error block_azimuths(const std::uint8_t* first, std::size_t stride, PacketInfo& info) {
  for (std::size_t b = 0; b < info.blocks; ++b) {
    info.block_azimuth[b] = load_le16(first + b * stride);
    if (info.block_azimuth[b] >= 36000) return Error::bad_azimuth;
  }
  for (std::size_t b = 1; b < info.blocks; ++b)
    if (b % info.returns != 0 && info.block_azimuth[b] != info.block_azimuth[b - 1]) return Error::dual_block_mismatch;
  return Error::ok;
}

/// The calendar form of a tail's 6-byte date-time: its year (decoded by the caller from byte 0),
/// then month, day, hour, minute, second from bytes 1..5.
inline DateTime tail_date_time(std::int32_t year, const std::uint8_t* dt) {
  return DateTime{year, dt[1], dt[2], dt[3], dt[4], dt[5]};
}

/// Pandar40P/64 year byte, by the vendor SDK's rule (udp_protocol_p40.h, udp_protocol_p64.h:
/// tm_year = byte, + 100 when byte < 70): 0..69 are 2000..2069, as the manuals' "year - 2000"
/// says; 70..255 are years since 1900, as the bundled Pandar64 unit sends them (120 = 2020).
constexpr std::int32_t pandar_year(std::uint8_t byte) { return byte < 70 ? 2000 + byte : 1900 + byte; }
static_assert(pandar_year(17) == 2017 && pandar_year(69) == 2069 && pandar_year(70) == 1970 && pandar_year(120) == 2020);

/// t0 = the tail's date-time (whole seconds, UTC) + its microseconds (at most max_us).
[[nodiscard]] inline Error tail_time(const DateTime& date_time, std::uint32_t max_us, PacketInfo& info) {
  info.date_time = date_time;
  if (!is_valid(info.date_time)) return Error::bad_date_time;
  if (info.timestamp_us > max_us) return Error::bad_timestamp;
  info.time_ns = unix_seconds(info.date_time) * 1000000000LL + static_cast<std::int64_t>(info.timestamp_us) * 1000;
  return Error::ok;
}

/// The tail fields the EE FF protocols with a 6-byte date-time share (QT128 3.2, PandarQT64 3.1,
/// PandarXT 6.1), at
/// their offsets from the tail's start: return mode, motor speed (u16 rpm), timestamp (u32 us),
/// factory info, and the u32 UDP sequence when `has_sequence`.
struct TailFields {
  std::size_t return_mode, motor_speed, timestamp, factory_info, sequence;
};
inline void read_tail(const std::uint8_t* tail, const TailFields& at, bool has_sequence, PacketInfo& info) {
  info.return_mode = tail[at.return_mode];
  info.motor_rpm = load_le16(tail + at.motor_speed);
  info.timestamp_us = load_le32(tail + at.timestamp);
  info.factory_info = tail[at.factory_info];
  if (has_sequence) {
    info.has_sequence = true;
    info.sequence = load_le32(tail + at.sequence);
  }
}

/// A 6-byte date-time whose year byte 0 means Unix seconds, big-endian, in bytes 2..5 (the vendor
/// SDK's GetMicroLidarTimeU64 in udp_protocol_v3_1.h, v3_2.h and v6_1.h; byte 1 is not read); otherwise the
/// calendar form with `year` decoded by the caller from byte 0.
inline DateTime calendar_or_unix(const std::uint8_t* dt, std::int32_t year) {
  return dt[0] == 0 ? date_time_from_unix(load_be32(dt + 2)) : tail_date_time(year, dt);
}

}  // namespace hesai::detail
