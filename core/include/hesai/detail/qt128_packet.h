// Wire layout of QT128C2X point cloud packets, protocol 3.2.
// Source: QT128C2X manual, Section 3.1.2 (UDP Data); offsets verified on every packet of the
// bundled capture (protocol notes); the unit size and channel customisation from the vendor SDK
// where the manual is silent. The body's size follows the header's laser num and flags, and
// optional sections are present per the flags, so every offset after the header is computed by
// qt128::Layout.
#pragma once

#include <cstddef>
#include <cstdint>

#include "hesai/error.h"

namespace hesai::qt128 {

// Pre-header (6) and header (6).
inline constexpr std::uint8_t kMagic0 = 0xEE;
inline constexpr std::uint8_t kMagic1 = 0xFF;
inline constexpr std::size_t kVersionMajor = 2;  ///< 0x03
inline constexpr std::size_t kVersionMinor = 3;  ///< 0x02
inline constexpr std::size_t kLaserNum = 6;      ///< 0x80; 1..128 with customised channels (flags bit 6)
inline constexpr std::size_t kBlockNum = 7;      ///< 0x02
inline constexpr std::size_t kFirstBlockReturn = 8;
inline constexpr std::size_t kDisUnit = 9;       ///< mm per distance step (0x04)
inline constexpr std::size_t kReturnNum = 10;    ///< 1 or 2
inline constexpr std::size_t kFlags = 11;
inline constexpr std::size_t kHeaderEnd = 12;

// Header flags.
inline constexpr std::uint8_t kFlagSequence = 1u << 0;
inline constexpr std::uint8_t kFlagImu = 1u << 1;
inline constexpr std::uint8_t kFlagFunctionalSafety = 1u << 2;
inline constexpr std::uint8_t kFlagSignature = 1u << 3;
/// Each point unit carries a confidence byte. The English manual calls bit 4 reserved and draws
/// 4-byte units; the vendor SDK (udp_protocol_v3_2.h, unitSize()) sizes a unit 3 bytes plus this
/// byte only when bit 4 is set, and units in the field send both (protocol notes).
inline constexpr std::uint8_t kFlagConfidence = 1u << 4;
/// Channel customisation: the header's laser num N (1..128) is the units per block, unit j being
/// the channel the channel-configuration file lists j-th for the block's firing loop (SDK
/// udp3_2_parser.cc).
inline constexpr std::uint8_t kFlagChannelCustom = 1u << 6;

// Body: 2 blocks x (azimuth u16, N units {distance u16, reflectivity u8[, confidence u8]}), then
// CRC1. N = 128 unless channels are customised.
inline constexpr std::size_t kBlocks = 2;
inline constexpr std::size_t kChannels = 128;
inline constexpr std::size_t kUnitBytes = 3;        ///< distance u16, reflectivity u8
inline constexpr std::size_t kConfidenceBytes = 1;  ///< with flags bit 4
inline constexpr std::size_t kBlockPoints = 2;      ///< the units follow the block azimuth
inline constexpr std::size_t kBody = kHeaderEnd;

// Functional safety, 17 bytes (flags bit 2): FS version, lidar state, fault code num/id,
// fault code u16, 8 reserved, CRC2 over the 12 bytes after the version.
inline constexpr std::size_t kFsBytes = 17;
inline constexpr std::size_t kFsVersion = 0;
inline constexpr std::size_t kFsLidarState = 1;
inline constexpr std::size_t kFsFaultNum = 2;
inline constexpr std::size_t kFsFaultCode = 3;
inline constexpr std::size_t kFsCrcFrom = 1;
inline constexpr std::size_t kFsCrc2 = 13;
static_assert(kFsCrc2 + 4 == kFsBytes);

// Tail, 30 bytes plus the u32 UDP sequence (flags bit 0), then CRC3 over the tail before it.
inline constexpr std::size_t kTailModeFlag = 5;
inline constexpr std::size_t kTailReturnMode = 12;
inline constexpr std::size_t kTailMotorSpeed = 13;  ///< u16 RPM
/// Date & Time, 6 bytes: year - 1900, month, day, hour, minute, second; or, when the year byte
/// is 0, Unix seconds u32 big-endian in bytes 2..5 (vendor SDK GetMicroLidarTimeU64; units
/// synchronised by PTP send it).
inline constexpr std::size_t kTailDateTime = 15;
inline constexpr std::size_t kDateTimeUnixSeconds = 2;  ///< within the date-time, when its year byte is 0
inline constexpr std::size_t kTailTimestamp = 21;   ///< u32 us
inline constexpr std::size_t kTailFactoryInfo = 25;
inline constexpr std::size_t kTailSequence = 26;    ///< present with flags bit 0
inline constexpr std::size_t kTailFixedBytes = 26;  ///< before the sequence
inline constexpr std::size_t kSignatureBytes = 32;  ///< HMAC-SHA256 (flags bit 3)

/// Where each section of one packet lies, from its header's laser num and flags.
struct Layout {
  std::size_t lasers = 0;     ///< units per block
  std::size_t unit = 0;       ///< bytes per unit: 3, or 4 with flags bit 4
  std::size_t block = 0;      ///< bytes per block: azimuth + units
  std::size_t crc1 = 0;       ///< CRC1 offset: CRC-32/MPEG-2 of the body [kBody, crc1), u32 LE
  std::size_t fs = 0;         ///< functional safety start (0 when absent)
  std::size_t tail = 0;       ///< tail start
  std::size_t crc3 = 0;       ///< CRC3 offset
  std::size_t signature = 0;  ///< signature start (0 when absent)
  std::size_t total = 0;      ///< payload length the header implies

  static constexpr Layout from_header(std::size_t laser_num, std::uint8_t flags) {
    Layout l;
    l.lasers = laser_num;
    l.unit = kUnitBytes + ((flags & kFlagConfidence) ? kConfidenceBytes : 0);
    l.block = kBlockPoints + laser_num * l.unit;
    l.crc1 = kBody + kBlocks * l.block;
    std::size_t at = l.crc1 + 4;
    if (flags & kFlagFunctionalSafety) {
      l.fs = at;
      at += kFsBytes;
    }
    l.tail = at;
    at += kTailFixedBytes + ((flags & kFlagSequence) ? 4 : 0);
    l.crc3 = at;
    at += 4;
    if (flags & kFlagSignature) {
      l.signature = at;
      at += kSignatureBytes;
    }
    l.total = at;
    return l;
  }
};
// The bundled captures' flags 0x1D: 4-byte units, CRC1 at 1040, the tail at 1061, 1127 bytes.
static_assert(Layout::from_header(128, 0x1D).block == 514 && Layout::from_header(128, 0x1D).crc1 == 1040);
static_assert(Layout::from_header(128, 0x1D).total == 1127 && Layout::from_header(128, 0x1D).tail == 1061);
static_assert(Layout::from_header(128, 0x10).total == 1074);
// Bit 4 clear (0x0D): 3-byte units, a body of 2 x (2 + 128 x 3) = 772 bytes, 1127 - 256 = 871 in all.
static_assert(2 * Layout::from_header(128, 0x0D).block == 772 && Layout::from_header(128, 0x0D).total == 871);
static_assert(Layout::from_header(128, 0x0D).crc1 == 12 + 772 && Layout::from_header(128, 0x0D).tail == 805);
// 80 customised channels of 4 bytes (0x5D): 2 x (2 + 80 x 4) = 644 body bytes, 1127 - 384 = 743.
static_assert(Layout::from_header(80, 0x5D).total == 743);

// qt128::seal() and qt128::sign(), which write what these fields check, are declared in hesai/decoder.h.

}  // namespace hesai::qt128
