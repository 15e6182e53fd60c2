// Compiler extensions the core uses where they exist, each with a portable path (private to the core).
//
// HESAI_GNU is 1 with GNU C++ (GCC, Clang and compilers that emulate them) unless
// HESAI_NO_GNU_EXTENSIONS is defined. It enables: the empty-asm optimisation barriers of ct.cpp
// and of crc/crc32.cpp's Thumb-2 slicing tables,
// always_inline in sha256.cpp, the kernels (scalar_loops.h, neon_units.h) and
// kernels/beam_cache.h (with __builtin_bit_cast there), noinline for size in
// sensors/block_points.h, a __builtin_memcpy word store in kernels/scalar_loops.h, and the
// x86-64 SHA-NI, PCLMULQDQ and vector-kernel paths (target attributes, <cpuid.h>). Any other compiler takes the portable paths, which ISO C++17 alone defines; CI
// compiles and tests them by defining HESAI_NO_GNU_EXTENSIONS (the hesai_portable_tests target).
#pragma once

#include "hesai/config.h"  // HESAI_NO_GNU_EXTENSIONS may come from the configuration header

#if (defined(__GNUC__) || defined(__clang__)) && !defined(HESAI_NO_GNU_EXTENSIONS)
#define HESAI_GNU 1
#else
#define HESAI_GNU 0
#endif

/// Forces inlining where the compiler can be told (a speed hint only: plain `inline` elsewhere).
#if HESAI_GNU
#define HESAI_ALWAYS_INLINE __attribute__((always_inline))
#else
#define HESAI_ALWAYS_INLINE
#endif

/// Keeps a function out of line when optimising for size (-Os), where the compiler can be told:
/// the callers then share one copy (a flash saving only; optimising for speed it may be inlined).
#if HESAI_GNU && defined(__OPTIMIZE_SIZE__)
#define HESAI_NOINLINE_FOR_SIZE __attribute__((noinline))
#else
#define HESAI_NOINLINE_FOR_SIZE
#endif
