// Wire layout of PandarXT16, PandarXT32 and PandarXT32M2X point cloud packets, protocol 6.1.
// No manual for these models is among the seeds. Source: the vendor SDK, HesaiLidar_SDK_2.0
// (ea7f86f), libhesai/UdpProtocol/udp_protocol_v6_1.h (HsLidarXTV1Header, HsLidarXTV1Tail and
// GetPacketSize) and the ReservedInfo structs of udp_protocol_header.h; tier4/nebula (606ac41f)
// pandar_xt32.hpp (TailXT32) agrees. Offsets confirmed on every packet of the three bundled
// captures (data/pandar_xt*.pcap). Protocol 6.1 carries no CRC and no signature.
#pragma once

#include <cstddef>
#include <cstdint>

namespace hesai::xt {

// Pre-header (6: EE FF, protocol major 6, minor 1, 2 reserved) and header (6).
inline constexpr std::size_t kVersionMajor = 2;   ///< 0x06
inline constexpr std::size_t kVersionMinor = 3;   ///< 0x01
inline constexpr std::size_t kLaserNum = 6;       ///< 16 (XT16) or 32 (XT32, XT32M2X)
inline constexpr std::size_t kBlockNum = 7;       ///< 8 (XT16, XT32) or 6 (XT32M2X)
/// Echo count ("first block return" in the SDK: 1 = the first block holds the last return, 2 = the
/// strongest). The captures send 1 whatever their return mode; kept, not checked.
inline constexpr std::size_t kFirstBlockReturn = 8;
inline constexpr std::size_t kDisUnit = 9;        ///< mm per distance step: 4 (XT16, XT32), 5 (XT32M2X capture)
/// Echo num. Not the returns per firing: the XT32M2X capture says 3 while its tail says dual
/// (0x3C) and its block azimuths come in pairs; the tail's return mode decides.
inline constexpr std::size_t kReturnNum = 10;
inline constexpr std::size_t kFlags = 11;
inline constexpr std::size_t kHeaderEnd = 12;
/// Header flags bit 0: the tail's UDP sequence is in use (SDK HasSeqNum). The field is part of
/// the tail, and of the length, whether or not the bit is set (SDK GetPacketSize).
inline constexpr std::uint8_t kFlagSequence = 1u << 0;

// Body: blocks x (azimuth u16, lasers x {distance u16, reflectivity u8, confidence u8}).
inline constexpr std::size_t kBody = kHeaderEnd;
inline constexpr std::size_t kUnitBytes = 4;
inline constexpr std::size_t kBlockPoints = 2;  ///< the units follow the block azimuth

// Tail, 28 bytes: three reserved {u16 data, u8 id}, shutdown flag (bit 0), return mode, motor
// speed u16 RPM, date-time (6), timestamp u32 us, factory info, UDP sequence u32.
inline constexpr std::size_t kTailShutdown = 9;
inline constexpr std::size_t kTailReturnMode = 10;
inline constexpr std::size_t kTailMotorSpeed = 11;
/// Year - 1900 (SDK: + 100 more when below 70), month, day, hour, minute, second; a year byte of
/// 0 means Unix seconds, u32 big-endian, in bytes 2..5 (SDK GetMicroLidarTimeU64).
inline constexpr std::size_t kTailDateTime = 13;
inline constexpr std::size_t kTailTimestamp = 19;
inline constexpr std::size_t kTailFactoryInfo = 23;
inline constexpr std::size_t kTailSequence = 24;
inline constexpr std::size_t kTailBytes = 28;

/// Bytes of one block with `lasers` units.
constexpr std::size_t block_bytes(std::size_t lasers) { return kBlockPoints + lasers * kUnitBytes; }
/// Offset of the tail in a packet of `lasers` x `blocks`.
constexpr std::size_t tail_offset(std::size_t lasers, std::size_t blocks) { return kBody + blocks * block_bytes(lasers); }
/// Payload length of a packet of `lasers` x `blocks`.
constexpr std::size_t packet_bytes(std::size_t lasers, std::size_t blocks) {
  return tail_offset(lasers, blocks) + kTailBytes;
}
// The bundled captures' payload lengths (captures README): XT16 568, XT32 1080, XT32M2X 820 bytes.
static_assert(packet_bytes(16, 8) == 568 && packet_bytes(32, 8) == 1080 && packet_bytes(32, 6) == 820);

}  // namespace hesai::xt
