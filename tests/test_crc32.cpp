// CRC-32/MPEG-2: catalogue and hand-derived values, every implementation path against the
// bitwise definition (every length 0..4096; every alignment 0..15 for the multi-byte paths),
// streaming, and the three CRCs of real QT128C2X packets.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include "hesai/bytes.h"
#include "hesai/crc32.h"
#include "hesai/sha256.h"
#include "test_support.h"
#include "vector_paths.h"

namespace {

using hesai::ByteView;
using hesai::CrcPath;
using hesai::kCrc32Mpeg2Init;

constexpr CrcPath kPaths[] = {CrcPath::bitwise, CrcPath::table, CrcPath::slicing, CrcPath::hardware,
                              CrcPath::hardware_128};

const char* path_name(CrcPath p) {
  switch (p) {
    case CrcPath::bitwise: return "bitwise";
    case CrcPath::table: return "table";
    case CrcPath::slicing: return "slicing";
    case CrcPath::hardware: return "hardware";
    case CrcPath::hardware_128: return "hardware_128";
  }
  return "?";
}

ByteView view(const std::vector<std::uint8_t>& v) { return {v.data(), v.size()}; }

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

// "123456789": the catalogue's check string (Greg Cook's CRC catalogue, CRC-32/MPEG-2 entry:
// width=32 poly=0x04c11db7 init=0xffffffff refin=false refout=false xorout=0x00000000 check=0x0376e6e7).
constexpr std::uint8_t kCheck[9] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
static_assert(hesai::crc32_mpeg2_bitwise(kCrc32Mpeg2Init, kCheck, 9) == 0x0376E6E7u);

TEST(Crc32Mpeg2, CheckValueOnEveryPath) {
  const ByteView check{kCheck, sizeof kCheck};
  EXPECT_EQ(hesai::crc32_mpeg2(check), 0x0376E6E7u);
  EXPECT_EQ(hesai::crc32_mpeg2_update(kCrc32Mpeg2Init, check), 0x0376E6E7u);
  EXPECT_EQ(hesai::crc32_mpeg2_bitwise(kCrc32Mpeg2Init, kCheck, sizeof kCheck), 0x0376E6E7u);
  for (CrcPath p : kPaths) EXPECT_EQ(hesai::crc32_mpeg2_update(p, kCrc32Mpeg2Init, check), 0x0376E6E7u) << path_name(p);
}

// A property of this CRC (no final xor, not reflected): a message followed by its own CRC,
// big-endian, leaves register 0. Lengths of 64 and more make the hardware path fold.
TEST(Crc32Mpeg2, ResidueIsZeroAfterAppendingTheCrc) {
  for (std::size_t n : {std::size_t{9}, std::size_t{64}, std::size_t{100}, std::size_t{1028}, std::size_t{4000}}) {
    std::vector<std::uint8_t> msg = pseudo_random(n + 4, static_cast<std::uint32_t>(n) + 1);
    const std::uint32_t crc = hesai::crc32_mpeg2(ByteView{msg.data(), n});
    hesai::store_be32(msg.data() + n, crc);
    for (CrcPath p : kPaths) {
      EXPECT_EQ(hesai::crc32_mpeg2_update(p, kCrc32Mpeg2Init, view(msg)), 0u) << path_name(p) << " n=" << n;
    }
  }
}

// Values worked out by hand from the definition (register 0xFFFFFFFF, poly 0x04C11DB7, MSB first):
// - the empty message leaves the initial register: 0xFFFFFFFF.
// - one byte 0x00: the register stays 0xFFFFFFFF after xoring 0x00 into its top byte, then 8 steps
//   "shift left; if the bit shifted out was 1, xor 0x04C11DB7":
//     FFFFFFFF -> FB3EE249 -> F2BCD925 -> E1B8AFFD -> C7B0424D -> 8BA1992D -> 13822FED
//     -> 27045FDA (top bit was 0: shift only) -> 4E08BFB4 (top bit 0 again).
// - FF FF FF FF: the four bytes cancel the initial register exactly, leaving 0.
// - FF FF FF FF 00: register 0 followed by a zero byte stays 0.
TEST(Crc32Mpeg2, HandDerivedValues) {
  const std::uint8_t zero[1] = {0x00};
  const std::uint8_t ones[5] = {0xFF, 0xFF, 0xFF, 0xFF, 0x00};
  for (CrcPath p : kPaths) {
    EXPECT_EQ(hesai::crc32_mpeg2_update(p, kCrc32Mpeg2Init, ByteView{}), 0xFFFFFFFFu) << path_name(p);
    EXPECT_EQ(hesai::crc32_mpeg2_update(p, kCrc32Mpeg2Init, ByteView{zero, 1}), 0x4E08BFB4u) << path_name(p);
    EXPECT_EQ(hesai::crc32_mpeg2_update(p, kCrc32Mpeg2Init, ByteView{ones, 4}), 0x00000000u) << path_name(p);
    EXPECT_EQ(hesai::crc32_mpeg2_update(p, kCrc32Mpeg2Init, ByteView{ones, 5}), 0x00000000u) << path_name(p);
  }
  EXPECT_EQ(hesai::crc32_mpeg2(ByteView{}), 0xFFFFFFFFu);
  EXPECT_EQ(hesai::crc32_mpeg2(ByteView{zero, 1}), 0x4E08BFB4u);
}

// The slicing size this build was configured with (hesai/config.h): the default, or the one a
// configuration's test program (tests/CMakeLists.txt) asks for.
#if defined(HESAI_TEST_CRC_SLICING)
constexpr std::size_t kConfiguredSlices = HESAI_TEST_CRC_SLICING;
#else
constexpr std::size_t kConfiguredSlices = sizeof(void*) >= 8 ? 16 : 8;
#endif

TEST(Crc32Mpeg2, SlicingTablesAsConfigured) {
  EXPECT_EQ(hesai::kCrc32Mpeg2Slices, kConfiguredSlices);
  EXPECT_EQ(hesai::crc32_mpeg2_make_slicing_tables().size(), kConfiguredSlices);
}

TEST(Crc32Mpeg2, TablesComeFromThePolynomial) {
  constexpr auto table = hesai::crc32_mpeg2_make_table();
  static_assert(table[0] == 0);
  static_assert(table[1] == hesai::kCrc32Mpeg2Poly);  // x^32 mod P
  EXPECT_EQ(table[0x80], 0x690CE0EEu);  // x^39 mod P: 0x04C11DB7 doubled 7 times with reductions, by hand
  constexpr auto slices = hesai::crc32_mpeg2_make_slicing_tables();
  EXPECT_TRUE(slices[0] == table);
  for (std::size_t k = 1; k < slices.size(); ++k) {
    std::uint8_t msg[16] = {};
    for (std::size_t b = 0; b < 256; ++b) {
      msg[0] = static_cast<std::uint8_t>(b);
      ASSERT_EQ(slices[k][b], hesai::crc32_mpeg2_bitwise(0, msg, k + 1)) << "table " << k << " entry " << b;
    }
  }
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(HESAI_NO_GNU_EXTENSIONS)
TEST(Crc32Mpeg2, HardwareDetectionAgreesWithTheCompiler) {
  __builtin_cpu_init();
  const bool expected = __builtin_cpu_supports("pclmul") && __builtin_cpu_supports("ssse3") &&
                        __builtin_cpu_supports("sse4.1");
  EXPECT_EQ(hesai::crc32_hardware_available(), expected);
}
#endif

// The portable core (HESAI_NO_GNU_EXTENSIONS, hesai_portable_tests): the x86-64 folding and SHA-NI
// paths need GNU target attributes and <cpuid.h>, so they are left out and every path is portable.
#if defined(__x86_64__) && defined(HESAI_NO_GNU_EXTENSIONS)
TEST(Crc32Mpeg2, PortableCoreHasNoX86HardwarePaths) {
  EXPECT_FALSE(hesai::crc32_hardware_available());
  EXPECT_FALSE(hesai::sha256_hardware_available());
}
#endif

// ARMv8 with the Crypto extension (-march=armv8-a+crypto, the aarch64 cross preset): the PMULL
// folding path is chosen at compile time, so it must be the one the hardware path runs.
#if defined(__aarch64__) && (defined(__ARM_FEATURE_CRYPTO) || defined(__ARM_FEATURE_AES)) && \
    defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
TEST(Crc32Mpeg2, PmullPathIsAvailableOnArmv8Crypto) {
  EXPECT_TRUE(hesai::crc32_hardware_available());
}
#endif

// ---- Every path against the definition, every length 0..4096 at every alignment 0..15 ----

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

// A heap block of exactly `size` bytes starting on a 16-byte boundary.
struct AlignedBlock {
  explicit AlignedBlock(std::size_t size)
      : bytes(static_cast<std::uint8_t*>(::operator new[](size, std::align_val_t{16}))) {}
  ~AlignedBlock() { ::operator delete[](bytes, std::align_val_t{16}); }
  AlignedBlock(const AlignedBlock&) = delete;
  AlignedBlock& operator=(const AlignedBlock&) = delete;
  std::uint8_t* bytes;
};

class Crc32EveryPath : public testing::TestWithParam<CrcPath> {};

TEST_P(Crc32EveryPath, EqualsTheDefinitionAtEveryLengthAndAlignment) {
  constexpr std::size_t kMaxLen = 4096;
  const std::vector<std::uint8_t> pattern = pseudo_random(kMaxLen, 0xC0FFEEu);
  // reference[n]: the definition over the first n bytes, fed one byte at a time.
  std::vector<std::uint32_t> reference(kMaxLen + 1);
  reference[0] = kCrc32Mpeg2Init;
  for (std::size_t n = 1; n <= kMaxLen; ++n) {
    reference[n] = hesai::crc32_mpeg2_bitwise(reference[n - 1], &pattern[n - 1], 1);
  }
  ASSERT_EQ(hesai::crc32_mpeg2_bitwise(kCrc32Mpeg2Init, pattern.data(), kMaxLen), reference[kMaxLen]);

  const CrcPath path = GetParam();
  if (path == CrcPath::hardware || path == CrcPath::hardware_128) {
    if (const std::string why = hesai_test::crc_portable_reason(path); !why.empty()) GTEST_SKIP() << why;
  }
  // Slicing and hardware load several bytes at a time: every length at every alignment. Bitwise
  // and table read one byte at a time, so alignment cannot matter to them; they get every length
  // at alignment 0 and every alignment for lengths below 256 (the full grid costs seconds).
  // Under the sanitizers (10x slower), lengths from 512 on are checked where (n + align) % 5 == 0:
  // every length still at three or four alignments, and every (n mod 16, align) pair still met.
  const bool wide_loads = path == CrcPath::slicing || path == CrcPath::hardware;
  std::size_t checked = 0;
  for (std::size_t align = 0; align < 16; ++align) {
    const std::size_t max_len = (wide_loads || align == 0) ? kMaxLen : 255;
    for (std::size_t n = 0; n <= max_len; ++n) {
      if (kSanitized && n >= 512 && (n + align) % 5 != 0) continue;
      // The message ends exactly where its heap block ends, so that the sanitizer sees any
      // read past the end; the block is 16-aligned, so the message starts `align` past a multiple of 16.
      const AlignedBlock block(align + n);
      std::uint8_t* msg = block.bytes + align;
      if (n != 0) std::memcpy(msg, pattern.data(), n);
      ASSERT_EQ(reinterpret_cast<std::uintptr_t>(msg) % 16, align);
      ASSERT_EQ(hesai::crc32_mpeg2_update(path, kCrc32Mpeg2Init, ByteView{msg, n}), reference[n])
          << path_name(path) << " length " << n << " alignment " << align;
      ++checked;
    }
  }
  if (!kSanitized) {
    EXPECT_EQ(checked, wide_loads ? 16 * (kMaxLen + 1) : (kMaxLen + 1) + 15 * 256);
  }
}

INSTANTIATE_TEST_SUITE_P(Paths, Crc32EveryPath, testing::ValuesIn(kPaths),
                         [](const testing::TestParamInfo<CrcPath>& param_info) { return std::string(path_name(param_info.param)); });

// ---- Streaming ----

TEST(Crc32Mpeg2, StreamingSplitAtEveryOffsetEqualsOneShot) {
  const std::vector<std::uint8_t> msg = pseudo_random(1100, 7);
  const ByteView all = view(msg);
  const std::uint32_t one_shot = hesai::crc32_mpeg2_bitwise(kCrc32Mpeg2Init, msg.data(), msg.size());
  ASSERT_EQ(hesai::crc32_mpeg2(all), one_shot);
  for (std::size_t cut = 0; cut <= msg.size(); ++cut) {
    hesai::Crc32Mpeg2 crc;
    crc.update(all.sub(0, cut));
    crc.update(all.sub(cut, msg.size() - cut));
    ASSERT_EQ(crc.value(), one_shot) << "cut at " << cut;
    ASSERT_EQ(hesai::crc32_mpeg2_update(hesai::crc32_mpeg2_update(kCrc32Mpeg2Init, all.sub(0, cut)),
                                        all.sub(cut, msg.size() - cut)),
              one_shot)
        << "cut at " << cut;
    for (CrcPath p : kPaths) {
      const std::uint32_t first = hesai::crc32_mpeg2_update(p, kCrc32Mpeg2Init, all.sub(0, cut));
      ASSERT_EQ(hesai::crc32_mpeg2_update(p, first, all.sub(cut, msg.size() - cut)), one_shot)
          << path_name(p) << " cut at " << cut;
    }
  }
}

TEST(Crc32Mpeg2, StreamingInUnevenPiecesAndReset) {
  const std::vector<std::uint8_t> msg = pseudo_random(5000, 11);
  const ByteView all = view(msg);
  const std::uint32_t one_shot = hesai::crc32_mpeg2_bitwise(kCrc32Mpeg2Init, msg.data(), msg.size());
  hesai::Crc32Mpeg2 crc;
  EXPECT_EQ(crc.value(), kCrc32Mpeg2Init);
  crc.update(ByteView{kCheck, sizeof kCheck});
  EXPECT_EQ(crc.value(), 0x0376E6E7u);
  crc.reset();
  EXPECT_EQ(crc.value(), kCrc32Mpeg2Init);
  std::size_t at = 0;
  for (std::size_t piece = 0; at < msg.size(); piece = (piece * 7 + 3) % 300) {
    const std::size_t n = piece < msg.size() - at ? piece : msg.size() - at;
    crc.update(all.sub(at, n));
    at += n;
  }
  EXPECT_EQ(crc.value(), one_shot);
  crc.update(ByteView{});
  EXPECT_EQ(crc.value(), one_shot);
}

// ---- Real QT128C2X packets (protocol 3.2, flags 0x1D: UDP sequence, functional safety, signature) ----

// Offsets of protocol-notes.md (QT128C2X table) with every optional section present.
constexpr std::size_t kQtPayload = 1127;
constexpr std::size_t kBodyFrom = 12, kCrc1At = 1040;               // CRC1 over bytes 12..1039
constexpr std::size_t kFsCrcFrom = 1045, kCrc2At = 1057;            // CRC2 over 1045..1056 (after FS version)
constexpr std::size_t kTailFrom = 1061, kCrc3At = 1091;             // CRC3 over 1061..1090
static_assert(kCrc2At - kFsCrcFrom == 12 && kCrc3At + 4 + 32 == kQtPayload);

TEST(Crc32Mpeg2, Qt128C2xPacketCrcs) {
  auto packets = hesai_test::pcap_payloads("qt128c2x_dual.pcap");
  ASSERT_GE(packets.size(), 8u);
  packets.resize(8);
  for (std::size_t i = 0; i < packets.size(); ++i) {
    const std::vector<std::uint8_t>& p = packets[i];
    ASSERT_EQ(p.size(), kQtPayload) << "packet " << i;
    ASSERT_EQ(p[0], 0xEE);
    ASSERT_EQ(p[1], 0xFF);
    ASSERT_EQ(p[2], 3);        // protocol 3.2
    ASSERT_EQ(p[3], 2);
    ASSERT_EQ(p[11], 0x1D);    // flags: sequence, functional safety, signature (+ bit 4)
    const ByteView v = view(p);
    // The stored CRCs are little-endian u32 (protocol notes).
    const std::uint32_t crc1 = hesai::load_le32(&p[kCrc1At]);
    const std::uint32_t crc2 = hesai::load_le32(&p[kCrc2At]);
    const std::uint32_t crc3 = hesai::load_le32(&p[kCrc3At]);
    for (CrcPath path : kPaths) {
      EXPECT_EQ(hesai::crc32_mpeg2_update(path, kCrc32Mpeg2Init, v.sub(kBodyFrom, kCrc1At - kBodyFrom)), crc1)
          << "CRC1, packet " << i << ", " << path_name(path);
      EXPECT_EQ(hesai::crc32_mpeg2_update(path, kCrc32Mpeg2Init, v.sub(kFsCrcFrom, kCrc2At - kFsCrcFrom)), crc2)
          << "CRC2, packet " << i << ", " << path_name(path);
      EXPECT_EQ(hesai::crc32_mpeg2_update(path, kCrc32Mpeg2Init, v.sub(kTailFrom, kCrc3At - kTailFrom)), crc3)
          << "CRC3, packet " << i << ", " << path_name(path);
    }
    EXPECT_EQ(hesai::crc32_mpeg2(v.sub(kBodyFrom, kCrc1At - kBodyFrom)), crc1) << "packet " << i;

    // Any single flipped bit of the body is caught.
    std::vector<std::uint8_t> bad = p;
    bad[kBodyFrom + 100 * i] ^= static_cast<std::uint8_t>(1u << (i % 8));
    EXPECT_NE(hesai::crc32_mpeg2(view(bad).sub(kBodyFrom, kCrc1At - kBodyFrom)), crc1) << "packet " << i;
  }
  // Consecutive packets differ in body and tail, so the CRCs are not all one constant.
  EXPECT_NE(hesai::load_le32(&packets[0][kCrc1At]), hesai::load_le32(&packets[1][kCrc1At]));
}

}  // namespace
