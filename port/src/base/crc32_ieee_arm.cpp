// CRC-32 (IEEE) with the ARMv8 CRC32 instructions, which compute this reflected polynomial
// (CRC32X/W/H/B: 8, 4, 2 and 1 bytes into the register, ACLE __crc32d and the others). Compiled in
// when the target has them (__ARM_FEATURE_CRC32: -march=armv8-a+crc, or armv8.1-a and later, as
// toolchains/aarch64-linux-gnu.cmake sets); empty otherwise.
#include "crc32_ieee_kernels.h"

#if defined(HESAI_CRC32_IEEE_ARMV8)

#include <arm_acle.h>

namespace hesai::port::crc32_ieee_kernels {
namespace {

// Little-endian loads from bytes (the instructions take the first byte in the lowest bits, in
// either byte order of the CPU); compilers fold them into one load.
inline std::uint64_t load_le64(const std::uint8_t* p) noexcept {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}

}  // namespace

std::uint32_t armv8(std::uint32_t reg, const std::uint8_t* p, std::size_t n) noexcept {
  // Four independent streams would hide the instruction's latency on wide cores; one stream of
  // 8 bytes is already several GB/s, past any writer's need here.
  for (; n >= 32; p += 32, n -= 32) {
    reg = __crc32d(reg, load_le64(p));
    reg = __crc32d(reg, load_le64(p + 8));
    reg = __crc32d(reg, load_le64(p + 16));
    reg = __crc32d(reg, load_le64(p + 24));
  }
  for (; n >= 8; p += 8, n -= 8) reg = __crc32d(reg, load_le64(p));
  for (; n != 0; ++p, --n) reg = __crc32b(reg, *p);
  return reg;
}

}  // namespace hesai::port::crc32_ieee_kernels

#endif  // HESAI_CRC32_IEEE_ARMV8
