// x86-64 CPU features for the paths chosen at run time (internal to the core): the CRC's
// PCLMULQDQ (and VPCLMULQDQ) folding, SHA-NI and the AVX2 and AVX-512 decodes. Read once from CPUID (and XGETBV) and cached in
// one relaxed atomic byte, the core's only static RAM: racing first calls store the same value.
#pragma once

#include <cstdint>

#include "compiler.h"

#if defined(__x86_64__) && HESAI_GNU
#define HESAI_X86_FEATURES 1

namespace hesai::detail {

enum class X86Feature : std::uint8_t {
  clmul = 1,  ///< PCLMULQDQ with SSSE3 and SSE4.1 (crc/crc32_x86.cpp)
  sha_ni = 2, ///< SHA extensions with SSSE3 and SSE4.1 (crypto/sha256.cpp)
  avx2 = 4,   ///< AVX2 and POPCNT, with the OS saving the AVX state (kernels/x86_columns.cpp, x86_points.cpp)
  avx512 = 8, ///< AVX2 and AVX-512 F, BW, DQ and VL, with the OS saving the AVX-512 state
  vpclmul = 16, ///< PCLMULQDQ, AVX-512 (as avx512) and VPCLMULQDQ: 512-bit carry-less multiplication
};

/// Whether this CPU has `feature`.
bool x86_has(X86Feature feature) noexcept;

}  // namespace hesai::detail

#endif
