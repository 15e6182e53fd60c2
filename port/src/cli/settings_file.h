// The settings file of 'hesai sensor apply': a flat JSON object of the keys of 'sensor set'.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "hesai/ptc_settings.h"

namespace hesai::cli {

/// One setting asked for: its key and its value as text (set: after '='; apply: the JSON value,
/// strings without their quotes, numbers as written).
struct Wanted {
  ptc::Setting setting;
  std::string text;
};

/// The largest settings file read (a settings file holds six keys).
inline constexpr std::size_t kMaxSettingsFileBytes = 65536;

/// Reads the file at `path` into `bytes`, at most kMaxSettingsFileBytes. It is opened without
/// blocking and checked on that descriptor (fstat) before a byte is read: anything but a regular
/// file (a FIFO, which would wait for a writer, a device, a folder) is refused. False with `error`
/// ("cannot read 'PATH': it is a FIFO, not a regular file", "cannot read 'PATH': Is a directory",
/// "'PATH' is larger than 65536 bytes: not a settings file").
bool read_settings_file(const std::string& path, std::string& bytes, std::string& error);

/// Reads {"key": value, ...} from `text` (any bytes; no I/O): `rpm` a number, `sync_angle` a
/// number or a string, the other keys strings. Numbers follow JSON's grammar (RFC 8259 section 6:
/// an optional '-', no leading zeros, digits after '.' and in the exponent), kept as written for
/// the key's own check. False with `error` naming the line ("line 3: not JSON: expected ',' or
/// '}', got 'x'", "line 1: not JSON: a number with a leading zero: '01'", "line 2: unknown key
/// 'colour' ...", "line 1: key 'rpm' takes a number, got a string", a key given twice); the
/// file's bytes in it are escaped for a terminal (a NUL is '\x00'). Strings take no escapes but
/// \" and \\ and no control bytes (every value is plain ASCII).
bool read_settings_json(std::string_view text, std::vector<Wanted>& out, std::string& error);

}  // namespace hesai::cli
