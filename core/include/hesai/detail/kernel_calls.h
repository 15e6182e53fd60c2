/// How many times each vector kernel ran: a hook for the tests that compare a vector path with
/// the portable one, which must see the kernel they name run (a kernel may decline a packet, and
/// the scalar loops then write it while decode_simd_name() still names the vector code).
///
/// Compiled in only where HESAI_KERNEL_COUNTERS is 1: the test suite's own build of the core
/// (tests/CMakeLists.txt, hesai_core_counted; the firmware's hesai_core_alt image). Elsewhere,
/// as in the hesai program, the library and the measured firmware images, the counters and
/// these functions do not exist and a kernel call costs nothing more. The counters are plain
/// static integers: not thread-safe, for single-threaded tests.
#pragma once

#include <cstddef>
#include <cstdint>

#if !defined(HESAI_KERNEL_COUNTERS)
#define HESAI_KERNEL_COUNTERS 0
#endif
#if HESAI_KERNEL_COUNTERS != 0 && HESAI_KERNEL_COUNTERS != 1
#error "HESAI_KERNEL_COUNTERS must be 0 or 1"
#endif

namespace hesai::detail {

/// The vector kernels, by instruction set and what they write (core/src/kernels/). `*_beams`: the
/// per-spin-rate beam-cache rebuild (x86-64 only); `armv7m_*`: a packet through the ARMv7E-M
/// assembly loops; `avx2_scan`: a packet's unit scan (UnitScan) by AVX2, on the AVX2 and AVX-512
/// paths alike.
enum class Kernel : std::uint8_t {
  avx512_columns, avx512_points, avx512_beams,
  avx2_columns, avx2_points, avx2_beams,
  neon_columns, neon_points,
  armv7m_columns, armv7m_points,
  avx2_scan,
};
inline constexpr std::size_t kKernelCount = 11;

#if HESAI_KERNEL_COUNTERS
/// Calls of `k` since the last reset_kernel_calls() (or the program's start): one a packet for
/// the decode kernels, one a firing loop's rebuild for the beam kernels.
std::uint32_t kernel_calls(Kernel k) noexcept;
/// Sets every counter to 0.
void reset_kernel_calls() noexcept;
/// "avx512_columns"...
const char* kernel_name(Kernel k) noexcept;
/// While set, every decode with a UnitScan scans the units by the reference scalar scan (the C
/// loop that the firmware builds run), whatever the path: for the tests that compare the hosted
/// scans (branch-free scalar, AVX2) with it. Clear at the start.
void use_reference_scan(bool on) noexcept;
#endif

}  // namespace hesai::detail
