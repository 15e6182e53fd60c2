// Little-endian fields of binary records (PCD, PLY, PointCloud2) stored at any alignment. On a
// little-endian host a store is one fixed-size memcpy, which the compiler makes one move; a
// big-endian host (s390x runs the tests) stores the bytes by shifts. Either way the bytes in the
// file are the same.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

namespace hesai {
namespace port {

#if defined(__BYTE_ORDER__) && defined(__ORDER_LITTLE_ENDIAN__)
inline constexpr bool kLittleEndianHost = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;
#else
inline constexpr bool kLittleEndianHost = false;  // unknown: the byte-by-byte stores, right everywhere
#endif

static_assert(std::numeric_limits<float>::is_iec559 && sizeof(float) == 4, "IEEE 754 binary32 float");
static_assert(std::numeric_limits<double>::is_iec559 && sizeof(double) == 8, "IEEE 754 binary64 double");

/// Stores `v` (an integer or an IEEE 754 float or double) at `out` in little-endian byte order.
template <typename T>
inline void store_le(std::uint8_t* out, T v) noexcept {
  static_assert(std::is_arithmetic<T>::value, "a number");
  if constexpr (kLittleEndianHost) {
    std::memcpy(out, &v, sizeof v);
  } else {
    using U = std::conditional_t<sizeof(T) == 1, std::uint8_t,
                                 std::conditional_t<sizeof(T) == 2, std::uint16_t,
                                                    std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>>;
    static_assert(sizeof(U) == sizeof(T), "1, 2, 4 or 8 bytes");
    U u = 0;
    std::memcpy(&u, &v, sizeof v);
    for (std::size_t i = 0; i < sizeof u; ++i) out[i] = static_cast<std::uint8_t>(u >> (8 * i));
  }
}

}  // namespace port
}  // namespace hesai
