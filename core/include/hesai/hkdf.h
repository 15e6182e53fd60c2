// HKDF-SHA256 (RFC 5869) and the Hesai session-key derivation built on it.
//
// Contract: every function is reentrant and thread-safe, writes only its output, and wipes its
// intermediate key material. Under 1 KiB of stack on Cortex-M; no heap.
#pragma once

#include <cstddef>
#include <cstdint>

#include "hesai/bytes.h"
#include "hesai/error.h"
#include "hesai/sha256.h"

namespace hesai {

/// Longest HKDF-SHA256 output: 255 blocks of 32 bytes.
inline constexpr std::size_t kHkdfSha256MaxLength = 255 * kSha256Size;

/// HKDF-Extract: prk = HMAC-SHA256(salt, ikm). An empty salt acts as 32 zero bytes.
void hkdf_sha256_extract(ByteView salt, ByteView ikm, std::uint8_t prk[kSha256Size]) noexcept;

/// HKDF-Expand: `len` bytes of output keying material from `prk` and `info` into `out`.
/// Error::invalid_argument when len > 8160 (255 * 32).
[[nodiscard]] Error hkdf_sha256_expand(ByteView prk, ByteView info, std::uint8_t* out, std::size_t len) noexcept;

/// Extract then expand. Error::invalid_argument when len > 8160.
[[nodiscard]] Error hkdf_sha256(ByteView salt, ByteView ikm, ByteView info, std::uint8_t* out,
                  std::size_t len) noexcept;

/// Shortest and longest shared secret the Hesai session-key derivation accepts, bytes.
inline constexpr std::size_t kHesaiSecretMin = 8;
inline constexpr std::size_t kHesaiSecretMax = 32;

/// The Hesai session key: HKDF-SHA256 with IKM = `secret` (8 to 32 bytes), salt =
/// lidar_random || client_random (64 bytes), info = "finish session key" (18 ASCII bytes),
/// L = 32. Error::invalid_argument for a secret of another length (then `key` is untouched).
[[nodiscard]] Error hesai_session_key(ByteView secret, const std::uint8_t lidar_random[32],
                        const std::uint8_t client_random[32], std::uint8_t key[32]) noexcept;

}  // namespace hesai
