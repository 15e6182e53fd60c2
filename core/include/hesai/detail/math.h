// Sine and cosine without the C library: the core runs where there is no libm.
#pragma once

#include <array>
#include <cstddef>
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

namespace detail {
// sin of 0, 1, ..., 90 degrees, rounded to float (364 bytes), computed at compile time.
constexpr std::array<float, 91> sin_whole_degrees() {
  std::array<float, 91> t{};
  for (std::size_t d = 0; d <= 90; ++d) t[d] = static_cast<float>(sin_cos_deg(static_cast<double>(d)).sin);
  return t;
}
inline constexpr std::array<float, 91> kSinWholeDegrees = sin_whole_degrees();
}  // namespace detail

/// sin and cos of an angle in hundredths of a degree (a block azimuth as sent), in single
/// precision only (no double arithmetic: a Cortex-M4F's FPU has none), within 3e-7 of the exact
/// values: the whole degrees' sine and cosine from a table, the hundredths (below 0.0173 rad) by
/// a short series (first omitted terms below 2e-11), joined by the angle-sum identities. A short
/// dependent chain: it runs once per block.
constexpr SinCosF sin_cos_centideg(std::uint16_t centideg) {
  const unsigned deg = centideg / 100u;
  const float f = static_cast<float>(centideg % 100u) * static_cast<float>(kPi / 18000.0);
  const float f2 = f * f;
  const float sin_f = f - f * f2 * (1.0f / 6);
  const float cos_f = 1.0f - f2 * 0.5f + f2 * f2 * (1.0f / 24);
  const unsigned d = deg % 90u;  // deg = 90 q + d
  const float sin_d = detail::kSinWholeDegrees[d];
  const float cos_d = detail::kSinWholeDegrees[90 - d];
  const float s = sin_d * cos_f + cos_d * sin_f;
  const float c = cos_d * cos_f - sin_d * sin_f;
  switch ((deg / 90u) & 3u) {
    case 0: return {s, c};
    case 1: return {c, -s};
    case 2: return {-s, -c};
    default: return {-c, s};
  }
}

static_assert(sin_cos_deg(90).sin == 1.0 && sin_cos_deg(180).cos == -1.0);
static_assert(sin_cos_deg(30).sin > 0.4999999999999 && sin_cos_deg(30).sin < 0.5000000000001);

}  // namespace hesai
