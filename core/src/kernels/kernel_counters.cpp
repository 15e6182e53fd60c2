// The kernel-call counters (hesai/detail/kernel_calls.h): test builds only.
#include "kernel_counters.h"

#if HESAI_KERNEL_COUNTERS

namespace hesai::kernels {
std::uint32_t kernel_call_counts[detail::kKernelCount];
bool reference_scan = false;
}  // namespace hesai::kernels

namespace hesai::detail {

static_assert(static_cast<std::size_t>(Kernel::avx2_scan) + 1 == kKernelCount, "kKernelCount: every Kernel");

std::uint32_t kernel_calls(Kernel k) noexcept { return kernels::kernel_call_counts[static_cast<std::size_t>(k)]; }

void reset_kernel_calls() noexcept {
  for (std::uint32_t& c : kernels::kernel_call_counts) c = 0;
}

void use_reference_scan(bool on) noexcept { kernels::reference_scan = on; }

const char* kernel_name(Kernel k) noexcept {
  switch (k) {
    case Kernel::avx512_columns: return "avx512_columns";
    case Kernel::avx512_points: return "avx512_points";
    case Kernel::avx512_beams: return "avx512_beams";
    case Kernel::avx2_columns: return "avx2_columns";
    case Kernel::avx2_points: return "avx2_points";
    case Kernel::avx2_beams: return "avx2_beams";
    case Kernel::neon_columns: return "neon_columns";
    case Kernel::neon_points: return "neon_points";
    case Kernel::armv7m_columns: return "armv7m_columns";
    case Kernel::armv7m_points: return "armv7m_points";
    case Kernel::avx2_scan: return "avx2_scan";
  }
  return "?";
}

}  // namespace hesai::detail

#endif  // HESAI_KERNEL_COUNTERS
