// ctest simd_path: prints the decode, CRC and SHA-256 paths the core chose on this machine, and
// fails when the environment names other ones: HESAI_EXPECT_SIMD (avx512, avx2, neon or none:
// hesai::decode_simd_name()), HESAI_EXPECT_CRC32 (hesai::crc32_path_name()) and
// HESAI_EXPECT_SHA256 (hesai::sha256_path_name()). Unset or empty, a variable is not checked.
// .ci/run and .ci/cross set them from what they know of the CPU (/proc/cpuinfo, the cross
// toolchain), and ctest's simd_path (tests/simd_path.cmake) the same way where none is set, so
// that vector code the machine has cannot go unused without a failing test.
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "hesai/crc32.h"
#include "hesai/decoder.h"
#include "hesai/sha256.h"

namespace {

struct Check {
  const char* variable;
  const char* actual;
  const char* known[6];  // the values the variable may take, null-terminated
};

// 0: as expected or not asked; 1: another path; 2: a value the variable cannot take.
int check(const Check& c) {
  const char* expect = std::getenv(c.variable);
  if (expect == nullptr || *expect == '\0') {
    std::printf("  %s unset: not checked\n", c.variable);
    return 0;
  }
  bool known = false;
  for (const char* const* k = c.known; *k != nullptr; ++k) known = known || std::strcmp(*k, expect) == 0;
  if (!known) {
    std::printf("FAIL: %s=%s is not one of the values it may take:", c.variable, expect);
    for (const char* const* k = c.known; *k != nullptr; ++k) std::printf(" %s", *k);
    std::printf("\n");
    return 2;
  }
  if (std::strcmp(expect, c.actual) != 0) {
    std::printf("FAIL: %s=%s, but the core runs %s on this machine\n", c.variable, expect, c.actual);
    return 1;
  }
  std::printf("  %s=%s: as expected\n", c.variable, expect);
  return 0;
}

}  // namespace

int main() {
  const Check checks[] = {
      {"HESAI_EXPECT_SIMD", hesai::decode_simd_name(), {"avx512", "avx2", "neon", "armv7m", "none", nullptr}},
      {"HESAI_EXPECT_CRC32", hesai::crc32_path_name(), {"vpclmulqdq", "pclmulqdq", "pmull", "slicing", "table", nullptr}},
      {"HESAI_EXPECT_SHA256", hesai::sha256_path_name(), {"sha-ni", "armv8-sha2", "portable", nullptr}},
  };
  std::printf("decode: %s\ncrc32: %s\nsha256: %s\n", checks[0].actual, checks[1].actual, checks[2].actual);
  int worst = 0;
  for (const Check& c : checks) {
    const int r = check(c);
    worst = r > worst ? r : worst;
  }
  return worst;
}
