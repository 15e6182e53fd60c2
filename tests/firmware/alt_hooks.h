// Counters of the platform hooks in the image built with HESAI_CRC32_ALT and HESAI_SHA256_ALT.
#pragma once

#include <cstddef>

#include "hesai/crc32.h"
#include "hesai/sha256.h"

#if HESAI_CRC32_ALT && HESAI_SHA256_ALT
extern std::size_t firmware_crc_hook_calls;   ///< hesai_crc32_mpeg2_alt calls
extern std::size_t firmware_sha_hook_blocks;  ///< blocks given to hesai_sha256_compress_alt
#endif
