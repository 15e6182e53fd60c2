// A fixed queue of raw packets, for the packets of a stream whose direction of rotation is not yet
// known (RotationDetector): held, they can be decoded in the right direction once it is.
//
// Contract: a HeldPackets<N> holds up to N packets of at most kMaxPacketBytes each, with a caller's
// tag per packet (an index, a receive time), in its own storage (N x 1 282 bytes on a 64-bit
// target, and two counters); no heap; one thread; constant work per call but push(), which
// copies the packet.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "hesai/bytes.h"
#include "hesai/detail/pandar40_packet.h"
#include "hesai/detail/pandar64_packet.h"
#include "hesai/detail/qt128_packet.h"
#include "hesai/detail/qt64_packet.h"
#include "hesai/detail/xt_packet.h"

namespace hesai {

/// The longest point-cloud packet any supported model sends: a Pandar40P with the UDP sequence,
/// 1 266 bytes. Decoder::decode() accepts no longer one.
inline constexpr std::size_t kMaxPacketBytes = pandar40::kPandar40PSequenceBytes;
static_assert(pandar64::kSequencePacketBytes <= kMaxPacketBytes, "Pandar64");
static_assert(qt128::Layout::from_header(qt128::kChannels, 0xFF).total <= kMaxPacketBytes, "QT128C2X, every flag");
static_assert(qt64::kSequencePacketBytes <= kMaxPacketBytes, "PandarQT64");
static_assert(xt::packet_bytes(32, 8) <= kMaxPacketBytes, "PandarXT32, the longest XT");

/// First in, first out: push() at the back, front() and pop_front() at the front.
template <std::size_t Capacity>
class HeldPackets {
  static_assert(Capacity > 0, "HeldPackets needs room for one packet");

 public:
  static constexpr std::size_t kCapacity = Capacity;

  /// Copies `packet` in at the back, with `tag`. False, and nothing held, when full or when the
  /// packet is longer than kMaxPacketBytes.
  [[nodiscard]] bool push(ByteView packet, std::uint64_t tag = 0) noexcept {
    if (count_ == Capacity || packet.size > kMaxPacketBytes) return false;
    const std::size_t at = (head_ + count_) % Capacity;
    if (packet.size != 0) std::memcpy(bytes_[at], packet.data, packet.size);
    sizes_[at] = packet.size;
    tags_[at] = tag;
    ++count_;
    return true;
  }
  /// The oldest packet held; valid until the next pop_front() or clear(). Empty when none is held.
  ByteView front() const noexcept { return count_ == 0 ? ByteView{} : ByteView{bytes_[head_], sizes_[head_]}; }
  /// The oldest packet's tag (0 when none is held).
  std::uint64_t front_tag() const noexcept { return count_ == 0 ? 0 : tags_[head_]; }
  /// Drops the oldest packet (nothing when none is held).
  void pop_front() noexcept {
    if (count_ == 0) return;
    head_ = (head_ + 1) % Capacity;
    --count_;
  }
  /// Drops every packet.
  void clear() noexcept { head_ = count_ = 0; }

  std::size_t size() const noexcept { return count_; }
  bool empty() const noexcept { return count_ == 0; }
  bool full() const noexcept { return count_ == Capacity; }

 private:
  std::uint8_t bytes_[Capacity][kMaxPacketBytes];
  std::size_t sizes_[Capacity] = {};
  std::uint64_t tags_[Capacity] = {};
  std::size_t head_ = 0;
  std::size_t count_ = 0;
};

}  // namespace hesai
