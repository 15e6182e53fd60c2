// Proof that a vector kernel ran: a vector kernel may decline a packet (AVX2 and NEON take whole
// steps of eight units only; a channel map goes to the scalar loops), and the scalar loops then
// write it while decode_simd_name() still names the vector code, so a test comparing that path
// with the portable one would compare the scalar loops with themselves. Against the core built
// with HESAI_KERNEL_COUNTERS=1 (hesai_core_counted), a test counts the decodes it expects each
// kernel to take, one a packet, and KernelTally::check() requires each kernel's own count to be
// exactly that: more than 0 for the kernel the test names, 0 for the others.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <string>

#include "hesai/decoder.h"
#include "hesai/detail/kernel_calls.h"

#if !HESAI_KERNEL_COUNTERS
#error "tests/kernels/ needs the core built with HESAI_KERNEL_COUNTERS=1 (hesai_core_counted)"
#endif

namespace hesai_test {

using hesai::detail::Kernel;

enum class Output { points, columns };

/// The decode kernel a decode by `path` into `out` runs on this machine by the core's own claim
/// (decode_simd_name(): what DecodePath::best runs): for DecodePath::best the claimed ISA's; for
/// DecodePath::avx2 the AVX2 kernel where the claim is AVX-512 or AVX2, the NEON kernel on
/// AArch64 (every path but portable is NEON there). False: no vector kernel is claimed
/// (DecodePath::portable, or no vector code on this CPU).
inline bool claimed_kernel(hesai::DecodePath path, Output out, Kernel& k) {
  if (path == hesai::DecodePath::portable || !hesai::decode_simd_available()) return false;
  const bool points = out == Output::points;
  const char* isa = hesai::decode_simd_name();
  if (std::strcmp(isa, "neon") == 0) {
    k = points ? Kernel::neon_points : Kernel::neon_columns;
  } else if (std::strcmp(isa, "avx512") == 0 && path == hesai::DecodePath::best) {
    k = points ? Kernel::avx512_points : Kernel::avx512_columns;
  } else if (std::strcmp(isa, "avx512") == 0 || std::strcmp(isa, "avx2") == 0) {
    k = points ? Kernel::avx2_points : Kernel::avx2_columns;
  } else {
    ADD_FAILURE() << "decode_simd_available() with decode_simd_name() \"" << isa << "\": no vector kernel of that name";
    return false;
  }
  return true;
}

/// The beam-cache rebuild kernel a decode by `path` at a new spin rate runs here by the same
/// claim: x86-64 only (AArch64 rebuilds by the scalar loop on every path). False: none claimed.
inline bool claimed_beams_kernel(hesai::DecodePath path, Kernel& k) {
  if (path == hesai::DecodePath::portable || !hesai::decode_simd_available()) return false;
  const char* isa = hesai::decode_simd_name();
  if (std::strcmp(isa, "avx512") == 0 && path == hesai::DecodePath::best) k = Kernel::avx512_beams;
  else if (std::strcmp(isa, "avx512") == 0 || std::strcmp(isa, "avx2") == 0) k = Kernel::avx2_beams;
  else return false;
  return true;
}

/// The rebuild kernel of `path` (where one is claimed) ran at least once since the counters were
/// last reset.
inline void expect_beams_rebuilt(hesai::DecodePath path, const std::string& what) {
  Kernel k;
  if (claimed_beams_kernel(path, k)) {
    EXPECT_GT(hesai::detail::kernel_calls(k), 0u) << what << ": kernel " << hesai::detail::kernel_name(k)
                                                  << " never ran: the scalar loop rebuilt the beams in its place";
  }
}

/// The decode kernels (not the beam-cache rebuilds, which a test counts on its own).
inline constexpr Kernel kDecodeKernels[] = {Kernel::avx512_columns, Kernel::avx512_points, Kernel::avx2_columns,
                                            Kernel::avx2_points,    Kernel::neon_columns,  Kernel::neon_points};

/// The decodes a test expects each kernel to take, against the counters from its construction.
class KernelTally {
 public:
  KernelTally() { hesai::detail::reset_kernel_calls(); }

  /// `n` decodes by `path` into `out` that the vector code takes whole (no channel map): the
  /// claimed kernel's count rises by n; none where no kernel is claimed.
  void decoded(hesai::DecodePath path, Output out, std::uint32_t n = 1) {
    Kernel k;
    if (claimed_kernel(path, out, k)) want_[static_cast<std::size_t>(k)] += n;
  }

  /// Every decode kernel ran exactly as counted; a kernel expected to run that never did is named
  /// as such (the scalar loops decoded in its place).
  void check(const std::string& what) const {
    for (const Kernel k : kDecodeKernels) {
      const std::uint32_t want = want_[static_cast<std::size_t>(k)], got = hesai::detail::kernel_calls(k);
      if (want > 0 && got == 0) {
        ADD_FAILURE() << what << ": kernel " << hesai::detail::kernel_name(k) << " never ran (" << want
                      << " decodes expected; decode_simd_name() is \"" << hesai::decode_simd_name()
                      << "\"): the scalar loops decoded in its place";
      } else {
        EXPECT_EQ(got, want) << what << ": calls of kernel " << hesai::detail::kernel_name(k);
      }
    }
  }

  /// The count expected so far of `k`.
  std::uint32_t expected(Kernel k) const { return want_[static_cast<std::size_t>(k)]; }

 private:
  std::array<std::uint32_t, hesai::detail::kKernelCount> want_{};
};

}  // namespace hesai_test
