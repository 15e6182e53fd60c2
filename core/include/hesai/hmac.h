// HMAC-SHA256 (RFC 2104) with the key schedule computed once per key.
//
// Contract: an HmacSha256Key (224 bytes) is written by set() and wipe() only; between those it
// is read-only, and HmacSha256 contexts (120 bytes) in any number of threads may share it. Each
// context belongs to one thread. hmac_sha256() is reentrant. No heap.
#pragma once

#include <cstddef>
#include <cstdint>

#include "hesai/bytes.h"
#include "hesai/ct.h"
#include "hesai/sha256.h"

namespace hesai {

/// A key made ready for HMAC-SHA256: the SHA-256 states after absorbing key^ipad and key^opad.
/// Compute it once per key (two compressions, three for keys longer than 64 bytes); every
/// message then starts from a copy. It holds key material: wiped on destruction.
class HmacSha256Key {
 public:
  /// The empty key.
  HmacSha256Key() noexcept { set(ByteView{}); }
  explicit HmacSha256Key(ByteView key, Sha256Path path = sha256_best_path()) noexcept {
    set(key, path);
  }
  HmacSha256Key(const HmacSha256Key&) noexcept = default;
  HmacSha256Key& operator=(const HmacSha256Key&) noexcept = default;
  ~HmacSha256Key() { wipe(); }

  /// Prepares `key` (any length; keys over 64 bytes are hashed first), hashing on `path`.
  void set(ByteView key, Sha256Path path = sha256_best_path()) noexcept;
  /// Erases the key states. set() a key again before the next use.
  void wipe() noexcept;

 private:
  friend class HmacSha256;
  Sha256 inner_;
  Sha256 outer_;
};

/// One HMAC-SHA256 computation under a prepared key. The key must outlive this object.
class HmacSha256 {
 public:
  explicit HmacSha256(const HmacSha256Key& key) noexcept : key_(&key), inner_(key.inner_) {}

  /// Absorbs message bytes (any length, split anywhere).
  void update(ByteView data) noexcept { inner_.update(data); }
  /// Writes the 32-byte MAC, then starts a new message under the same key.
  void finish(std::uint8_t out[kSha256Size]) noexcept;

 private:
  const HmacSha256Key* key_;
  Sha256 inner_;
};

/// One-shot HMAC-SHA256 of `msg` under `key` into `out` (32 bytes).
void hmac_sha256(ByteView key, ByteView msg, std::uint8_t out[kSha256Size]) noexcept;

}  // namespace hesai
