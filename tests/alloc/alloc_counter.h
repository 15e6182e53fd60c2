// Counts every heap allocation of the process (operator new in all its forms, and malloc,
// calloc and realloc where the C library lets us interpose them).
#pragma once

#include <cstddef>

namespace hesai_test {

/// Heap allocations since the program started.
std::size_t allocation_count();
/// True when malloc itself is counted (not under a sanitizer, which owns malloc).
bool counts_malloc();

/// Runs `f` and returns how many allocations it made.
template <class F>
std::size_t allocations_during(F&& f) {
  const std::size_t before = allocation_count();
  f();
  return allocation_count() - before;
}

}  // namespace hesai_test
