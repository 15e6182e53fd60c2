// The core with both platform hooks (hesai/config.h HESAI_CRC32_ALT, HESAI_SHA256_ALT), as a
// firmware with a CRC unit and a hash accelerator would build it: ctest alt.*, whose program
// (tests/config/alt_test.cpp) provides the two functions.
#pragma once

#define HESAI_CRC32_ALT 1
#define HESAI_SHA256_ALT 1
