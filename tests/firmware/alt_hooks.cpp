// The platform hooks of hesai/config.h (HESAI_CRC32_ALT, HESAI_SHA256_ALT) as a firmware provides
// them, for the image built with both (hesai_firmware_alt): each counts its calls and computes with
// the core's own software path (a real platform would drive its CRC unit or hash accelerator here).
// Compiled into every image; empty without the hooks.
#include "alt_hooks.h"

#if HESAI_CRC32_ALT && HESAI_SHA256_ALT

std::size_t firmware_crc_hook_calls = 0;
std::size_t firmware_sha_hook_blocks = 0;

extern "C" std::uint32_t hesai_crc32_mpeg2_alt(std::uint32_t crc, const std::uint8_t* data, std::size_t size) noexcept {
  ++firmware_crc_hook_calls;
  return hesai::crc32_mpeg2_update(hesai::CrcPath::slicing, crc, hesai::ByteView{data, size});
}

extern "C" void hesai_sha256_compress_alt(std::uint32_t state[8], const std::uint8_t* blocks, std::size_t nblocks) noexcept {
  firmware_sha_hook_blocks += nblocks;
  hesai::sha256_compress(hesai::Sha256Path::portable, state, blocks, nblocks);
}

#endif
