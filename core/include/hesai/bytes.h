// Byte views, explicit-byte-order loads and a bounded reader.
#pragma once

#include <cstddef>
#include <cstdint>

#include "hesai/config.h"
#include "hesai/error.h"

namespace hesai {

/// A read-only view of bytes: pointer and size. The caller owns the bytes.
struct ByteView {
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;

  constexpr ByteView() = default;
  constexpr ByteView(const std::uint8_t* d, std::size_t n) : data(d), size(n) {}

  /// The bytes [offset, offset + count); the caller has checked the range (HESAI_ASSERT).
  constexpr ByteView sub(std::size_t offset, std::size_t count) const {
    HESAI_ASSERT(offset <= size && count <= size - offset);
    return {data + offset, count};
  }
  constexpr const std::uint8_t& operator[](std::size_t i) const { return data[i]; }
};

// Loads from bytes with shifts: the byte order is named at every read and no wire field is
// read through a cast, so these are correct on big-endian and alignment-faulting targets.
// Compilers fold them into single loads where the target allows.
constexpr std::uint16_t load_le16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
constexpr std::uint16_t load_be16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>((p[0] << 8) | p[1]);
}
constexpr std::uint32_t load_le32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}
constexpr std::uint32_t load_be32(const std::uint8_t* p) {
  return (static_cast<std::uint32_t>(p[0]) << 24) | (static_cast<std::uint32_t>(p[1]) << 16) |
         (static_cast<std::uint32_t>(p[2]) << 8) | static_cast<std::uint32_t>(p[3]);
}
constexpr std::uint64_t load_le64(const std::uint8_t* p) {
  return static_cast<std::uint64_t>(load_le32(p)) | (static_cast<std::uint64_t>(load_le32(p + 4)) << 32);
}
constexpr std::uint64_t load_be64(const std::uint8_t* p) {
  return (static_cast<std::uint64_t>(load_be32(p)) << 32) | static_cast<std::uint64_t>(load_be32(p + 4));
}
constexpr void store_le16(std::uint8_t* p, std::uint16_t v) {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
constexpr void store_le32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
constexpr void store_be32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (24 - 8 * i));
}
constexpr void store_be64(std::uint8_t* p, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) p[i] = static_cast<std::uint8_t>(v >> (56 - 8 * i));
}

/// Bounded reader over a ByteView. A read that would pass the end returns false, records
/// Error::truncated and leaves the cursor where it was; reads after that still work if they fit.
class ByteReader {
 public:
  constexpr explicit ByteReader(ByteView v) : view_(v) {}

  constexpr std::size_t position() const { return pos_; }
  constexpr std::size_t remaining() const { return view_.size - pos_; }
  /// Error::truncated once any read has failed, Error::ok otherwise.
  [[nodiscard]] constexpr Error error() const { return error_; }

  constexpr bool u8(std::uint8_t& out) { return fixed(1) && (out = view_.data[take(1)], true); }
  constexpr bool le16(std::uint16_t& out) { return fixed(2) && (out = load_le16(view_.data + take(2)), true); }
  constexpr bool be16(std::uint16_t& out) { return fixed(2) && (out = load_be16(view_.data + take(2)), true); }
  constexpr bool le32(std::uint32_t& out) { return fixed(4) && (out = load_le32(view_.data + take(4)), true); }
  constexpr bool be32(std::uint32_t& out) { return fixed(4) && (out = load_be32(view_.data + take(4)), true); }
  constexpr bool le64(std::uint64_t& out) { return fixed(8) && (out = load_le64(view_.data + take(8)), true); }
  constexpr bool be64(std::uint64_t& out) { return fixed(8) && (out = load_be64(view_.data + take(8)), true); }

  /// The next `n` bytes as a view (no copy).
  constexpr bool bytes(std::size_t n, ByteView& out) {
    if (!fixed(n)) return false;
    out = view_.sub(pos_, n);
    pos_ += n;
    return true;
  }
  constexpr bool skip(std::size_t n) { return fixed(n) && (take(n), true); }
  /// Moves the cursor to an absolute offset (<= size).
  constexpr bool seek(std::size_t offset) {
    if (offset > view_.size) return fail();
    pos_ = offset;
    return true;
  }

 private:
  constexpr bool fail() {
    error_ = Error::truncated;
    return false;
  }
  // Overflow-safe: n <= size - pos, with pos <= size always.
  constexpr bool fixed(std::size_t n) { return n <= view_.size - pos_ ? true : fail(); }
  constexpr std::size_t take(std::size_t n) {
    std::size_t at = pos_;
    pos_ += n;
    return at;
  }

  ByteView view_;
  std::size_t pos_ = 0;
  Error error_ = Error::ok;
};

}  // namespace hesai
