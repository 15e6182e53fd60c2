#include "alloc_counter.h"

#include <atomic>
#include <cstdlib>
#include <new>

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer)
#define HESAI_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define HESAI_SANITIZED 1
#endif

namespace {
std::atomic<std::size_t> g_allocations{0};
}

namespace hesai_test {
std::size_t allocation_count() { return g_allocations.load(); }
#if defined(HESAI_SANITIZED) || !defined(__GLIBC__)
bool counts_malloc() { return false; }
#else
bool counts_malloc() { return true; }
#endif
}  // namespace hesai_test

#if !defined(HESAI_SANITIZED) && defined(__GLIBC__)
// glibc lets a program interpose malloc; forward to its own implementation.
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void __libc_free(void*);
void* malloc(std::size_t n) {
  g_allocations.fetch_add(1);
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t m) {
  g_allocations.fetch_add(1);
  return __libc_calloc(n, m);
}
void* realloc(void* p, std::size_t n) {
  g_allocations.fetch_add(1);
  return __libc_realloc(p, n);
}
void free(void* p) { __libc_free(p); }
}
#endif

// operator new in every form counts itself (and, through malloc, may count twice: fine, any
// non-zero count fails the test).
void* operator new(std::size_t n) {
  g_allocations.fetch_add(1);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1);
  return std::malloc(n == 0 ? 1 : n);
}
void* operator new[](std::size_t n, const std::nothrow_t& t) noexcept { return operator new(n, t); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
