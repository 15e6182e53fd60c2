// CRC-32 as zlib, PNG and MCAP compute it: pure functions, no allocation (the MCAP writer and
// reader use it; the core's CRC is CRC-32/MPEG-2, another polynomial order). Reentrant; the
// CPU check of the x86-64 path runs once (a function-local static).
#pragma once

#include <cstddef>
#include <cstdint>

namespace hesai::port {

/// CRC-32 as zlib, PNG and MCAP compute it (IEEE 802.3: reflected polynomial 0xEDB88320, initial
/// value and final XOR 0xFFFFFFFF; check value 0xCBF43926 for "123456789"). Not the core's
/// CRC-32/MPEG-2. Pass the previous result as `crc` to continue over more bytes. Runs the fastest
/// path this CPU has (crc32_ieee_best_path()).
std::uint32_t crc32_ieee(const void* data, std::size_t size, std::uint32_t crc = 0);
/// The CRC-32 of A followed by B from crc32_ieee(A), crc32_ieee(B) and B's length, without B's
/// bytes (the zlib crc32_combine operation).
std::uint32_t crc32_ieee_combine(std::uint32_t crc_a, std::uint32_t crc_b, std::uint64_t size_b);

/// The implementations, selectable for tests and benchmarks. All give the same result.
enum class Crc32IeeePath : std::uint8_t {
  bytewise,  ///< one 256-entry table lookup per byte
  slicing,   ///< slicing-by-16 (8 tables of 1 KiB on 32-bit targets: slicing-by-8), any byte order
  pclmul,    ///< x86-64 PCLMULQDQ folding, 64 bytes a step (inputs of 64 bytes and more; the
             ///< rest by slicing); where the CPU has PCLMULQDQ, SSSE3 and SSE4.1
  armv8,     ///< the ARMv8 CRC32 instructions, 8 bytes each (__crc32d); AArch64 built with +crc
};

/// Whether `path` runs on this CPU (bytewise and slicing always do).
bool crc32_ieee_available(Crc32IeeePath path) noexcept;
/// What crc32_ieee() runs here: pclmul or armv8 where available, else slicing. The one place that
/// chooses.
Crc32IeeePath crc32_ieee_best_path() noexcept;
/// "bytewise", "slicing", "pclmul" or "armv8".
const char* crc32_ieee_path_name(Crc32IeeePath path) noexcept;
/// crc32_ieee through one chosen path; a path not available here runs slicing instead.
std::uint32_t crc32_ieee(Crc32IeeePath path, const void* data, std::size_t size, std::uint32_t crc = 0);

}  // namespace hesai::port
