// The default configuration (hesai/config.h with no HESAI_CONFIG_HEADER), as the main build uses
// it. The other configurations are tested by hesai_minimal_tests and hesai_crc_slicing<N>_tests.
#include <gtest/gtest.h>

#include "hesai/config.h"
#include "hesai/crc32.h"
#include "hesai/decoder.h"

namespace {

TEST(Config, Defaults) {
  EXPECT_EQ(HESAI_SIGNATURE, 1);
  EXPECT_EQ(hesai::kCrc32Mpeg2Slices, sizeof(void*) >= 8 ? 16u : 8u);  // 16 KiB on 64-bit, 8 KiB on 32-bit
}

TEST(Config, DefaultAssertRunsNothing) {
  int calls = 0;
  auto broken = [&calls] { return ++calls < 0; };
  HESAI_ASSERT(broken());  // compiled, never evaluated
  EXPECT_EQ(calls, 0);
}

TEST(Config, SessionKeyIsSupported) {
  hesai::Decoder dec(hesai::Model::qt128c2x);
  const std::uint8_t key[32] = {7};
  EXPECT_EQ(dec.set_session_key(key), hesai::Error::ok);
}

}  // namespace
