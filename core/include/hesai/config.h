// Build configuration of the core, in the manner of Mbed TLS's mbedtls_config.h and libcanard's
// CANARD_CONFIG_HEADER: a firmware build trades flash for speed and switches features off
// without patching sources.
//
// To configure, define HESAI_CONFIG_HEADER as the name of your header, e.g.
//     -DHESAI_CONFIG_HEADER='"my_hesai_config.h"'   (CMake: -DHESAI_CONFIG_HEADER=/path/to/it.h)
// It is included first and may define any macro below (or define them with -D); the rest take the
// defaults here. The core and every file that includes its headers must see the same
// configuration (sizeof(Decoder) and kCrc32Mpeg2Slices depend on it): the CMake target carries
// the definitions to its users.
#pragma once

#include <cstdint>

#if defined(HESAI_CONFIG_HEADER)
#include HESAI_CONFIG_HEADER
#endif

/// HESAI_CRC_SLICING: tables of the CRC-32/MPEG-2 slicing path, 1 KiB of flash each.
///  16: slicing-by-16, 16 KiB, the fastest (default on 64-bit targets);
///   8: slicing-by-8, 8 KiB (default on 32-bit targets);
///   4: slicing-by-4, 4 KiB;
///   1: the single byte table, 1 KiB: one lookup per byte.
#if !defined(HESAI_CRC_SLICING)
#if SIZE_MAX > 0xFFFFFFFFu
#define HESAI_CRC_SLICING 16
#else
#define HESAI_CRC_SLICING 8
#endif
#endif
#if HESAI_CRC_SLICING != 16 && HESAI_CRC_SLICING != 8 && HESAI_CRC_SLICING != 4 && HESAI_CRC_SLICING != 1
#error "HESAI_CRC_SLICING must be 16, 8, 4 or 1"
#endif

/// HESAI_SIGNATURE: 1 (default) verifies QT128 HMAC-SHA256 signatures under a session key. 0 leaves
/// the decoder without SHA-256/HMAC code and without the key state: a signed packet is still
/// decoded and reported SignatureStatus::unverified, and Decoder::set_session_key() returns
/// Error::unsupported_feature. (sha256.h, hmac.h and hkdf.h stay usable on their own.)
#if !defined(HESAI_SIGNATURE)
#define HESAI_SIGNATURE 1
#endif
#if HESAI_SIGNATURE != 0 && HESAI_SIGNATURE != 1
#error "HESAI_SIGNATURE must be 0 or 1"
#endif

/// HESAI_ASSERT(condition): called on the core's internal contracts (a range the caller has
/// checked, a buffer large enough), never on bad input, which is an Error. Default: nothing
/// runs, the condition is only compiled. A firmware build may define it to trap, e.g.
///     #define HESAI_ASSERT(x) ((x) ? (void)0 : my_fault(__FILE__, __LINE__))
/// It is used in constexpr functions: keep the passing branch a constant expression, as above.
#if !defined(HESAI_ASSERT)
#define HESAI_ASSERT(x) ((void)sizeof((x) ? 1 : 0))
#endif

/// HESAI_CRC32_ALT: define it to 1 when the platform computes CRC-32/MPEG-2 itself, as Mbed TLS's
/// MBEDTLS_SHA256_ALT lets a platform replace a primitive. The platform then provides
///     extern "C" uint32_t hesai_crc32_mpeg2_alt(uint32_t crc, const uint8_t* data, size_t size);
/// which feeds `size` bytes (size >= 1) into the register `crc` (most significant bit first, no
/// reflection, no final xor; the register starts at 0xFFFFFFFF) and returns the new register. Every
/// CRC the decoder checks (crc32_mpeg2(), crc32_mpeg2_update() and CrcPath::hardware) then runs it;
/// the other CrcPath values keep the core's own code. An STM32 CRC unit in its reset configuration
/// (polynomial 0x04C11DB7, initial value all ones, no reversal, no final xor) computes exactly
/// this, a 32-bit word at a time.
#if !defined(HESAI_CRC32_ALT)
#define HESAI_CRC32_ALT 0
#endif
#if HESAI_CRC32_ALT != 0 && HESAI_CRC32_ALT != 1
#error "HESAI_CRC32_ALT must be 0 or 1"
#endif

/// HESAI_SHA256_ALT: define it to 1 when the platform computes the SHA-256 compression function
/// (a hash accelerator). The platform then provides
///     extern "C" void hesai_sha256_compress_alt(uint32_t state[8], const uint8_t* blocks, size_t nblocks);
/// which runs the FIPS 180-4 compression over `nblocks` (>= 1) consecutive 64-byte blocks, updating
/// `state`. Sha256Path::hardware (the default path of SHA-256, HMAC, HKDF and the signature check)
/// then runs it; Sha256Path::portable keeps the core's own code.
#if !defined(HESAI_SHA256_ALT)
#define HESAI_SHA256_ALT 0
#endif
#if HESAI_SHA256_ALT != 0 && HESAI_SHA256_ALT != 1
#error "HESAI_SHA256_ALT must be 0 or 1"
#endif

/// HESAI_NO_GNU_EXTENSIONS: define it to take the ISO C++ path of every GNU extension the core
/// uses (inline-asm barriers, always_inline, the x86-64 SHA-NI and PCLMULQDQ paths) with a
/// compiler that defines __GNUC__ but lacks them. Other compilers take those paths anyway.
