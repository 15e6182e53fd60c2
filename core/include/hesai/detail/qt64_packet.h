// Wire layout of PandarQT64 point cloud packets, point cloud protocol 3.1.
// No manual for this model is among the seeds. Source: the vendor SDK, HesaiLidar_SDK_2.0
// (ea7f86f) libhesai/UdpProtocol/udp_protocol_v3_1.h (HS_LIDAR_HEADER_QT_V1, HS_LIDAR_BODY_*_QT_V1,
// HS_LIDAR_TAIL_QT_V1, GetPacketSize) and udp_protocol_header.h (pre-header, the 3-byte reserved
// infos); the same offsets in tier4/nebula (606ac41f) decoders/pandar_qt64.hpp (PacketQT64,
// TailQT64). Every offset verified on all 1200 packets of data/pandar_qt64.pcap (1072 bytes each).
// Protocol 3.1 carries no CRC and no signature (neither source has one).
#pragma once

#include <cstddef>
#include <cstdint>

namespace hesai::qt64 {

// Pre-header (6) and header (6).
inline constexpr std::size_t kVersionMajor = 2;  ///< 0x03
inline constexpr std::size_t kVersionMinor = 3;  ///< 0x01
inline constexpr std::size_t kLaserNum = 6;      ///< 0x40
inline constexpr std::size_t kBlockNum = 7;      ///< 0x04
inline constexpr std::size_t kFirstBlockReturn = 8;  ///< SDK "echo count"; not needed to decode
inline constexpr std::size_t kDisUnit = 9;       ///< mm per distance step (0x04)
inline constexpr std::size_t kReturnNum = 10;    ///< SDK "echo num"; the tail's return mode decides
inline constexpr std::size_t kFlags = 11;
inline constexpr std::size_t kHeaderEnd = 12;

// Header flags (SDK HS_LIDAR_HEADER_QT_V1: kSequenceNum, kIMU).
inline constexpr std::uint8_t kFlagSequence = 1u << 0;  ///< the tail ends with a u32 UDP sequence
inline constexpr std::uint8_t kFlagImu = 1u << 1;       ///< no layout published: refused

// Body: 4 blocks x (azimuth u16, 64 units {distance u16, reflectivity u8, confidence u8}).
inline constexpr std::size_t kBlocks = 4;
inline constexpr std::size_t kChannels = 64;
inline constexpr std::size_t kUnitBytes = 4;
inline constexpr std::size_t kBlockPoints = 2;  ///< the units follow the block azimuth
inline constexpr std::size_t kBlockBytes = kBlockPoints + kChannels * kUnitBytes;
inline constexpr std::size_t kBody = kHeaderEnd;

// Tail, 24 bytes, then the u32 UDP sequence (flags bit 0). Offsets inside the tail.
inline constexpr std::size_t kTail = kBody + kBlocks * kBlockBytes;
inline constexpr std::size_t kTailShutdown = 6;     ///< bit 0: shutdown (after 2 reserved infos of 3 bytes)
inline constexpr std::size_t kTailMotorSpeed = 10;  ///< u16 RPM (after a third reserved info)
inline constexpr std::size_t kTailTimestamp = 12;   ///< u32 us within the second
inline constexpr std::size_t kTailReturnMode = 16;
inline constexpr std::size_t kTailFactoryInfo = 17;
/// Date & Time, 6 bytes: year, month, day, hour, minute, second. The year byte by the SDK's
/// GetMicroLidarTimeU64: tm_year = byte (+ 100 below 70), i.e. years since 1900 as nebula reads
/// it (DateTime<1900>); a year byte of 0 means Unix seconds u32 big-endian in bytes 2..5.
inline constexpr std::size_t kTailDateTime = 18;
inline constexpr std::size_t kTailSequence = 24;        ///< u32, present with flags bit 0
inline constexpr std::size_t kPacketBytes = kTail + kTailSequence;  ///< without the UDP sequence
inline constexpr std::size_t kSequencePacketBytes = kPacketBytes + 4;
static_assert(kBlockBytes == 258 && kTail == 1044 && kSequencePacketBytes == 1072);

}  // namespace hesai::qt64
