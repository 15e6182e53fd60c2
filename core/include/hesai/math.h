// Sine and cosine without the C library: the core runs where there is no libm.
#pragma once

#include <cstdint>

namespace hesai {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDegToRad = kPi / 180.0;

struct SinCos {
  double sin;
  double cos;
};

namespace detail {
// Taylor series of sin and cos on |x| <= pi/4; the first omitted terms are below 2e-15 there.
constexpr double sin_reduced(double x) {
  const double x2 = x * x;
  return x * (1 - x2 / 6 * (1 - x2 / 20 * (1 - x2 / 42 * (1 - x2 / 72 * (1 - x2 / 110 * (1 - x2 / 156))))));
}
constexpr double cos_reduced(double x) {
  const double x2 = x * x;
  return 1 - x2 / 2 * (1 - x2 / 12 * (1 - x2 / 30 * (1 - x2 / 56 * (1 - x2 / 90 * (1 - x2 / 132 * (1 - x2 / 182))))));
}
}  // namespace detail

/// sin and cos of an angle in degrees, within 5e-14 of libm, for any finite angle whose magnitude is
/// below 1e15. The reduction to one octant is done in degrees, where multiples of 90 are exact.
constexpr SinCos sin_cos_deg(double deg) {
  // Bring deg into [0, 360).
  if (deg < 0 || deg >= 360) {
    const double turns = deg / 360.0;
    long long whole = static_cast<long long>(turns);
    if (static_cast<double>(whole) > turns) --whole;  // floor for negative angles
    deg -= static_cast<double>(whole) * 360.0;
    if (deg < 0) deg += 360.0;
    if (deg >= 360.0) deg -= 360.0;
  }
  // Quadrant q and remainder r in [-45, 45]: deg = 90 q + r.
  int q = static_cast<int>((deg + 45.0) / 90.0);
  const double r = (deg - 90.0 * q) * kDegToRad;
  const double s = detail::sin_reduced(r);
  const double c = detail::cos_reduced(r);
  switch (q & 3) {
    case 0: return {s, c};
    case 1: return {c, -s};
    case 2: return {-s, -c};
    default: return {-c, s};
  }
}

/// sin and cos in single precision.
struct SinCosF {
  float sin;
  float cos;
};

/// sin and cos of an angle in hundredths of a degree (a block azimuth as sent), in single
/// precision only (no double arithmetic: a Cortex-M4F's FPU has none), within 2 float ulps of the
/// exact values. The reduction to [-45, 45] degrees is exact, in integers.
constexpr SinCosF sin_cos_centideg(std::uint16_t centideg) {
  const int q = (centideg + 4500) / 9000;  // quadrant: centideg = 9000 q + r, r in [-4500, 4500)
  const float x = static_cast<float>(centideg - 9000 * q) * static_cast<float>(kPi / 18000.0);
  const float x2 = x * x;
  // Taylor series on |x| <= pi/4; the first omitted terms are below 3e-10.
  const float s = x * (1.0f - x2 * (1.0f / 6) * (1.0f - x2 * (1.0f / 20) * (1.0f - x2 * (1.0f / 42) * (1.0f - x2 * (1.0f / 72)))));
  const float c = 1.0f - x2 * 0.5f * (1.0f - x2 * (1.0f / 12) * (1.0f - x2 * (1.0f / 30) * (1.0f - x2 * (1.0f / 56) * (1.0f - x2 * (1.0f / 90)))));
  switch (q & 3) {
    case 0: return {s, c};
    case 1: return {c, -s};
    case 2: return {-s, -c};
    default: return {-c, s};
  }
}

static_assert(sin_cos_deg(90).sin == 1.0 && sin_cos_deg(180).cos == -1.0);
static_assert(sin_cos_deg(30).sin > 0.4999999999999 && sin_cos_deg(30).sin < 0.5000000000001);

}  // namespace hesai
