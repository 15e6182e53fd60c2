// Counters that stop at their largest value instead of wrapping (issue #32: every counter
// saturates; none wraps). A saturated counter is no longer exact, so it is never decremented.
#pragma once

#include <cstdint>

namespace hesai {

/// Adds `n` to `counter`, stopping at the largest value.
constexpr void saturating_add(std::uint64_t& counter, std::uint64_t n) noexcept {
  counter = counter > UINT64_MAX - n ? UINT64_MAX : counter + n;
}
/// Adds `n` to a 32-bit `counter`, stopping at its largest value.
constexpr void saturating_add(std::uint32_t& counter, std::uint32_t n) noexcept {
  counter = counter > UINT32_MAX - n ? UINT32_MAX : counter + n;
}
/// One more, stopping at the largest value.
constexpr void saturating_increment(std::uint64_t& counter) noexcept {
  if (counter != UINT64_MAX) ++counter;
}
/// `n` less (at most down to 0), unless the counter saturated.
constexpr void saturating_subtract(std::uint64_t& counter, std::uint64_t n) noexcept {
  if (counter != UINT64_MAX) counter = counter > n ? counter - n : 0;
}
/// `total` moved by the change of a part from `before` to `after` (either way), saturating.
constexpr void saturating_follow(std::uint64_t& total, std::uint64_t before, std::uint64_t after) noexcept {
  if (after >= before) saturating_add(total, after - before);
  else saturating_subtract(total, before - after);
}

static_assert([] {
  std::uint64_t a = UINT64_MAX - 1, b = UINT64_MAX, c = 3;
  saturating_add(a, 5);
  saturating_subtract(b, 1);
  saturating_increment(b);
  saturating_subtract(c, 5);
  return a == UINT64_MAX && b == UINT64_MAX && c == 0;
}(), "a counter stops at its largest value and, saturated, stays there");

}  // namespace hesai
