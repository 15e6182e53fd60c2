#include "vector_isa.h"

#include "../base/cpu_x86.h"
#include "kernel_inputs.h"

namespace hesai::kernels {

VectorIsa vector_isa([[maybe_unused]] DecodePath path) noexcept {
#if defined(HESAI_KERNELS_X86)
  if (path == DecodePath::portable || !detail::x86_has(detail::X86Feature::avx2)) return VectorIsa::none;
  if (path == DecodePath::best && detail::x86_has(detail::X86Feature::avx512)) return VectorIsa::avx512;
  return VectorIsa::avx2;
#elif defined(HESAI_KERNELS_NEON)
  return path == DecodePath::portable ? VectorIsa::none : VectorIsa::neon;
#elif defined(HESAI_KERNELS_ARMV7M)
  return path == DecodePath::portable ? VectorIsa::none : VectorIsa::armv7m;
#else
  return VectorIsa::none;
#endif
}

const char* vector_isa_name(VectorIsa isa) noexcept {
  switch (isa) {
    case VectorIsa::avx512: return "avx512";
    case VectorIsa::avx2: return "avx2";
    case VectorIsa::neon: return "neon";
    case VectorIsa::armv7m: return "armv7m";
    case VectorIsa::none: break;
  }
  return "none";
}

}  // namespace hesai::kernels
