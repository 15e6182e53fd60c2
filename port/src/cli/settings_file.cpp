// The settings file of 'hesai sensor apply' (settings_file.h).
#include "settings_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "hesai_port/base/files.h"
#include "hesai_port/base/text.h"

namespace hesai::cli {
namespace {

using ptc::Setting;

bool is_digit(char c) { return c >= '0' && c <= '9'; }

class JsonReader {
 public:
  explicit JsonReader(std::string_view text) : t_(text) {}
  // Reads {"key": value, ...} into `out`; false with `error` ("line N: ...").
  bool read(std::vector<Wanted>& out, std::string& error) {
    if (!expect('{', error)) return false;
    skip();
    if (peek() == '}') {
      ++at_;
      return end(error);
    }
    for (;;) {
      skip();
      const std::size_t key_line = line_;
      std::string key;
      if (peek() != '"') return fail("a key in double quotes", error);
      if (!string(key, error)) return false;
      if (!expect(':', error)) return false;
      skip();
      Setting s;
      if (!ptc::setting_from_name(key.data(), key.size(), s)) {
        error = "line " + std::to_string(key_line) + ": unknown key '" + port::terminal_text(key) +
                "' (keys: rpm, return_mode, standby, sync_angle, destination, fov)";
        return false;
      }
      for (const Wanted& w : out)
        if (w.setting == s) {
          error = "line " + std::to_string(key_line) + ": key '" + key + "' given twice";
          return false;
        }
      std::string value;
      const char c = peek();
      const bool number = c == '-' || is_digit(c);
      if (c == '"') {
        if (!string(value, error)) return false;
      } else if (number) {
        if (!json_number(value, error)) return false;
      } else {
        const char* kind = c == '{' ? "an object" : c == '[' ? "an array" : c == 't' || c == 'f' ? "a boolean" : c == 'n' ? "null" : nullptr;
        if (kind == nullptr) return fail("a value", error);
        error = "line " + std::to_string(line_) + ": key '" + key + "' takes " + type_of(s) + ", got " + kind;
        return false;
      }
      const bool wants_number = s == Setting::rpm || s == Setting::sync_angle;
      if (number && !wants_number) {
        error = "line " + std::to_string(key_line) + ": key '" + key + "' takes " + type_of(s) + ", got a number";
        return false;
      }
      if (!number && s == Setting::rpm) {
        error = "line " + std::to_string(key_line) + ": key '" + key + "' takes a number, got a string";
        return false;
      }
      out.push_back({s, value});
      skip();
      if (peek() == ',') {
        ++at_;
        continue;
      }
      if (peek() == '}') {
        ++at_;
        return end(error);
      }
      return fail("',' or '}'", error);
    }
  }

 private:
  static const char* type_of(Setting s) {
    return s == Setting::rpm ? "a number" : s == Setting::sync_angle ? "a number or \"off\"" : "a string";
  }
  // The byte at the cursor; '\0' at the end (and for a NUL in the text, which no rule accepts).
  char peek() const { return at_ < t_.size() ? t_[at_] : '\0'; }
  bool digit_here() const { return at_ < t_.size() && is_digit(t_[at_]); }
  void skip() {
    while (at_ < t_.size() && (t_[at_] == ' ' || t_[at_] == '\t' || t_[at_] == '\r' || t_[at_] == '\n')) {
      if (t_[at_] == '\n') ++line_;
      ++at_;
    }
  }
  bool fail(const char* wanted, std::string& error) {
    error = "line " + std::to_string(line_) + ": not JSON: expected " + wanted +
            (at_ < t_.size() ? ", got '" + port::terminal_text(t_.substr(at_, 1)) + "'" : std::string(", got the end of the file"));
    return false;
  }
  bool expect(char c, std::string& error) {
    skip();
    if (at_ >= t_.size() || t_[at_] != c) return fail(c == '{' ? "'{'" : "':'", error);
    ++at_;
    return true;
  }
  bool end(std::string& error) {
    skip();
    return at_ == t_.size() || fail("the end of the file after '}'", error);
  }
  // A string without escapes but \" and \\ and without control bytes (every value here is plain
  // ASCII). The cursor is on the opening quote.
  bool string(std::string& out, std::string& error) {
    ++at_;
    while (at_ < t_.size() && t_[at_] != '"') {
      if (static_cast<unsigned char>(t_[at_]) < 0x20) return fail("the closing '\"' on the same line", error);
      char c = t_[at_++];
      if (c == '\\') {
        if (at_ >= t_.size() || (t_[at_] != '"' && t_[at_] != '\\')) return fail("only \\\" or \\\\ after '\\'", error);
        c = t_[at_++];
      }
      out += c;
    }
    if (at_ >= t_.size()) return fail("the closing '\"'", error);
    ++at_;
    return true;
  }
  // A number as RFC 8259 section 6 writes it: -? (0 | [1-9][0-9]*) (.[0-9]+)? ([eE][+-]?[0-9]+)?,
  // into `out` as written. The cursor is on '-' or a digit.
  bool json_number(std::string& out, std::string& error) {
    const std::size_t start = at_;
    if (t_[at_] == '-') ++at_;
    if (!digit_here()) return fail("a digit after '-'", error);
    if (t_[at_] == '0') {
      ++at_;
      if (digit_here()) {
        error = "line " + std::to_string(line_) + ": not JSON: a number with a leading zero: '" +
                port::terminal_text(t_.substr(start, at_ + 1 - start)) + "'";
        return false;
      }
    } else {
      while (digit_here()) ++at_;
    }
    if (at_ < t_.size() && t_[at_] == '.') {
      ++at_;
      if (!digit_here()) return fail("a digit after '.'", error);
      while (digit_here()) ++at_;
    }
    if (at_ < t_.size() && (t_[at_] == 'e' || t_[at_] == 'E')) {
      ++at_;
      if (at_ < t_.size() && (t_[at_] == '+' || t_[at_] == '-')) ++at_;
      if (!digit_here()) return fail("a digit in the exponent", error);
      while (digit_here()) ++at_;
    }
    out.assign(t_.data() + start, at_ - start);
    return true;
  }

  std::string_view t_;
  std::size_t at_ = 0;
  std::size_t line_ = 1;
};

}  // namespace

bool read_settings_file(const std::string& path, std::string& bytes, std::string& error) {
  bytes.clear();
  // O_NONBLOCK: a FIFO opens at once (and is refused below) instead of waiting for a writer.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) {
    error = "cannot read '" + path + "': " + std::strerror(errno);
    return false;
  }
  struct stat st {};
  if (fstat(fd, &st) != 0) {
    error = "cannot read '" + path + "': " + std::strerror(errno);
    ::close(fd);
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    error = "cannot read '" + path + "': " +
            (S_ISDIR(st.st_mode) ? std::string(std::strerror(EISDIR))
                                 : std::string("it is ") + port::file_kind(st.st_mode) + ", not a regular file");
    ::close(fd);
    return false;
  }
  char buf[4096];
  while (bytes.size() <= kMaxSettingsFileBytes) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n > 0) {
      bytes.append(buf, static_cast<std::size_t>(n));
    } else if (n == 0) {
      break;
    } else if (errno != EINTR) {
      error = "cannot read '" + path + "': " + std::strerror(errno);
      ::close(fd);
      return false;
    }
  }
  ::close(fd);
  if (bytes.size() > kMaxSettingsFileBytes) {
    error = "'" + path + "' is larger than " + std::to_string(kMaxSettingsFileBytes) + " bytes: not a settings file";
    return false;
  }
  return true;
}

bool read_settings_json(std::string_view text, std::vector<Wanted>& out, std::string& error) {
  return JsonReader(text).read(out, error);
}

}  // namespace hesai::cli
