// Rows of the calibration CSVs, shared by the three readers (internal to the core): a row reader
// that splits lines at commas and trims fields, and the header-word and number helpers.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "hesai/bytes.h"
#include "hesai/calibration.h"

namespace hesai::csv {

constexpr bool is_digit(char c) { return c >= '0' && c <= '9'; }
constexpr unsigned digit(char c) { return static_cast<unsigned>(c - '0'); }

struct Field {
  const char* begin = nullptr;
  const char* end = nullptr;
  std::size_t size() const { return static_cast<std::size_t>(end - begin); }
};

inline constexpr std::size_t kMaxFields = 8;  // more than any format has: a longer row is a bad row anyway

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
bool word_is(const Field& f, const char* word);

/// "Channel", "Laser id", "LaserID" or "laser".
bool is_channel_word(const Field& f);

/// "fire time", "fire time(us)" (us as "us", U+03BC or U+00B5).
bool is_firetime_word(const Field& f);

/// An integer field: optional sign and digits. Magnitudes from 10^9 up stop growing (they are out
/// of every range anyway).
bool parse_int(const Field& f, std::int32_t& out);

inline bool parse_number(const Field& f, double& out) { return parse_decimal(f.begin, f.end, out); }

constexpr ParseResult fail(Error e, std::uint32_t line) { return ParseResult{e, line}; }

/// Checks `EEFF,major,minor` (the caller has seen the EEFF).
ParseResult check_version_row(const Row& row);

/// True when 1 <= ch <= limit.
inline bool channel_in_range(std::int32_t ch, std::size_t limit) {
  return ch >= 1 && static_cast<std::size_t>(ch) <= limit;
}

inline bool expected_ok(std::size_t expected) { return expected >= 1 && expected <= kMaxChannels; }

inline constexpr std::array<const char*, 2> kLoopWord = {"loop1", "loop2"};
inline constexpr std::array<const char*, 2> kFiretimeWord = {"firetime1", "firetime2"};

}  // namespace hesai::csv
