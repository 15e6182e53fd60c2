#include "cpu_x86.h"

#if defined(HESAI_X86_FEATURES)

#include <cpuid.h>

#include <atomic>

namespace hesai::detail {
namespace {

constexpr std::uint8_t kKnown = 0x80;  // the byte holds the answer
std::atomic<std::uint8_t> g_features{0};

std::uint8_t read_features() noexcept {
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  if (__get_cpuid(1, &eax, &ebx, &ecx, &edx) == 0) return kKnown;
  const unsigned ecx1 = ecx;
  // CPUID.01H:ECX (Intel SDM vol. 2A, table 3-10): PCLMULQDQ 1, SSSE3 9, SSE4.1 19, POPCNT 23,
  // OSXSAVE 27, AVX 28. CPUID.(EAX=07H, ECX=0):EBX: AVX2 5, AVX512F 16, AVX512DQ 17, SHA 29,
  // AVX512BW 30, AVX512VL 31; ECX: VPCLMULQDQ 10.
  const auto has1 = [ecx1](unsigned bits) { return (ecx1 & bits) == bits; };
  constexpr unsigned kSsse3Sse41 = (1u << 9) | (1u << 19);
  unsigned ebx7 = 0, ecx7 = 0;
  if (__get_cpuid_count(7, 0, &eax, &ebx, &ecx, &edx) != 0) ebx7 = ebx, ecx7 = ecx;
  const auto has7 = [ebx7](unsigned bits) { return (ebx7 & bits) == bits; };
  std::uint8_t f = kKnown;
  const auto add = [&f](X86Feature feature) { f = static_cast<std::uint8_t>(f | static_cast<std::uint8_t>(feature)); };
  if (has1((1u << 1) | kSsse3Sse41)) add(X86Feature::clmul);
  if (has1(kSsse3Sse41) && has7(1u << 29)) add(X86Feature::sha_ni);
  if (has1((1u << 23) | (1u << 27) | (1u << 28)) && has7(1u << 5)) {
    // XCR0 (XGETBV needs OSXSAVE, checked above): bits 1 and 2, the OS saves the SSE and AVX
    // state; bits 5, 6 and 7, the opmask and the 512-bit registers.
    unsigned xcr0_lo = 0, xcr0_hi = 0;
    __asm__("xgetbv" : "=a"(xcr0_lo), "=d"(xcr0_hi) : "c"(0));
    if ((xcr0_lo & 0x06u) == 0x06u) add(X86Feature::avx2);
    constexpr unsigned kAvx512 = (1u << 16) | (1u << 17) | (1u << 30) | (1u << 31);
    if ((xcr0_lo & 0xE6u) == 0xE6u && has7(kAvx512)) {
      add(X86Feature::avx512);
      if (has1(1u << 1) && (ecx7 & (1u << 10)) != 0) add(X86Feature::vpclmul);
    }
  }
  return f;
}

}  // namespace

bool x86_has(X86Feature feature) noexcept {
  std::uint8_t f = g_features.load(std::memory_order_relaxed);
  if (f == 0) {
    f = read_features();
    g_features.store(f, std::memory_order_relaxed);
  }
  return (f & static_cast<std::uint8_t>(feature)) != 0;
}

}  // namespace hesai::detail

#endif
