// CRC-32 as zlib, PNG and MCAP compute it: pure functions, no allocation (the MCAP writer and
// reader use it; the core's CRC is CRC-32/MPEG-2, another polynomial order).
#pragma once

#include <cstddef>
#include <cstdint>

namespace hesai::port {

/// CRC-32 as zlib, PNG and MCAP compute it (IEEE 802.3: reflected polynomial 0xEDB88320, initial
/// value and final XOR 0xFFFFFFFF; check value 0xCBF43926 for "123456789"). Not the core's
/// CRC-32/MPEG-2. Pass the previous result as `crc` to continue over more bytes.
std::uint32_t crc32_ieee(const void* data, std::size_t size, std::uint32_t crc = 0);
/// The CRC-32 of A followed by B from crc32_ieee(A), crc32_ieee(B) and B's length, without B's
/// bytes (the zlib crc32_combine operation).
std::uint32_t crc32_ieee_combine(std::uint32_t crc_a, std::uint32_t crc_b, std::uint64_t size_b);

}  // namespace hesai::port
