// libFuzzer harness: the settings file of 'hesai sensor apply' (port/src/cli/settings_file.cpp),
// read_settings_json() on any bytes, without I/O.
// Invariants: the same answer twice; an error is one line of printable ASCII that starts with
// "line N: " for a line the input has (the file's bytes are escaped in it: nothing a terminal acts
// on); a file read is at most the six keys, each once, every value without a control byte, each
// number of JSON's grammar and spelled in the input as it is.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_common.h"
#include "settings_file.h"

namespace {

using hesai_fuzz::check;

// RFC 8259 section 6: -? (0 | [1-9][0-9]*) (.[0-9]+)? ([eE][+-]?[0-9]+)?
bool json_number(std::string_view s) {
  std::size_t i = 0;
  const auto digits = [&] {
    const std::size_t from = i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
    return i > from;
  };
  if (i < s.size() && s[i] == '-') ++i;
  if (i < s.size() && s[i] == '0') ++i;
  else if (!digits()) return false;
  if (i < s.size() && s[i] == '.' && (++i, !digits())) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    if (!digits()) return false;
  }
  return i == s.size();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const hesai_fuzz::ExactCopy in(data, size);
  const std::string_view text(reinterpret_cast<const char*>(in.bytes.data()), in.bytes.size());
  std::vector<hesai::cli::Wanted> a, b;
  std::string error_a, error_b;
  const bool ok = hesai::cli::read_settings_json(text, a, error_a);
  const bool ok2 = hesai::cli::read_settings_json(text, b, error_b);
  check(ok == ok2 && error_a == error_b && a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) check(a[i].setting == b[i].setting && a[i].text == b[i].text);
  if (!ok) {
    check(error_a.rfind("line ", 0) == 0);
    for (const char c : error_a) check(c >= 0x20 && c < 0x7F);
    std::size_t lines = 1;
    for (const char c : text) lines += c == '\n';
    const std::size_t line = std::stoul(error_a.substr(5));
    check(line >= 1 && line <= lines);
    return 0;
  }
  check(error_a.empty());
  check(a.size() <= 6);
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) check(a[i].setting != a[j].setting);
    for (const char c : a[i].text) check(static_cast<unsigned char>(c) >= 0x20);
    check(a[i].text.size() <= text.size());
    // rpm takes only a number, spelled in the input as it is.
    if (a[i].setting == hesai::ptc::Setting::rpm)
      check(json_number(a[i].text) && text.find(a[i].text) != std::string_view::npos);
  }
  return 0;
}
