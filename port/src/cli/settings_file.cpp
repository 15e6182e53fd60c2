// The settings file of 'hesai sensor apply' (settings_file.h).
#include "settings_file.h"

#include <cstring>

namespace hesai::cli {
namespace {

using ptc::Setting;

class JsonReader {
 public:
  explicit JsonReader(const std::string& text) : t_(text) {}
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
      if (peek() != '"' || !string(key, error)) return fail("a key in double quotes", error);
      if (!expect(':', error)) return false;
      skip();
      Setting s;
      if (!ptc::setting_from_name(key.data(), key.size(), s)) {
        error = "line " + std::to_string(key_line) + ": unknown key '" + key +
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
      const bool number = c == '-' || (c >= '0' && c <= '9');
      if (c == '"') {
        if (!string(value, error)) return false;
      } else if (number) {
        while (at_ < t_.size() && std::strchr("+-.eE0123456789", t_[at_]) != nullptr) value += t_[at_++];
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
  char peek() const { return at_ < t_.size() ? t_[at_] : '\0'; }
  void skip() {
    while (at_ < t_.size() && (t_[at_] == ' ' || t_[at_] == '\t' || t_[at_] == '\r' || t_[at_] == '\n')) {
      if (t_[at_] == '\n') ++line_;
      ++at_;
    }
  }
  bool fail(const char* wanted, std::string& error) {
    error = "line " + std::to_string(line_) + ": not JSON: expected " + wanted +
            (at_ < t_.size() ? std::string(", got '") + t_[at_] + "'" : std::string(", got the end of the file"));
    return false;
  }
  bool expect(char c, std::string& error) {
    skip();
    if (peek() != c) return fail(c == '{' ? "'{'" : "':'", error);
    ++at_;
    return true;
  }
  bool end(std::string& error) {
    skip();
    return at_ == t_.size() || fail("the end of the file after '}'", error);
  }
  // A string without escapes but \" and \\ (every value here is plain ASCII).
  bool string(std::string& out, std::string& error) {
    ++at_;  // the opening quote
    while (at_ < t_.size() && t_[at_] != '"') {
      char c = t_[at_++];
      if (c == '\n' || static_cast<unsigned char>(c) < 0x20) return fail("the closing '\"' on the same line", error);
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

  const std::string& t_;
  std::size_t at_ = 0;
  std::size_t line_ = 1;
};

}  // namespace

bool read_settings_json(const std::string& text, std::vector<Wanted>& out, std::string& error) {
  return JsonReader(text).read(out, error);
}

}  // namespace hesai::cli
