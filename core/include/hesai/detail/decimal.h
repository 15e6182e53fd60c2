// Decimal text to double, correctly rounded in every case the calibration files use, without the
// C library (freestanding targets have no strtod). Used by the calibration parsers.
#pragma once

namespace hesai {

/// Parses the whole of [begin, end) as a decimal number: optional sign, digits with an optional
/// fraction (at least one digit), optional exponent (`e`/`E`, optional sign, digits). No spaces,
/// no hex, no inf/nan. False when the text is not such a number or its magnitude overflows a
/// double; a magnitude below the smallest subnormal gives (signed) zero. The result is within 1 ulp
/// of the decimal value, and is the nearest double (as strtod gives) unless the value has more than
/// 19 significant digits (the rest are dropped), is subnormal (rounded twice), or lies within about
/// 2^-100 (relative) of a tie between two doubles. Digits that form an integer up to 2^53, scaled
/// by 10^k with |k| <= 22 (every calibration value), take one exact IEEE operation: always nearest.
[[nodiscard]] bool parse_decimal(const char* begin, const char* end, double& out) noexcept;

}  // namespace hesai
