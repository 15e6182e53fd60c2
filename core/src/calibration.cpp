#include "hesai/calibration.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace hesai {
namespace {

// ---------------------------------------------------------------------------------------------
// Decimal to double.
//
// The significant digits (at most 19, more are dropped) form an integer m; the value is
// m * 10^e10. When m <= 2^53 and |e10| <= 22, m and 10^|e10| are exact doubles and one IEEE
// multiplication or division gives the nearest double. Otherwise the product or quotient is
// formed in double-double arithmetic (about 104 bits: Dekker's error-free transformations)
// and rounded once at the end, which is within 1 ulp, and the nearest outside near-halfway cases.

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

// ---------------------------------------------------------------------------------------------
// CSV rows.

struct Field {
  const char* begin = nullptr;
  const char* end = nullptr;
  std::size_t size() const { return static_cast<std::size_t>(end - begin); }
};

constexpr std::size_t kMaxFields = 8;  // more than any format has: a longer row is a bad row anyway

/// One line split at commas, fields trimmed of spaces and tabs, trailing empty fields dropped.
struct Row {
  std::uint32_t line = 0;  ///< 1-based
  std::size_t count = 0;   ///< fields up to the last non-empty one (only the first kMaxFields kept)
  std::array<Field, kMaxFields> field{};
};

constexpr bool is_blank(char c) { return c == ' ' || c == '\t'; }

class RowReader {
 public:
  explicit RowReader(ByteView text) {
    if (text.data == nullptr) return;
    p_ = reinterpret_cast<const char*>(text.data);  // char may alias any object
    end_ = p_ + text.size;
    if (text.size >= 3 && text[0] == 0xEF && text[1] == 0xBB && text[2] == 0xBF) p_ += 3;  // UTF-8 BOM
  }

  /// The next row that has a non-empty field; false at the end of the text.
  bool next(Row& row) {
    while (p_ != end_) {
      const char* begin = p_;
      while (p_ != end_ && *p_ != '\n') ++p_;
      const char* end = p_;
      if (p_ != end_) ++p_;
      if (line_ != std::numeric_limits<std::uint32_t>::max()) ++line_;
      if (end != begin && end[-1] == '\r') --end;
      split(begin, end, row);
      if (row.count != 0) {
        row.line = line_;
        return true;
      }
    }
    return false;
  }

  /// Lines read so far.
  std::uint32_t line() const { return line_; }

 private:
  static void split(const char* begin, const char* end, Row& row) {
    row.count = 0;
    std::size_t n = 0;
    const char* f = begin;
    for (;;) {
      const char* fe = f;
      while (fe != end && *fe != ',') ++fe;
      Field field{f, fe};
      while (field.begin != field.end && is_blank(*field.begin)) ++field.begin;
      while (field.end != field.begin && is_blank(field.end[-1])) --field.end;
      if (n < kMaxFields) row.field[n] = field;
      ++n;
      if (field.begin != field.end) row.count = n;
      if (fe == end) break;
      f = fe + 1;
    }
  }

  const char* p_ = nullptr;
  const char* end_ = nullptr;
  std::uint32_t line_ = 0;
};

/// True when the field, ASCII letters lowered and spaces and underscores dropped, equals `word`.
bool word_is(const Field& f, const char* word) {
  const char* w = word;
  for (const char* p = f.begin; p != f.end; ++p) {
    char c = *p;
    if (c == ' ' || c == '_') continue;
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    if (*w == '\0' || *w != c) return false;
    ++w;
  }
  return *w == '\0';
}

bool is_channel_word(const Field& f) {
  return word_is(f, "channel") || word_is(f, "laserid") || word_is(f, "laser");
}

bool is_firetime_word(const Field& f) {
  return word_is(f, "firetime") || word_is(f, "firetime(us)") ||
         word_is(f, "firetime(\xCE\xBCs)") ||  // U+03BC GREEK SMALL LETTER MU (the shipped file)
         word_is(f, "firetime(\xC2\xB5s)");    // U+00B5 MICRO SIGN
}

/// An integer field: optional sign and digits. Magnitudes from 10^9 up stop growing (they are out
/// of every range anyway).
bool parse_int(const Field& f, std::int32_t& out) {
  const char* p = f.begin;
  bool negative = false;
  if (p != f.end && (*p == '+' || *p == '-')) {
    negative = *p == '-';
    ++p;
  }
  if (p == f.end) return false;
  std::int32_t v = 0;
  for (; p != f.end; ++p) {
    if (!is_digit(*p)) return false;
    if (v < 100000000) v = v * 10 + static_cast<std::int32_t>(digit(*p));  // stays below 10^9
  }
  out = negative ? -v : v;
  return true;
}

bool parse_number(const Field& f, double& out) { return parse_decimal(f.begin, f.end, out); }

constexpr ParseResult fail(Error e, std::uint32_t line) { return ParseResult{e, line}; }

/// Checks `EEFF,major,minor` (the caller has seen the EEFF).
ParseResult check_version_row(const Row& row) {
  if (row.count != 3) return fail(Error::calib_bad_header, row.line);
  std::int32_t v = 0;
  if (!parse_int(row.field[1], v) || !parse_int(row.field[2], v)) return fail(Error::calib_bad_number, row.line);
  return {};
}

/// True when 1 <= ch <= limit.
bool channel_in_range(std::int32_t ch, std::size_t limit) {
  return ch >= 1 && static_cast<std::size_t>(ch) <= limit;
}

bool expected_ok(std::size_t expected) { return expected >= 1 && expected <= kMaxChannels; }

constexpr std::array<const char*, 2> kLoopWord = {"loop1", "loop2"};
constexpr std::array<const char*, 2> kFiretimeWord = {"firetime1", "firetime2"};

ParseResult parse_qt_firetime(RowReader& rows, Row& row, std::size_t expected, FiretimeCorrection& out) {
  ParseResult r = check_version_row(row);
  if (r.error != Error::ok) return r;

  if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  if (row.count != 4 || !word_is(row.field[0], "horizontalresolutionmode") || !word_is(row.field[2], "loopnum")) {
    return fail(Error::calib_bad_header, row.line);
  }
  std::int32_t mode = 0;
  std::int32_t loops = 0;
  if (!parse_int(row.field[1], mode) || !parse_int(row.field[3], loops)) return fail(Error::calib_bad_number, row.line);
  if (loops < 1 || loops > 2) return fail(Error::calib_bad_header, row.line);
  const std::size_t nloops = static_cast<std::size_t>(loops);

  if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  if (row.count != 2 * nloops) return fail(Error::calib_bad_header, row.line);
  for (std::size_t k = 0; k < nloops; ++k) {
    if (!word_is(row.field[2 * k], kLoopWord[k]) || !word_is(row.field[2 * k + 1], kFiretimeWord[k])) {
      return fail(Error::calib_bad_header, row.line);
    }
  }

  std::size_t n = 0;
  std::uint32_t last = row.line;
  while (rows.next(row)) {
    last = row.line;
    if (n == expected) return fail(Error::calib_channel_count, row.line);
    if (row.count != 2 * nloops) return fail(Error::calib_bad_row, row.line);
    std::array<std::int32_t, 2> ch{};
    std::array<double, 2> t{};
    for (std::size_t k = 0; k < nloops; ++k) {
      if (!parse_int(row.field[2 * k], ch[k]) || !parse_number(row.field[2 * k + 1], t[k])) {
        return fail(Error::calib_bad_number, row.line);
      }
    }
    for (std::size_t k = 0; k < nloops; ++k) {
      if (ch[k] == 0) continue;  // no entry (padding)
      if (!channel_in_range(ch[k], expected)) return fail(Error::calib_bad_channel, row.line);
      const std::size_t i = static_cast<std::size_t>(ch[k] - 1);
      if (out.fires[k][i]) return fail(Error::calib_bad_channel, row.line);
      out.fires[k][i] = true;
      out.firetime_us[k][i] = t[k];
    }
    ++n;
  }
  for (std::size_t i = 0; i < expected; ++i) {
    if (!out.fires[0][i] && !out.fires[1][i]) return fail(Error::calib_channel_count, last + 1);
  }
  out.loops = static_cast<std::uint8_t>(nloops);
  return {};
}

}  // namespace

// ---------------------------------------------------------------------------------------------

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

ParseResult parse_angle_csv(ByteView text, std::size_t expected_channels, AngleCorrection& out) noexcept {
  out.channels = 0;
  out.elevation_deg.fill(0.0);
  out.azimuth_deg.fill(0.0);
  if (!expected_ok(expected_channels)) return fail(Error::invalid_argument, 0);

  RowReader rows(text);
  Row row;
  if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  if (word_is(row.field[0], "eeff")) {  // QT128, manual Figure 1.7
    const ParseResult r = check_version_row(row);
    if (r.error != Error::ok) return r;
    if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  }
  if (row.count != 3 || !is_channel_word(row.field[0]) || !word_is(row.field[1], "elevation") ||
      !word_is(row.field[2], "azimuth")) {
    return fail(Error::calib_bad_header, row.line);
  }

  std::array<bool, kMaxChannels> seen{};
  std::size_t n = 0;
  std::uint32_t last = row.line;
  while (rows.next(row)) {
    last = row.line;
    if (n == expected_channels) return fail(Error::calib_channel_count, row.line);
    if (row.count != 3) return fail(Error::calib_bad_row, row.line);
    std::int32_t ch = 0;
    double elevation = 0.0;
    double azimuth = 0.0;
    if (!parse_int(row.field[0], ch) || !parse_number(row.field[1], elevation) ||
        !parse_number(row.field[2], azimuth)) {
      return fail(Error::calib_bad_number, row.line);
    }
    if (!channel_in_range(ch, expected_channels)) return fail(Error::calib_bad_channel, row.line);
    const std::size_t i = static_cast<std::size_t>(ch - 1);
    if (seen[i]) return fail(Error::calib_bad_channel, row.line);
    seen[i] = true;
    out.elevation_deg[i] = elevation;
    out.azimuth_deg[i] = azimuth;
    ++n;
  }
  if (n != expected_channels) return fail(Error::calib_channel_count, last + 1);
  out.channels = static_cast<std::uint16_t>(expected_channels);
  return {};
}

ParseResult parse_firetime_csv(ByteView text, std::size_t expected_channels, FiretimeCorrection& out) noexcept {
  out.channels = 0;
  out.loops = 1;
  for (auto& loop : out.firetime_us) loop.fill(0.0);
  for (auto& loop : out.fires) loop.fill(false);
  if (!expected_ok(expected_channels)) return fail(Error::invalid_argument, 0);

  RowReader rows(text);
  Row row;
  if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  if (word_is(row.field[0], "eeff")) {  // QT128, manual App. II
    const ParseResult r = parse_qt_firetime(rows, row, expected_channels, out);
    if (r.error != Error::ok) return r;
    out.channels = static_cast<std::uint16_t>(expected_channels);
    return r;
  }

  // Pandar40P / Pandar64: channel,time pairs.
  if (row.count != 2 || !is_channel_word(row.field[0]) || !is_firetime_word(row.field[1])) {
    return fail(Error::calib_bad_header, row.line);
  }
  std::size_t n = 0;
  std::uint32_t last = row.line;
  while (rows.next(row)) {
    last = row.line;
    if (n == expected_channels) return fail(Error::calib_channel_count, row.line);
    if (row.count != 2) return fail(Error::calib_bad_row, row.line);
    std::int32_t ch = 0;
    double t = 0.0;
    if (!parse_int(row.field[0], ch) || !parse_number(row.field[1], t)) return fail(Error::calib_bad_number, row.line);
    if (!channel_in_range(ch, expected_channels)) return fail(Error::calib_bad_channel, row.line);
    const std::size_t i = static_cast<std::size_t>(ch - 1);
    if (out.fires[0][i]) return fail(Error::calib_bad_channel, row.line);
    out.fires[0][i] = true;
    out.firetime_us[0][i] = t;
    ++n;
  }
  if (n != expected_channels) return fail(Error::calib_channel_count, last + 1);
  out.channels = static_cast<std::uint16_t>(expected_channels);
  return {};
}

ParseResult parse_channel_config_csv(ByteView text, ChannelConfig& out) noexcept {
  out.laser_num = 0;
  out.block_num = 0;
  out.loops = 0;
  for (auto& loop : out.channel) loop.fill(0);
  out.hash.fill('\0');
  out.hash_length = 0;

  RowReader rows(text);
  Row row;
  if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  if (!word_is(row.field[0], "eeff")) return fail(Error::calib_bad_header, row.line);
  ParseResult r = check_version_row(row);
  if (r.error != Error::ok) return r;

  if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  if (row.count != 4 || !word_is(row.field[0], "lasernum") || !word_is(row.field[2], "blocknum")) {
    return fail(Error::calib_bad_header, row.line);
  }
  std::int32_t laser_num = 0;
  std::int32_t block_num = 0;
  if (!parse_int(row.field[1], laser_num) || !parse_int(row.field[3], block_num)) {
    return fail(Error::calib_bad_number, row.line);
  }
  if (!channel_in_range(laser_num, kMaxChannels) || block_num < 1 || block_num > 255) {
    return fail(Error::calib_bad_header, row.line);
  }
  const std::size_t nlaser = static_cast<std::size_t>(laser_num);

  if (!rows.next(row)) return fail(Error::calib_bad_header, rows.line() + 1);
  if (row.count < 1 || row.count > 2) return fail(Error::calib_bad_header, row.line);
  const std::size_t nloops = row.count;
  for (std::size_t k = 0; k < nloops; ++k) {
    if (!word_is(row.field[k], kLoopWord[k])) return fail(Error::calib_bad_header, row.line);
  }

  std::array<std::array<bool, kMaxChannels>, 2> seen{};
  std::size_t n = 0;
  bool have_hash = false;
  std::uint32_t last = row.line;
  while (rows.next(row)) {
    last = row.line;
    if (n == nlaser) {  // past the channel rows: one hash line may follow
      if (have_hash || row.count != 1) return fail(Error::calib_channel_count, row.line);
      const Field& h = row.field[0];
      if (h.size() > out.hash.size()) return fail(Error::calib_bad_row, row.line);
      for (std::size_t i = 0; i < h.size(); ++i) out.hash[i] = h.begin[i];
      out.hash_length = static_cast<std::uint8_t>(h.size());
      have_hash = true;
      continue;
    }
    if (row.count != nloops) return fail(Error::calib_bad_row, row.line);
    std::array<std::int32_t, 2> ch{};
    for (std::size_t k = 0; k < nloops; ++k) {
      if (!parse_int(row.field[k], ch[k])) return fail(Error::calib_bad_number, row.line);
    }
    for (std::size_t k = 0; k < nloops; ++k) {
      if (!channel_in_range(ch[k], kMaxChannels)) return fail(Error::calib_bad_channel, row.line);
      const std::size_t c = static_cast<std::size_t>(ch[k] - 1);
      if (seen[k][c]) return fail(Error::calib_bad_channel, row.line);
      seen[k][c] = true;
      out.channel[k][n] = static_cast<std::uint8_t>(ch[k]);
    }
    ++n;
  }
  if (n != nlaser) return fail(Error::calib_channel_count, last + 1);
  out.laser_num = static_cast<std::uint16_t>(nlaser);
  out.block_num = static_cast<std::uint8_t>(block_num);
  out.loops = static_cast<std::uint8_t>(nloops);
  return {};
}

}  // namespace hesai
