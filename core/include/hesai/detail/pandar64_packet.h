// Wire layout of Pandar64 point cloud packets.
// Source: Pandar64 manual, Section 3.1.2: header 3.1.2.1, body 3.1.2.2, tail 3.1.2.3.
#pragma once

#include <cstddef>
#include <cstdint>

namespace hesai::pandar64 {

// Header, 8 bytes.
inline constexpr std::uint8_t kMagic0 = 0xEE;
inline constexpr std::uint8_t kMagic1 = 0xFF;
inline constexpr std::size_t kLaserNum = 2;  ///< 0x40
inline constexpr std::size_t kBlockNum = 3;  ///< 0x06
inline constexpr std::size_t kDisUnit = 5;   ///< mm per distance step (0x04)
inline constexpr std::size_t kHeaderBytes = 8;

// Body: 6 blocks x (azimuth u16, 64 x {distance u16, reflectivity u8}).
inline constexpr std::size_t kBlocks = 6;
inline constexpr std::size_t kChannels = 64;
inline constexpr std::size_t kPointBytes = 3;
inline constexpr std::size_t kBlockPoints = 2;  ///< offset of channel 1 inside a block
inline constexpr std::size_t kBlockBytes = kBlockPoints + kChannels * kPointBytes;
inline constexpr std::size_t kBody = kHeaderBytes;
static_assert(kBlockBytes == 194);

// Tail, 22 bytes, then the optional u32 UDP sequence.
inline constexpr std::size_t kTail = kBody + kBlocks * kBlockBytes;
inline constexpr std::size_t kHighTemperature = kTail + 5;
inline constexpr std::size_t kMotorSpeed = kTail + 8;   ///< u16 RPM
inline constexpr std::size_t kTimestamp = kTail + 10;   ///< u32 us within the second
inline constexpr std::size_t kReturnMode = kTail + 14;
inline constexpr std::size_t kFactoryInfo = kTail + 15;
/// Year, month, day, hour, minute, second. The manual's year byte is year - 2000; units send years
/// since 1900 as well (120 = 2020): read by the vendor SDK's rule, byte < 70 -> 2000 + byte, else
/// 1900 + byte.
inline constexpr std::size_t kDateTime = kTail + 16;
inline constexpr std::size_t kPacketBytes = kTail + 22;
inline constexpr std::size_t kSequence = kPacketBytes;
inline constexpr std::size_t kSequencePacketBytes = kPacketBytes + 4;
static_assert(kTail == 1172 && kPacketBytes == 1194 && kSequencePacketBytes == 1198);

}  // namespace hesai::pandar64
