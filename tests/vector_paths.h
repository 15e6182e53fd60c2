// Whether a path runs vector or hardware code on this CPU, for the tests that compare it with the
// portable code: where the requested path falls back to the portable code, such a test would
// compare that code with itself and pass by accident, so it skips and gives the reason. The
// answers are the core's dispatch queries; ctest simd_path checks those against the CPU flags
// that .ci/run reads from /proc/cpuinfo.
#pragma once

#include <string>

#include "hesai/crc32.h"
#include "hesai/decoder.h"
#include "hesai/sha256.h"

namespace hesai_test {

/// Empty when decoding into PacketColumns through `path` runs vector code here; else why not.
inline std::string columns_scalar_reason(hesai::DecodePath path) {
  if (path == hesai::DecodePath::portable) return "DecodePath::portable is the scalar code";
  if (!hesai::decode_simd_available())
    return std::string("no vector decode on this CPU (decode_simd_name() is \"") + hesai::decode_simd_name() +
           "\"): the path falls back to the scalar code";
  return "";
}

/// As columns_scalar_reason, for Points: every vector decode writes them too (AVX-512, AVX2 on
/// x86-64; NEON on AArch64). The per-spin-rate beam rebuild has vector code on x86-64 only: on
/// AArch64 every path rebuilds by the scalar loop, and a test that rebuilds still compares the
/// Points the NEON code writes from it.
inline std::string points_scalar_reason(hesai::DecodePath path) { return columns_scalar_reason(path); }

/// Empty when `path` runs carry-less multiplication here (for inputs long enough to fold); else why not.
inline std::string crc_portable_reason(hesai::CrcPath path) {
  const bool folding = path == hesai::CrcPath::hardware || path == hesai::CrcPath::hardware_128;
  if (!folding) return "not a hardware path";
  if (!hesai::crc32_hardware_available())
    return std::string("no carry-less multiplication on this CPU: the hardware path falls back to ") +
           hesai::crc32_path_name();
  return "";
}

/// Empty when `path` runs the CPU's SHA instructions here; else why not.
inline std::string sha256_portable_reason(hesai::Sha256Path path) {
  if (path == hesai::Sha256Path::portable) return "Sha256Path::portable is the portable code";
  if (!hesai::sha256_hardware_available())
    return "no SHA instructions on this CPU: the hardware path falls back to the portable code";
  return "";
}

}  // namespace hesai_test
