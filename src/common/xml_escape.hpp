#pragma once
// Text for XML and HTML (the report's HTML and SVG, JUnit): the five markup characters as
// entities, and the control characters XML 1.0 cannot hold (all below U+0020 but tab, newline and
// carriage return) as U+FFFD, so that any recording's name makes a well-formed document.
#include <string>
#include <string_view>

namespace rcsim {

std::string xml_escape(std::string_view text);

}  // namespace rcsim
