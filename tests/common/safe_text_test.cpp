// Names that reach a shell, a CSV file or a terminal (common/safe_text.hpp): which characters
// break a line or control a terminal, what invalid UTF-8 is, plain names and shell quoting.
#include "common/safe_text.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rcsim::safe_text_test {

TEST(SafeText, ControlCharactersAreNamedWithTheirByte) {
  EXPECT_EQ(find_control_character("front_left"), std::nullopt);
  EXPECT_EQ(find_control_character(""), std::nullopt);
  EXPECT_EQ(find_control_character("Stra\xC3\x9F" "e \xE2\x82\xAC \xF0\x9F\x9A\x97"), std::nullopt);  // ß, €, a car
  EXPECT_EQ(find_control_character("a\nb"), "a newline (U+000A) at byte 1");
  EXPECT_EQ(find_control_character("ab\r"), "a carriage return (U+000D) at byte 2");
  EXPECT_EQ(find_control_character("\tx"), "a tab (U+0009) at byte 0");
  EXPECT_EQ(find_control_character(std::string("x\0y", 3)), "a NUL (U+0000) at byte 1");
  EXPECT_EQ(find_control_character("\x1B[31mred"), "an escape (U+001B) at byte 0");
  EXPECT_EQ(find_control_character("ab\x7F"), "a control character (U+007F) at byte 2");  // DEL
  // C1 controls and the separators are counted by the byte their sequence starts at.
  EXPECT_EQ(find_control_character("\xC3\xA9\xC2\x85"), "a control character (U+0085) at byte 2");  // é, NEL
  EXPECT_EQ(find_control_character("abc\xE2\x80\xA8"), "a line separator (U+2028) at byte 3");
  EXPECT_EQ(find_control_character("\xE2\x80\xA9"), "a line separator (U+2029) at byte 0");
  EXPECT_EQ(find_control_character("\xC2\xA0"), std::nullopt);  // U+00A0, the first after C1
}

TEST(SafeText, InvalidUtf8IsNamedByItsByte) {
  EXPECT_EQ(find_control_character("ab\xFF"), "invalid UTF-8 at byte 2");          // no lead byte
  EXPECT_EQ(find_control_character("a\x80"), "invalid UTF-8 at byte 1");           // a lone continuation
  EXPECT_EQ(find_control_character("\xC0\x8A"), "invalid UTF-8 at byte 0");        // overlong newline
  EXPECT_EQ(find_control_character("\xE0\x80\x8A"), "invalid UTF-8 at byte 0");    // overlong, 3 bytes
  EXPECT_EQ(find_control_character("xy\xE2\x82"), "invalid UTF-8 at byte 2");      // cut short
  EXPECT_EQ(find_control_character("\xE2\x41\x41"), "invalid UTF-8 at byte 0");    // not a continuation
  EXPECT_EQ(find_control_character("\xED\xA0\x80"), "invalid UTF-8 at byte 0");    // surrogate U+D800
  EXPECT_EQ(find_control_character("\xF4\x90\x80\x80"), "invalid UTF-8 at byte 0");  // U+110000
}

TEST(SafeText, PlainNamesAreShortAsciiWordsStartingWithALetterOrDigit) {
  EXPECT_TRUE(is_plain_name("srr24"));
  EXPECT_TRUE(is_plain_name("0.5_run-b+c"));
  EXPECT_FALSE(is_plain_name(""));
  EXPECT_FALSE(is_plain_name("-rf"));       // an option to a shell command
  EXPECT_FALSE(is_plain_name(".hidden"));
  EXPECT_FALSE(is_plain_name("a b"));
  EXPECT_FALSE(is_plain_name("a/b"));
  EXPECT_FALSE(is_plain_name("a;b"));
  EXPECT_FALSE(is_plain_name("caf\xC3\xA9"));  // é is not ASCII
  EXPECT_TRUE(is_plain_name(std::string(64, 'a')));
  EXPECT_FALSE(is_plain_name(std::string(65, 'a')));
  EXPECT_TRUE(is_plain_name("abc", 3));
  EXPECT_FALSE(is_plain_name("abcd", 3));
}

TEST(SafeText, ShellQuotingMakesOneWordOfAnything) {
  EXPECT_EQ(shell_quoted("plain"), "'plain'");
  EXPECT_EQ(shell_quoted(""), "''");
  EXPECT_EQ(shell_quoted("$(rm -rf ~) `x` \"y\""), "'$(rm -rf ~) `x` \"y\"'");
  // A single quote ends the quoting, is escaped, and the quoting resumes: 'it'\''s'.
  EXPECT_EQ(shell_quoted("it's"), "'it'\\''s'");
  EXPECT_EQ(shell_quoted("''"), "''\\'''\\'''");
}

// Issue 51: a message quoting the input writes its control characters out, so a terminal escape
// can neither erase the message nor forge a line after it; printable text, UTF-8 included, stays.
TEST(SafeText, EscapingWritesOutEveryControlCharacterAndNoOtherText) {
  EXPECT_EQ(escape_control_characters("car\x1b[2K\rrcsim: done\n"), "car\\x1B[2K\\x0Drcsim: done\\x0A");
  EXPECT_EQ(escape_control_characters(std::string("a\0b\x7f", 4)), "a\\x00b\\x7F");
  EXPECT_EQ(escape_control_characters("caf\xc3\xa9 \xe2\x82\xac 50"), "caf\xc3\xa9 \xe2\x82\xac 50");
  EXPECT_EQ(escape_control_characters("\xc2\x9b" "2J"), "\\u{009B}2J");                 // C1 CSI
  EXPECT_EQ(escape_control_characters("a\xe2\x80\xa8" "b"), "a\\u{2028}b");             // line separator
  EXPECT_EQ(escape_control_characters("\xff\xc3(\xed\xa0\x80"), "\\xFF\\xC3(\\xED\\xA0\\x80");  // invalid UTF-8
  EXPECT_EQ(escape_control_characters("\xe2\x82"), "\\xE2\\x82");                     // cut short
  for (int c = 0; c < 256; ++c) {
    const std::string escaped = escape_control_characters(std::string(1, static_cast<char>(c)));
    EXPECT_FALSE(find_control_character(escaped).has_value()) << c << ": " << escaped;
  }
}

}  // namespace rcsim::safe_text_test
