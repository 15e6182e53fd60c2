// Wire layout of QT128C2X point cloud packets, protocol 3.2.
// Source: QT128C2X manual, Section 3.1.2 (UDP Data); offsets verified on every packet of the
// bundled capture (protocol notes). Optional sections are present per the header flags, so the
// offsets after the body are computed by qt128::Layout.
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
inline constexpr std::size_t kLaserNum = 6;      ///< 0x80
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
inline constexpr std::uint8_t kFlagChannelCustom = 1u << 6;

// Body: 2 blocks x (azimuth u16, 128 x {distance u16, reflectivity u8, confidence u8}), then CRC1.
inline constexpr std::size_t kBlocks = 2;
inline constexpr std::size_t kChannels = 128;
inline constexpr std::size_t kPointBytes = 4;
inline constexpr std::size_t kBlockPoints = 2;
inline constexpr std::size_t kBlockBytes = kBlockPoints + kChannels * kPointBytes;
inline constexpr std::size_t kBody = kHeaderEnd;
inline constexpr std::size_t kBodyBytes = kBlocks * kBlockBytes;
inline constexpr std::size_t kCrc1 = kBody + kBodyBytes;  ///< CRC-32/MPEG-2 of the body, u32 LE
inline constexpr std::size_t kBodyEnd = kCrc1 + 4;
static_assert(kBlockBytes == 514 && kCrc1 == 1040 && kBodyEnd == 1044);

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
inline constexpr std::size_t kTailDateTime = 15;    ///< year - 1900, month, day, hour, minute, second
inline constexpr std::size_t kTailTimestamp = 21;   ///< u32 us
inline constexpr std::size_t kTailFactoryInfo = 25;
inline constexpr std::size_t kTailSequence = 26;    ///< present with flags bit 0
inline constexpr std::size_t kTailFixedBytes = 26;  ///< before the sequence
inline constexpr std::size_t kSignatureBytes = 32;  ///< HMAC-SHA256 (flags bit 3)

/// Where each section of one packet lies, from its flags.
struct Layout {
  std::size_t fs = 0;         ///< functional safety start (0 when absent)
  std::size_t tail = 0;       ///< tail start
  std::size_t crc3 = 0;       ///< CRC3 offset
  std::size_t signature = 0;  ///< signature start (0 when absent)
  std::size_t total = 0;      ///< payload length these flags imply

  static constexpr Layout from_flags(std::uint8_t flags) {
    Layout l;
    std::size_t at = kBodyEnd;
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
static_assert(Layout::from_flags(0x1D).total == 1127 && Layout::from_flags(0x1D).tail == 1061);
static_assert(Layout::from_flags(0x00).total == 1074);

/// Rewrites CRC1 (body), CRC2 (functional safety, when present) and CRC3 (tail) of a QT128
/// packet from its bytes, where the layout of its header flags puts them: for tools that change a
/// field (a replayer renumbering the UDP sequence, a test building packets). The signature, when
/// present, is left as it is (it no longer verifies once a signed byte changed).
/// Error::bad_length (nothing written) when `size` is not the length the flags imply;
/// Error::bad_magic when the packet does not start with EE FF.
Error seal(std::uint8_t* payload, std::size_t size) noexcept;

}  // namespace hesai::qt128
