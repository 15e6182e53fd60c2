// Constant-time comparison and wiping of secrets.
#pragma once

#include <cstddef>
#include <cstdint>

namespace hesai {

/// True when the `n` bytes at `a` and `b` are equal. The time taken depends on `n` only, never
/// on where the bytes differ: use it to compare MACs.
bool constant_time_equal(const std::uint8_t* a, const std::uint8_t* b, std::size_t n) noexcept;

/// Sets `n` bytes at `p` to zero in a way the compiler cannot drop as a dead store, even when
/// the memory is about to go out of scope. Use it on keys and intermediate key material.
void secure_wipe(void* p, std::size_t n) noexcept;

}  // namespace hesai
