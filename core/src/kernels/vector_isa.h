// The one place that picks the vector code a decode runs (internal to the core): from the
// caller's DecodePath and, on x86-64, the CPU's features (read once, base/cpu_x86.h). The vector
// kernels, the beam-cache rebuild and hesai::decode_simd_name() all ask it.
#pragma once

#include <cstdint>

#include "hesai/point.h"

namespace hesai::kernels {

enum class VectorIsa : std::uint8_t { none, avx2, avx512, neon };

/// What `path` runs here: none for DecodePath::portable or a target without vector kernels;
/// x86-64: avx512 for `best` where the CPU has AVX-512 F, BW, DQ and VL, else avx2 where it has
/// AVX2; AArch64: neon.
VectorIsa vector_isa(DecodePath path) noexcept;
/// "avx512", "avx2", "neon" or "none".
const char* vector_isa_name(VectorIsa isa) noexcept;

}  // namespace hesai::kernels
