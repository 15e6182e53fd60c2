// The rebuild of the per-spin-rate beam cache (internal to the core): for each channel of one
// firing sequence, its beam direction turned by the firing-time correction (firing time x spin
// rate) as cos(e) cos(b), cos(e) sin(b) and b in degrees, and the spread of b. Decoder::update_spin
// (sensors/decoder.cpp) runs it on every change of spin rate, which real units make every few
// hundred packets and a stream may make on every packet: no branch per channel, so that the
// compiler vectorises it, and AVX2 and AVX-512 copies of the same loop on x86-64 (vector_isa.h
// picks one; every copy gives the same bits).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "../base/compiler.h"
#include "vector_isa.h"

namespace hesai::kernels {


// Float comparisons as integer ones on the bits, exact for the finite values update_spin() sees:
// for float a and b >= 0, a >= b (a > b) exactly when bits(a) >= bits(b) (>) as int32 (a negative a has a
// negative int32), and a < 0 exactly when bits(-a) > 0 as int32 (-0 is not below 0). Written so
// because a float comparison may trap (-ftrapping-math, GCC's default), and a selection under a
// trapping comparison is not turned into a vector blend: with them the loop below is scalar code
// with two branches per channel; with these, 4 or 8 channels at a time.
// The bits of a float and back (the GNU builtin where there is one: a 4-byte memcpy to a float
// register stays a library call at -Os on Arm).
template <class To, class From>
HESAI_ALWAYS_INLINE inline To same_bits(From v) noexcept {
  static_assert(sizeof(To) == sizeof(From), "same size");
#if HESAI_GNU
  return __builtin_bit_cast(To, v);
#else
  To t;
  std::memcpy(&t, &v, sizeof t);
  return t;
#endif
}
HESAI_ALWAYS_INLINE inline std::int32_t bits(float v) noexcept { return same_bits<std::int32_t>(v); }
HESAI_ALWAYS_INLINE inline bool below_zero(float a) noexcept { return bits(-a) > 0; }
HESAI_ALWAYS_INLINE inline bool at_least(float a, float positive) noexcept { return bits(a) >= bits(positive); }
HESAI_ALWAYS_INLINE inline bool above(float a, float positive) noexcept { return bits(a) > bits(positive); }
// c ? a : b on the bits: both computed, neither moved into a branch (which GCC does to a float
// ternary's operands, and then cannot make a blend of it).
HESAI_ALWAYS_INLINE inline float select(bool c, float a, float b) noexcept {
  return same_bits<float>(bits(b) ^ ((bits(a) ^ bits(b)) & -static_cast<std::int32_t>(c)));
}

// A key whose int32 order is the order of the floats (no NaN): negative floats' magnitude bits
// reversed. -0 and +0 get keys -1 and 0.
HESAI_ALWAYS_INLINE inline std::int32_t order_key(float v) noexcept {
  const std::int32_t b = bits(v);
  return b ^ ((b >> 31) & 0x7FFFFFFF);
}
HESAI_ALWAYS_INLINE inline float from_order_key(std::int32_t k) noexcept {
  return same_bits<float>(k ^ ((k >> 31) & 0x7FFFFFFF));
}

// One firing sequence's inputs ([channel] arrays) and the cache arrays it fills.
struct BeamLoop {
  const std::int32_t* fire_ns;     // firing time offset, ns
  const float* cos_el_cos_az;      // cos(elevation) cos(azimuth offset)
  const float* cos_el_sin_az;      // cos(elevation) sin(azimuth offset)
  const float* offset_deg;         // azimuth offset, degrees
  float* dir_cos;                  // out: cos(e) cos(b)
  float* dir_sin;                  // out: cos(e) sin(b)
  float* azimuth_deg;              // out: b in [0, 360)
};

/// Fills one loop's cache for `channels` channels at spin rate `omega` (radians per ns, negative
/// counter-clockwise) by the code `isa` names (the scalar loop where it has none); lo_key and
/// hi_key take the order keys of the smallest and largest b folded into (-180, 180].
void rebuild_beams(const BeamLoop& loop, std::size_t channels, float omega, VectorIsa isa, std::int32_t& lo_key,
                   std::int32_t& hi_key) noexcept;
/// Only the spread of rebuild_beams (the same lo_key and hi_key; the cache arrays untouched), by the
/// code `isa` names; false, and nothing done, where it has none (the scalar path rebuilds whole).
bool spread_of_beams(const BeamLoop& loop, std::size_t channels, float omega, VectorIsa isa, std::int32_t& lo_key,
                     std::int32_t& hi_key) noexcept;

}  // namespace hesai::kernels
