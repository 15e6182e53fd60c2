// Text from a peer or a file made safe to print (hesai_port/base/text.h): every expected output
// below is written by hand from the rules of the header (issue #44, finding 3).
#include <gtest/gtest.h>

#include <string>

#include "hesai_port/base/text.h"

namespace {

using hesai::port::json_string;
using hesai::port::terminal_text;
using namespace std::string_literals;

TEST(TerminalText, PrintableAsciiAsItIs) {
  EXPECT_EQ(terminal_text(""), "");
  EXPECT_EQ(terminal_text("STANDIN"), "STANDIN");
  EXPECT_EQ(terminal_text(" ~QT128C2X-0001 (v1.2)"), " ~QT128C2X-0001 (v1.2)");
  EXPECT_EQ(terminal_text("say \"hi\" 'there'"), "say \"hi\" 'there'");
}

TEST(TerminalText, EveryOtherByteAsHex) {
  // An xterm title and a screen clear: ESC ] 0 ; ... BEL, ESC [ 2 J.
  EXPECT_EQ(terminal_text("\x1b]0;owned\x07\x1b[2J"), "\\x1b]0;owned\\x07\\x1b[2J");
  // The line feed too: one field stays on one line; CR, TAB, DEL.
  EXPECT_EQ(terminal_text("a\nb\rc\td\x7f"), "a\\x0ab\\x0dc\\x09d\\x7f");
  // NUL inside the text is a byte like any other.
  EXPECT_EQ(terminal_text("a\0b"s), "a\\x00b");
  // The backslash: every backslash of the result starts an escape.
  EXPECT_EQ(terminal_text("C:\\x1b"), "C:\\x5cx1b");
  // From 0x80 on, valid UTF-8 or not: a C1 CSI (U+009B as C2 9B), an e acute (C3 A9), a stray 0xFF.
  EXPECT_EQ(terminal_text("\xc2\x9b" "31m \xc3\xa9 \xff"), "\\xc2\\x9b31m \\xc3\\xa9 \\xff");
  EXPECT_EQ(terminal_text("\x01\x1f\x20\x7e\x80"), "\\x01\\x1f ~\\x80");
}

TEST(JsonString, QuotesAndPlainText) {
  EXPECT_EQ(json_string(""), "\"\"");
  EXPECT_EQ(json_string("STANDIN"), "\"STANDIN\"");
  EXPECT_EQ(json_string("a\"b\\c/d"), "\"a\\\"b\\\\c/d\"");
}

TEST(JsonString, ControlBytesAndDel) {
  EXPECT_EQ(json_string("\x1b]0;owned\x07"), "\"\\u001b]0;owned\\u0007\"");
  EXPECT_EQ(json_string("\r\n\t\x7f"), "\"\\u000d\\u000a\\u0009\\u007f\"");
  EXPECT_EQ(json_string("a\0b"s), "\"a\\u0000b\"");
  EXPECT_EQ(json_string("\x1f\x20"), "\"\\u001f \"");
}

TEST(JsonString, WellFormedUtf8AsItIsButC1Controls) {
  // e acute (U+00E9), the euro sign (U+20AC), U+10348 (4 bytes), U+10FFFF (the last).
  EXPECT_EQ(json_string("\xc3\xa9 \xe2\x82\xac \xf0\x90\x8d\x88 \xf4\x8f\xbf\xbf"),
            "\"\xc3\xa9 \xe2\x82\xac \xf0\x90\x8d\x88 \xf4\x8f\xbf\xbf\"");
  // U+0080 and U+009B (CSI), C1 controls: escaped by their code point.
  EXPECT_EQ(json_string("\xc2\x80\xc2\x9b\xc2\xa0"), "\"\\u0080\\u009b\xc2\xa0\"");
}

TEST(JsonString, BytesThatAreNotUtf8ByTheirValue) {
  EXPECT_EQ(json_string("\xff"), "\"\\u00ff\"");
  EXPECT_EQ(json_string("\x9b" "31m"), "\"\\u009b31m\"");             // a stray continuation byte
  EXPECT_EQ(json_string("\xc3"), "\"\\u00c3\"");                      // cut short at the end
  EXPECT_EQ(json_string("\xc3x"), "\"\\u00c3x\"");                    // cut short by ASCII
  EXPECT_EQ(json_string("\xc0\xaf"), "\"\\u00c0\\u00af\"");           // overlong '/'
  EXPECT_EQ(json_string("\xe0\x80\xaf"), "\"\\u00e0\\u0080\\u00af\"");  // overlong, 3 bytes
  EXPECT_EQ(json_string("\xed\xa0\x80"), "\"\\u00ed\\u00a0\\u0080\"");  // a surrogate (U+D800)
  EXPECT_EQ(json_string("\xf4\x90\x80\x80"), "\"\\u00f4\\u0090\\u0080\\u0080\"");  // above U+10FFFF
  EXPECT_EQ(json_string("\xe2\x82"), "\"\\u00e2\\u0082\"");           // 2 of 3 bytes
}

// Whatever the bytes, no control byte and no byte of malformed UTF-8 leaves either function
// (every single byte, every pair of bytes).
TEST(TextEscaping, NoControlByteForAnyInput) {
  const auto clean = [](const std::string& s, bool ascii_only) {
    for (const char c : s) {
      const unsigned char b = static_cast<unsigned char>(c);
      if (b < 0x20 || b == 0x7F || (ascii_only && b >= 0x80)) return false;
    }
    return true;
  };
  for (unsigned a = 0; a < 256; ++a)
    for (unsigned b = 0; b < 256; ++b) {
      const std::string in{static_cast<char>(a), static_cast<char>(b)};
      ASSERT_TRUE(clean(terminal_text(in), true)) << a << " " << b;
      const std::string j = json_string(in);
      ASSERT_TRUE(clean(j, false)) << a << " " << b;
      ASSERT_EQ(j.front(), '"');
      ASSERT_EQ(j.back(), '"');
    }
}

}  // namespace
