// The settings file of 'hesai sensor apply': a flat JSON object of the keys of 'sensor set'.
#pragma once

#include <string>
#include <vector>

#include "hesai/ptc_settings.h"

namespace hesai::cli {

/// One setting asked for: its key and its value as text (set: after '='; apply: the JSON value,
/// strings without their quotes, numbers as written).
struct Wanted {
  ptc::Setting setting;
  std::string text;
};

/// Reads {"key": value, ...}: `rpm` a number, `sync_angle` a number or a string, the other keys
/// strings. False with `error` naming the line ("line 3: not JSON: expected ',' or '}'", "line 2:
/// unknown key 'colour' ...", "line 1: key 'rpm' takes a number, got a string", a key given twice).
/// Strings take no escapes but \" and \\ (every value is plain ASCII).
bool read_settings_json(const std::string& text, std::vector<Wanted>& out, std::string& error);

}  // namespace hesai::cli
