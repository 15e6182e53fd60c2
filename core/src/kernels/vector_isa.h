// The one place that picks the vector code a decode runs (internal to the core): from the
// caller's DecodePath and, on x86-64, the CPU's features (read once, base/cpu_x86.h). The vector
// kernels, the beam-cache rebuild and hesai::decode_simd_name() all ask it.
#pragma once

#include <cstdint>

#include "hesai/point.h"

namespace hesai::kernels {

// armv7m: not vector code but the assembly unit loops of ARMv7E-M (armv7m_loops.h), chosen the same way.
enum class VectorIsa : std::uint8_t { none, avx2, avx512, neon, armv7m };

/// What `path` runs here: none for DecodePath::portable or a target without vector kernels;
/// x86-64: avx512 for `best` where the CPU has AVX-512 F, BW, DQ and VL, else avx2 where it has
/// AVX2; AArch64: neon; ARMv7E-M with an FPU: armv7m.
VectorIsa vector_isa(DecodePath path) noexcept;
/// "avx512", "avx2", "neon", "armv7m" or "none".
const char* vector_isa_name(VectorIsa isa) noexcept;

}  // namespace hesai::kernels
