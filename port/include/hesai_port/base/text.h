// Text that came from elsewhere (a unit's serial, versions and error texts, a certificate's
// subject, a file's keys and values, a bag's topics), made safe to print: on a terminal, or as a
// JSON string. Any bytes in, never a control byte out, whatever the input holds (NUL included).
#pragma once

#include <string>
#include <string_view>

namespace hesai::port {

/// `s` for a terminal, one field on one line: printable ASCII (0x20..0x7E) as it is, except the
/// backslash; every other byte as \xNN (two lowercase hex digits): the control bytes (ESC, BEL,
/// CR, the line feed too), DEL, the backslash (\x5c, so that every backslash of the result starts
/// an escape) and every byte from 0x80 on, valid UTF-8 or not. Serials, versions and subjects of
/// units are ASCII; escaping all of the rest keeps out C1 controls (a UTF-8 U+009B is a CSI to
/// some terminals), bidirectional overrides and look-alike letters.
/// "A\x1b[2J\\" gives "A\x1b[2J\x5c" (as written in C: "A\\x1b[2J\\x5c").
std::string terminal_text(std::string_view s);

/// `s` as a JSON string literal, with its quotes, valid JSON (RFC 8259) for any bytes: `"` and
/// `\` escaped with a backslash; every code point below U+0020, DEL and the C1 controls
/// (U+007F..U+009F) as \u00xx; the rest of well-formed UTF-8 as it is; a byte that is not part of
/// well-formed UTF-8 (a stray continuation byte, a truncated sequence, an overlong form, a
/// surrogate, above U+10FFFF) as \u00xx of its value, as if the byte were Latin-1 (so no byte is
/// lost, and an invalid 0xE9 and a valid U+00E9 read alike).
std::string json_string(std::string_view s);

}  // namespace hesai::port
