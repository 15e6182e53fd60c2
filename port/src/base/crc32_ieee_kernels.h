// The CPU-specific CRC-32 (IEEE) kernels (private to port/src/base): crc32_ieee.cpp chooses among
// them. Each takes and returns the CRC register (the complemented CRC, as zlib keeps it inside).
#pragma once

#include <cstddef>
#include <cstdint>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define HESAI_CRC32_IEEE_PCLMUL 1  // crc32_ieee_x86.cpp: target attributes, chosen by CPUID
#endif
#if defined(__aarch64__) && defined(__ARM_FEATURE_CRC32)
#define HESAI_CRC32_IEEE_ARMV8 1  // crc32_ieee_arm.cpp: the target has +crc (-march=armv8-a+crc, armv8.1-a on)
#endif

namespace hesai::port::crc32_ieee_kernels {

/// Slicing-by-8/16 over any length (crc32_ieee.cpp): the tail of the other kernels.
std::uint32_t slicing(std::uint32_t reg, const std::uint8_t* p, std::size_t n) noexcept;

#if defined(HESAI_CRC32_IEEE_PCLMUL)
/// PCLMULQDQ, SSSE3 and SSE4.1 present (CPUID, read once).
bool pclmul_available() noexcept;
/// Folds n bytes, n >= 64 and a multiple of 16.
std::uint32_t pclmul_blocks(std::uint32_t reg, const std::uint8_t* p, std::size_t n) noexcept;
inline constexpr std::size_t kPclmulMinBytes = 64;
#endif

#if defined(HESAI_CRC32_IEEE_ARMV8)
/// Any length.
std::uint32_t armv8(std::uint32_t reg, const std::uint8_t* p, std::size_t n) noexcept;
#endif

}  // namespace hesai::port::crc32_ieee_kernels
