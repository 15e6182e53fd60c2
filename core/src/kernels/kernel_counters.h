// The kernel-call counters of hesai/detail/kernel_calls.h (internal to the core): each vector
// kernel's dispatch counts its call with HESAI_COUNT_KERNEL(name), which is nothing unless
// HESAI_KERNEL_COUNTERS is 1 (test builds only).
#pragma once

#include <cstddef>
#include <cstdint>

#include "hesai/detail/kernel_calls.h"

#if HESAI_KERNEL_COUNTERS
namespace hesai::kernels {
extern std::uint32_t kernel_call_counts[detail::kKernelCount];
// detail::use_reference_scan().
extern bool reference_scan;
}  // namespace hesai::kernels
#define HESAI_COUNT_KERNEL(name) \
  (void)++::hesai::kernels::kernel_call_counts[static_cast<std::size_t>(::hesai::detail::Kernel::name)]
#else
#define HESAI_COUNT_KERNEL(name) ((void)0)
#endif
