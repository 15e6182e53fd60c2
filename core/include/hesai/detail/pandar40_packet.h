// Wire layout of Pandar40 and Pandar40P point cloud packets.
// Sources: Pandar40 manual, Section 3.1.2, Tables 3.3 and 3.4; the Pandar40P packet document
// ("Hesai Pandar40P LiDAR Packet Structure Analysis", "LiDAR UDP Payload Structure").
#pragma once

#include <cstddef>
#include <cstdint>

namespace hesai::pandar40 {

// Body: 10 blocks x (preamble FF EE, azimuth u16, 40 x {distance u16, reflectivity u8}).
inline constexpr std::size_t kBlocks = 10;
inline constexpr std::size_t kChannels = 40;
inline constexpr std::size_t kPointBytes = 3;
inline constexpr std::uint8_t kPreamble0 = 0xFF;  ///< "0xFFEE, 0xFF first"
inline constexpr std::uint8_t kPreamble1 = 0xEE;
inline constexpr std::size_t kBlockAzimuth = 2;   ///< offset of the azimuth inside a block
inline constexpr std::size_t kBlockPoints = 4;    ///< offset of channel 1 inside a block
inline constexpr std::size_t kBlockBytes = kBlockPoints + kChannels * kPointBytes;
inline constexpr std::size_t kBodyBytes = kBlocks * kBlockBytes;
static_assert(kBlockBytes == 124 && kBodyBytes == 1240);

// Tail, both models: offsets from the start of the payload.
inline constexpr std::size_t kTail = kBodyBytes;
inline constexpr std::size_t kHighTemperature = kTail + 5;  ///< after 5 reserved bytes
inline constexpr std::size_t kMotorSpeed = kTail + 8;       ///< u16 RPM, after 2 reserved bytes
inline constexpr std::size_t kTimestamp = kTail + 10;       ///< u32 us
inline constexpr std::size_t kReturnMode = kTail + 14;
inline constexpr std::size_t kFactoryInfo = kTail + 15;

// Pandar40: 16-byte tail, timestamp in us since the top of the hour (Appendix II).
inline constexpr std::size_t kPandar40Bytes = kTail + 16;
static_assert(kPandar40Bytes == 1256);

// Pandar40P: 22-byte tail with date-time (year byte: < 70 -> 2000 + byte, else 1900 + byte, the
// vendor SDK's rule; the manual says year - 2000), then the optional u32 UDP sequence.
inline constexpr std::size_t kDateTime = kTail + 16;
inline constexpr std::size_t kPandar40PBytes = kTail + 22;
inline constexpr std::size_t kSequence = kPandar40PBytes;
inline constexpr std::size_t kPandar40PSequenceBytes = kPandar40PBytes + 4;
static_assert(kPandar40PBytes == 1262 && kPandar40PSequenceBytes == 1266);

}  // namespace hesai::pandar40
