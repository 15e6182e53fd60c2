// CRC-32 (IEEE, as zlib, PNG and MCAP) on every path this build has (port/src/base/crc32_ieee.cpp:
// bytewise, slicing, PCLMULQDQ folding, the ARMv8 CRC32 instructions) against the bitwise
// definition written here: every length 0..4096 at every alignment 0..15, from the initial value
// and continuing from another CRC; the catalogue's check value; and the CPU's own path required
// where the CPU has it (CPUID through the compiler's __builtin_cpu_supports, not the code's check).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include "hesai_port/base/crc32_ieee.h"

namespace {

using hesai::port::Crc32IeeePath;
using hesai::port::crc32_ieee;

constexpr Crc32IeeePath kPaths[] = {Crc32IeeePath::bytewise, Crc32IeeePath::slicing, Crc32IeeePath::pclmul,
                                    Crc32IeeePath::armv8};

// The definition: the register (complemented CRC) shifted right a bit at a time, the reflected
// polynomial 0xEDB88320 xored in when a 1 falls out (CRC catalogue, CRC-32/ISO-HDLC: refin and
// refout true, init and xorout 0xFFFFFFFF).
std::uint32_t bitwise_register(std::uint32_t reg, std::uint8_t byte) {
  reg ^= byte;
  for (int k = 0; k < 8; ++k) reg = (reg & 1u) != 0 ? (reg >> 1) ^ 0xEDB88320u : reg >> 1;
  return reg;
}

std::uint32_t bitwise_crc(const std::uint8_t* p, std::size_t n, std::uint32_t crc = 0) {
  std::uint32_t reg = ~crc;
  for (std::size_t i = 0; i < n; ++i) reg = bitwise_register(reg, p[i]);
  return ~reg;
}

std::vector<std::uint8_t> pseudo_random(std::size_t n, std::uint32_t seed) {
  std::vector<std::uint8_t> v(n);
  std::uint32_t s = seed;
  for (auto& b : v) {
    s ^= s << 13;  // xorshift32
    s ^= s >> 17;
    s ^= s << 5;
    b = static_cast<std::uint8_t>(s >> 11);
  }
  return v;
}

std::vector<Crc32IeeePath> available_paths() {
  std::vector<Crc32IeeePath> paths;
  for (const Crc32IeeePath p : kPaths) {
    if (hesai::port::crc32_ieee_available(p)) paths.push_back(p);
  }
  return paths;
}

TEST(Crc32IeeePaths, CheckValueOnEveryPath) {
  const char* check = "123456789";
  EXPECT_EQ(bitwise_crc(reinterpret_cast<const std::uint8_t*>(check), 9), 0xCBF43926u);  // the catalogue's
  for (const Crc32IeeePath p : kPaths) {  // an unavailable path runs slicing: the same value
    EXPECT_EQ(crc32_ieee(p, check, 9), 0xCBF43926u) << hesai::port::crc32_ieee_path_name(p);
    EXPECT_EQ(crc32_ieee(p, check, 0), 0u) << hesai::port::crc32_ieee_path_name(p);
  }
}

TEST(Crc32IeeePaths, TheCpusPathIsAvailableAndChosen) {
  EXPECT_TRUE(hesai::port::crc32_ieee_available(Crc32IeeePath::bytewise));
  EXPECT_TRUE(hesai::port::crc32_ieee_available(Crc32IeeePath::slicing));
  const Crc32IeeePath best = hesai::port::crc32_ieee_best_path();
  EXPECT_TRUE(hesai::port::crc32_ieee_available(best));
#if defined(__x86_64__)
  const bool pclmul = __builtin_cpu_supports("pclmul") && __builtin_cpu_supports("sse4.1") &&
                      __builtin_cpu_supports("ssse3");
  EXPECT_EQ(hesai::port::crc32_ieee_available(Crc32IeeePath::pclmul), pclmul);
  EXPECT_EQ(best, pclmul ? Crc32IeeePath::pclmul : Crc32IeeePath::slicing);
  EXPECT_FALSE(hesai::port::crc32_ieee_available(Crc32IeeePath::armv8));
#elif defined(__aarch64__) && defined(__ARM_FEATURE_CRC32)
  EXPECT_EQ(best, Crc32IeeePath::armv8);  // the build targets +crc (toolchains/aarch64-linux-gnu.cmake)
  EXPECT_FALSE(hesai::port::crc32_ieee_available(Crc32IeeePath::pclmul));
#else
  EXPECT_EQ(best, Crc32IeeePath::slicing);
  EXPECT_FALSE(hesai::port::crc32_ieee_available(Crc32IeeePath::pclmul));
  EXPECT_FALSE(hesai::port::crc32_ieee_available(Crc32IeeePath::armv8));
#endif
  std::printf("crc32_ieee: best path %s; available:", hesai::port::crc32_ieee_path_name(best));
  for (const Crc32IeeePath p : available_paths()) std::printf(" %s", hesai::port::crc32_ieee_path_name(p));
  std::printf("\n");
}

// Every length 0..4096 at every alignment 0..15 of the start, from the initial value and
// continuing from a CRC, on every available path: the reference for all lengths of one start in
// one pass of the definition.
TEST(Crc32IeeePaths, EveryLengthAndAlignmentEqualsTheDefinition) {
  constexpr std::size_t kMaxLength = 4096;
  const std::vector<std::uint8_t> data = pseudo_random(kMaxLength + 16, 0x1234567u);
  constexpr std::uint32_t kPrior = 0x9E3779B9u;  // a CRC of earlier bytes to continue from
  std::vector<std::uint32_t> fresh(kMaxLength + 1), continued(kMaxLength + 1);
  for (const Crc32IeeePath path : available_paths()) {
    const char* name = hesai::port::crc32_ieee_path_name(path);
    for (std::size_t align = 0; align < 16; ++align) {
      const std::uint8_t* p = data.data() + align;
      std::uint32_t a = ~0u, b = ~kPrior;
      fresh[0] = ~a;
      continued[0] = ~b;
      for (std::size_t n = 1; n <= kMaxLength; ++n) {
        a = bitwise_register(a, p[n - 1]);
        b = bitwise_register(b, p[n - 1]);
        fresh[n] = ~a;
        continued[n] = ~b;
      }
      std::size_t failures = 0;
      for (std::size_t n = 0; n <= kMaxLength && failures < 5; ++n) {
        const std::uint32_t got = crc32_ieee(path, p, n);
        const std::uint32_t got_continued = crc32_ieee(path, p, n, kPrior);
        if (got != fresh[n] || got_continued != continued[n]) {
          ++failures;
          ADD_FAILURE() << name << " length " << n << " alignment " << align << ": " << std::hex << got << " "
                        << got_continued << ", definition " << fresh[n] << " " << continued[n];
        }
      }
    }
  }
}

TEST(Crc32IeeePaths, LargeBufferSplitAnywhereOnEveryPath) {
  const std::vector<std::uint8_t> big = pseudo_random(1u << 20, 99u);
  const std::uint32_t whole = bitwise_crc(big.data(), big.size());
  EXPECT_EQ(crc32_ieee(big.data(), big.size()), whole);
  for (const Crc32IeeePath path : available_paths()) {
    EXPECT_EQ(crc32_ieee(path, big.data(), big.size()), whole) << hesai::port::crc32_ieee_path_name(path);
    for (const std::size_t k : {std::size_t{1}, std::size_t{63}, std::size_t{64}, std::size_t{65537}}) {
      const std::uint32_t first = crc32_ieee(path, big.data(), k);
      EXPECT_EQ(crc32_ieee(path, big.data() + k, big.size() - k, first), whole)
          << hesai::port::crc32_ieee_path_name(path) << " split at " << k;
    }
  }
}

}  // namespace
