// Text for XML and HTML (common/xml_escape.hpp): the five markup characters as entities, the
// control characters XML 1.0 cannot hold as U+FFFD, everything else as it was.
#include "common/xml_escape.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rcsim::xml_escape_test {

TEST(XmlEscape, MarkupCharactersBecomeEntities) {
  EXPECT_EQ(xml_escape(""), "");
  EXPECT_EQ(xml_escape("front_left 24 GHz"), "front_left 24 GHz");
  EXPECT_EQ(xml_escape("<a href=\"x\">Tom & Jerry's</a>"),
            "&lt;a href=&quot;x&quot;&gt;Tom &amp; Jerry&#39;s&lt;/a&gt;");
  EXPECT_EQ(xml_escape("&amp;"), "&amp;amp;");  // escaped again: text, not markup
}

TEST(XmlEscape, ControlCharactersXmlCannotHoldBecomeTheReplacementCharacter) {
  const std::string replacement = "\xEF\xBF\xBD";  // U+FFFD in UTF-8
  // Tab, newline and carriage return are allowed in XML 1.0 and kept; NUL, 0x01 and 0x1F are not.
  EXPECT_EQ(xml_escape(std::string("a\0b\x01" "c\td\ne\rf\x1F", 12)),
            "a" + replacement + "b" + replacement + "c\td\ne\rf" + replacement);
  EXPECT_EQ(xml_escape("\x1B[31m"), replacement + "[31m");
  // Bytes of multi-byte UTF-8 (here é and €) and DEL are no such control characters.
  EXPECT_EQ(xml_escape("caf\xC3\xA9 \xE2\x82\xAC\x7F"), "caf\xC3\xA9 \xE2\x82\xAC\x7F");
}

}  // namespace rcsim::xml_escape_test
