// Decimal text to the nearest double, without the C library (hesai/detail/decimal.h).
//
// The significant digits (at most 19, more are dropped) form an integer m; the value is
// m * 10^e10. When m <= 2^53 and |e10| <= 22, m and 10^|e10| are exact doubles and one IEEE
// multiplication or division gives the nearest double. Otherwise the product or quotient is
// formed in double-double arithmetic (about 104 bits: Dekker's error-free transformations)
// and rounded once at the end, which is within 1 ulp, and the nearest outside near-halfway cases.
#include "hesai/detail/decimal.h"

#include <array>
#include <cstdint>
#include <limits>

namespace hesai {
namespace {

constexpr int kMaxDigits = 19;  // 10^19 - 1 < 2^64
constexpr std::uint64_t kTwoPow53 = std::uint64_t{1} << 53;

/// The exact powers of ten a double holds: 10^0 .. 10^22.
constexpr std::array<double, 23> kExactPow10 = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                                1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                                1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/// An unevaluated sum hi + lo with |lo| <= ulp(hi) / 2.
struct DoubleDouble {
  double hi;
  double lo;
};

constexpr DoubleDouble quick_two_sum(double a, double b) {  // needs |a| >= |b|
  const double s = a + b;
  return {s, b - (s - a)};
}

constexpr DoubleDouble two_sum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}

// Dekker's split of a into two halves of 26 bits each, hi + lo == a. At run time the product is
// stored through a volatile: g++ contracts `t - (t - a)` with t = c * a into a fused multiply-add
// on FMA targets (even in ISO mode), which would break the split. Constant evaluation rounds every
// operation, so the table below is built with the plain form.
template <bool kRunTime>
constexpr DoubleDouble split(double a) {
  constexpr double kSplitter = 134217729.0;           // 2^27 + 1
  constexpr double kSplitLimit = 6.69692879491417e299;  // about 2^996: above, c * a could overflow
  double scale = 1.0;
  if (a > kSplitLimit || a < -kSplitLimit) {
    a *= 0x1p-28;
    scale = 0x1p28;
  }
  double t = 0.0;
  if constexpr (kRunTime) {
    volatile double stored = kSplitter * a;
    t = stored;
  } else {
    t = kSplitter * a;
  }
  const double hi = t - (t - a);
  const double lo = a - hi;
  return {hi * scale, lo * scale};
}

// a * b == p + err exactly. Every partial product is exact, so a fused multiply-add changes nothing.
template <bool kRunTime>
constexpr DoubleDouble two_prod(double a, double b) {
  const double p = a * b;
  const DoubleDouble sa = split<kRunTime>(a);
  const DoubleDouble sb = split<kRunTime>(b);
  const double err = ((sa.hi * sb.hi - p) + sa.hi * sb.lo + sa.lo * sb.hi) + sa.lo * sb.lo;
  return {p, err};
}

template <bool kRunTime>
constexpr DoubleDouble mul(DoubleDouble a, DoubleDouble b) {
  DoubleDouble p = two_prod<kRunTime>(a.hi, b.hi);
  p.lo += a.hi * b.lo + a.lo * b.hi;
  return quick_two_sum(p.hi, p.lo);
}

DoubleDouble sub(DoubleDouble a, DoubleDouble b) {
  DoubleDouble s = two_sum(a.hi, -b.hi);
  s.lo += a.lo - b.lo;
  return quick_two_sum(s.hi, s.lo);
}

DoubleDouble div(DoubleDouble a, DoubleDouble b) {
  const double q1 = a.hi / b.hi;
  const DoubleDouble r = sub(a, mul<true>(b, DoubleDouble{q1, 0.0}));
  const double q2 = r.hi / b.hi;
  return quick_two_sum(q1, q2);
}

/// 10^(2^i) for i = 0..8 (10 .. 10^256) as hi + lo, where hi is the double nearest 10^(2^i) and lo
/// the double nearest the rest (computed exactly in integers: 10^32 - hi = -5366162204393472).
constexpr std::array<DoubleDouble, 9> kPow10Pow2 = {{
    {1e1, 0.0},
    {1e2, 0.0},
    {1e4, 0.0},
    {1e8, 0.0},
    {1e16, 0.0},
    {0x1.3b8b5b5056e17p+106, -0x1.3107f00000000p+52},
    {0x1.84f03e93ff9f5p+212, -0x1.2ac340948e389p+157},
    {0x1.27748f9301d32p+425, -0x1.901cc86649e4ap+371},
    {0x1.54fdd7f73bf3cp+850, -0x1.7222446fe4670p+795},
}};

// Proof of the table: each entry is the square of the one before, to 2^-100 (double-double
// squaring loses a few of the 106 bits, hence not equality).
constexpr bool pow10_table_is_squares() {
  if (kPow10Pow2[0].hi != 10.0 || kPow10Pow2[0].lo != 0.0) return false;
  for (std::size_t i = 1; i < kPow10Pow2.size(); ++i) {
    const DoubleDouble sq = mul<false>(kPow10Pow2[i - 1], kPow10Pow2[i - 1]);
    const double diff = sq.lo - kPow10Pow2[i].lo;
    const double bound = kPow10Pow2[i].hi * 0x1p-100;
    if (sq.hi != kPow10Pow2[i].hi || diff > bound || -diff > bound) return false;
  }
  return true;
}
static_assert(pow10_table_is_squares());
static_assert(kPow10Pow2[5].lo == -5366162204393472.0);  // 1e32 as a double is 10^32 + 5366162204393472

/// 10^k as a double-double, k <= 308.
DoubleDouble pow10(unsigned k) {
  DoubleDouble r{1.0, 0.0};
  for (std::size_t i = 0; k != 0; ++i, k >>= 1) {
    if ((k & 1u) != 0) r = mul<true>(r, kPow10Pow2[i]);
  }
  return r;
}

constexpr bool is_digit(char c) { return c >= '0' && c <= '9'; }
constexpr unsigned digit(char c) { return static_cast<unsigned>(c - '0'); }
}  // namespace

bool parse_decimal(const char* begin, const char* end, double& out) noexcept {
  const char* p = begin;
  if (p == end) return false;
  bool negative = false;
  if (*p == '+' || *p == '-') {
    negative = *p == '-';
    ++p;
  }
  std::uint64_t m = 0;    // significant digits
  int ndigits = 0;        // digits in m
  std::int64_t e10 = 0;   // value = m * 10^e10
  bool any_digit = false;
  for (; p != end && is_digit(*p); ++p) {
    any_digit = true;
    if (m == 0 && *p == '0') continue;  // leading zero
    if (ndigits < kMaxDigits) {
      m = m * 10 + digit(*p);
      ++ndigits;
    } else {
      ++e10;  // dropped integer digit
    }
  }
  if (p != end && *p == '.') {
    for (++p; p != end && is_digit(*p); ++p) {
      any_digit = true;
      if (m == 0 && *p == '0') {
        --e10;
        continue;
      }
      if (ndigits < kMaxDigits) {
        m = m * 10 + digit(*p);
        ++ndigits;
        --e10;
      }
    }
  }
  if (!any_digit) return false;
  if (p != end && (*p == 'e' || *p == 'E')) {
    ++p;
    bool exp_negative = false;
    if (p != end && (*p == '+' || *p == '-')) {
      exp_negative = *p == '-';
      ++p;
    }
    if (p == end || !is_digit(*p)) return false;
    std::int64_t exp = 0;
    for (; p != end && is_digit(*p); ++p) {
      if (exp < 1000000000) exp = exp * 10 + static_cast<std::int64_t>(digit(*p));
    }
    e10 += exp_negative ? -exp : exp;
  }
  if (p != end) return false;

  const double sign = negative ? -1.0 : 1.0;
  if (m == 0) {
    out = sign * 0.0;
    return true;
  }
  // The value lies in [10^magnitude, 10^(magnitude + 1)).
  const std::int64_t magnitude = e10 + ndigits - 1;
  if (magnitude > 308) return false;  // above DBL_MAX (1.8e308)
  if (magnitude < -325) {             // below half the smallest subnormal (4.9e-324)
    out = sign * 0.0;
    return true;
  }

  double value = 0.0;
  if (m <= kTwoPow53 && e10 >= -22 && e10 <= 22) {
    const double dm = static_cast<double>(m);  // exact
    value = e10 >= 0 ? dm * kExactPow10[static_cast<std::size_t>(e10)]
                     : dm / kExactPow10[static_cast<std::size_t>(-e10)];
  } else {
    // m as an exact double-double, from its two 32-bit halves.
    DoubleDouble x = two_sum(static_cast<double>(static_cast<std::uint32_t>(m >> 32)) * 4294967296.0,
                             static_cast<double>(static_cast<std::uint32_t>(m)));
    // Scale by a power of two near the ends of the range so that no intermediate overflows or
    // loses bits to subnormals; the final scaling back is exact or the one rounding to a subnormal.
    double scale_back = 1.0;
    if (magnitude > 290) {
      x = {x.hi * 0x1p-200, x.lo * 0x1p-200};
      scale_back = 0x1p200;
    } else if (magnitude < -270) {
      x = {x.hi * 0x1p200, x.lo * 0x1p200};
      scale_back = 0x1p-200;
    }
    if (e10 >= 0) {
      x = mul<true>(x, pow10(static_cast<unsigned>(e10)));  // e10 <= magnitude <= 308
    } else {
      std::int64_t k = -e10;  // <= 325 + 18
      if (k > 300) {
        x = div(x, pow10(300));
        k -= 300;
      }
      x = div(x, pow10(static_cast<unsigned>(k)));
    }
    value = (x.hi + x.lo) * scale_back;
  }
  if (!(value <= std::numeric_limits<double>::max())) return false;  // rounded up to infinity
  out = sign * value;
  return true;
}

}  // namespace hesai
