// Zero-allocation proof for CRC-32/MPEG-2: every path, the one-shot and streaming API, and the
// first call (which detects the CPU on x86-64).
#include <gtest/gtest.h>

#include <cstdint>

#include "alloc_counter.h"
#include "hesai/crc32.h"

TEST(ZeroAllocation, Crc32Mpeg2EveryPath) {
  static std::uint8_t buf[4096];
  for (std::size_t i = 0; i < sizeof buf; ++i) buf[i] = static_cast<std::uint8_t>(i * 131u + 7u);
  volatile std::uint32_t sink = 0;
  const std::size_t n = hesai_test::allocations_during([&] {
    sink = sink ^ (hesai::crc32_hardware_available() ? 1u : 0u);
    for (std::size_t len : {std::size_t{0}, std::size_t{9}, std::size_t{63}, std::size_t{64}, std::size_t{1028},
                            sizeof buf - 3}) {
      const hesai::ByteView v{buf + 3, len};
      sink = sink ^ hesai::crc32_mpeg2(v);
      sink = sink ^ hesai::crc32_mpeg2_update(sink, v);
      for (hesai::CrcPath p : {hesai::CrcPath::bitwise, hesai::CrcPath::table, hesai::CrcPath::slicing,
                               hesai::CrcPath::hardware, hesai::CrcPath::hardware_128}) {
        sink = sink ^ hesai::crc32_mpeg2_update(p, hesai::kCrc32Mpeg2Init, v);
      }
      hesai::Crc32Mpeg2 crc;
      crc.update(v.sub(0, len / 2));
      crc.update(v.sub(len / 2, len - len / 2));
      sink = sink ^ crc.value();
      crc.reset();
    }
  });
  EXPECT_EQ(n, 0u);
}
