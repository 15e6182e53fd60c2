// SHA-256 (FIPS 180-4) with a caller-owned context and no heap.
//
// Contract: sha256() and sha256_compress() are reentrant and thread-safe; a Sha256 context
// (112 bytes) belongs to one thread at a time. Cost: one compression per 64 bytes, plus one or two
// for the padding; under 400 bytes of stack on Cortex-M.
#pragma once

#include <cstddef>
#include <cstdint>

#include "hesai/bytes.h"

#if HESAI_SHA256_ALT
/// The platform's SHA-256 compression function (hesai/config.h, HESAI_SHA256_ALT): `nblocks` >= 1
/// consecutive 64-byte blocks into `state`.
extern "C" void hesai_sha256_compress_alt(std::uint32_t state[8], const std::uint8_t* blocks, std::size_t nblocks) noexcept;
#endif

namespace hesai {

inline constexpr std::size_t kSha256Size = 32;       ///< digest, bytes
inline constexpr std::size_t kSha256BlockSize = 64;  ///< compression block, bytes

/// Which compression function runs: the portable C++ one, or the CPU's SHA instructions
/// (x86-64 SHA-NI, chosen at run time; ARMv8 SHA-2, chosen at compile time).
enum class Sha256Path : std::uint8_t { portable, hardware };

/// True when the hardware path can run on this CPU.
bool sha256_hardware_available() noexcept;
/// The fastest available path: hardware when available, else portable.
Sha256Path sha256_best_path() noexcept;
/// The compression function sha256_best_path() runs on this CPU: "sha-ni" (x86-64),
/// "armv8-sha2" (AArch64), "alt" (the platform's function, HESAI_SHA256_ALT) or "portable". A
/// static string.
const char* sha256_path_name() noexcept;

/// Runs the compression function over `nblocks` consecutive 64-byte blocks, updating `state`.
/// `hardware` falls back to portable when the CPU lacks the instructions. For tests and benchmarks.
void sha256_compress(Sha256Path path, std::uint32_t state[8], const std::uint8_t* blocks,
                     std::size_t nblocks) noexcept;

/// Incremental SHA-256. Feed bytes with update(), read the digest with finish().
class Sha256 {
 public:
  /// A context on sha256_best_path().
  Sha256() noexcept;
  /// A context on `path` (hardware falls back to portable when unavailable).
  explicit Sha256(Sha256Path path) noexcept;
  Sha256(const Sha256&) noexcept = default;
  Sha256& operator=(const Sha256&) noexcept = default;
  /// Wipes the state and the buffered bytes.
  ~Sha256();

  /// Starts a new message (same path); wipes the buffered bytes.
  void reset() noexcept;
  /// Starts a new message on `path` (as a new Sha256(path) would, without a temporary).
  void reset(Sha256Path path) noexcept;
  /// Absorbs `data` (any length, split anywhere).
  void update(ByteView data) noexcept;
  /// Writes the 32-byte digest of everything absorbed since the last reset, then resets.
  void finish(std::uint8_t out[kSha256Size]) noexcept;

  Sha256Path path() const noexcept { return path_; }

 private:
  std::uint32_t state_[8];
  std::uint64_t length_;                    // bytes absorbed since reset
  std::uint8_t block_[kSha256BlockSize];    // the incomplete block: length_ % 64 bytes
  Sha256Path path_;
};

/// One-shot SHA-256 of `data` into `out` (32 bytes).
void sha256(ByteView data, std::uint8_t out[kSha256Size]) noexcept;

}  // namespace hesai
