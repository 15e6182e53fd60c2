// The header-word and number helpers of the calibration CSVs (csv_rows.h).
#include "csv_rows.h"

namespace hesai::csv {

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

/// Checks `EEFF,major,minor` (the caller has seen the EEFF).
ParseResult check_version_row(const Row& row) {
  if (row.count != 3) return fail(Error::calib_bad_header, row.line);
  std::int32_t v = 0;
  if (!parse_int(row.field[1], v) || !parse_int(row.field[2], v)) return fail(Error::calib_bad_number, row.line);
  return {};
}

}  // namespace hesai::csv
