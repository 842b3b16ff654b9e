#include "common/safe_text.hpp"

#include <fmt/format.h>

namespace rcsim {

namespace {

std::string described(char32_t code, std::size_t byte) {
  const char* what = code == U'\n'   ? "a newline"
                     : code == U'\r' ? "a carriage return"
                     : code == U'\t' ? "a tab"
                     : code == 0     ? "a NUL"
                     : code == 0x1b  ? "an escape"
                     : code == 0x2028 || code == 0x2029 ? "a line separator"
                                                        : "a control character";
  return fmt::format("{} (U+{:04X}) at byte {}", what, static_cast<std::uint32_t>(code), byte);
}

}  // namespace

std::optional<std::string> find_control_character(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const auto lead = static_cast<unsigned char>(text[i]);
    if (lead < 0x80) {
      if (lead < 0x20 || lead == 0x7f) return described(lead, i);
      ++i;
      continue;
    }
    // A multi-byte UTF-8 sequence: its length from the lead byte, its code point from the rest.
    std::size_t length = 0;
    if (lead >= 0xc2 && lead <= 0xdf) length = 2;
    if (lead >= 0xe0 && lead <= 0xef) length = 3;
    if (lead >= 0xf0 && lead <= 0xf4) length = 4;
    if (length == 0 || i + length > text.size()) return fmt::format("invalid UTF-8 at byte {}", i);
    char32_t code = lead & (length == 2 ? 0x1f : length == 3 ? 0x0f : 0x07);
    for (std::size_t k = 1; k < length; ++k) {
      const auto next = static_cast<unsigned char>(text[i + k]);
      if ((next & 0xc0) != 0x80) return fmt::format("invalid UTF-8 at byte {}", i);
      code = (code << 6) | (next & 0x3f);
    }
    const char32_t smallest = length == 2 ? 0x80 : length == 3 ? 0x800 : 0x10000;
    if (code < smallest || code > 0x10ffff || (code >= 0xd800 && code < 0xe000)) {
      return fmt::format("invalid UTF-8 at byte {}", i);
    }
    if (code < 0xa0 || code == 0x2028 || code == 0x2029) return described(code, i);
    i += length;
  }
  return std::nullopt;
}

std::string escape_control_characters(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto lead = static_cast<unsigned char>(text[i]);
    if (lead < 0x80) {
      if (lead < 0x20 || lead == 0x7f) {
        out += fmt::format("\\x{:02X}", lead);
      } else {
        out += static_cast<char>(lead);
      }
      ++i;
      continue;
    }
    std::size_t length = 0;
    if (lead >= 0xc2 && lead <= 0xdf) length = 2;
    if (lead >= 0xe0 && lead <= 0xef) length = 3;
    if (lead >= 0xf0 && lead <= 0xf4) length = 4;
    bool valid = length != 0 && i + length <= text.size();
    char32_t code = lead & (length == 2 ? 0x1f : length == 3 ? 0x0f : 0x07);
    for (std::size_t k = 1; valid && k < length; ++k) {
      const auto next = static_cast<unsigned char>(text[i + k]);
      if ((next & 0xc0) != 0x80) valid = false;
      code = (code << 6) | (next & 0x3f);
    }
    const char32_t smallest = length == 2 ? 0x80 : length == 3 ? 0x800 : 0x10000;
    if (valid && (code < smallest || code > 0x10ffff || (code >= 0xd800 && code < 0xe000))) valid = false;
    if (!valid) {
      // One byte at a time: the next may start a valid sequence.
      out += fmt::format("\\x{:02X}", lead);
      ++i;
      continue;
    }
    if (code < 0xa0 || code == 0x2028 || code == 0x2029) {
      out += fmt::format("\\u{{{:04X}}}", static_cast<std::uint32_t>(code));
    } else {
      out.append(text.substr(i, length));
    }
    i += length;
  }
  return out;
}

bool is_plain_name(std::string_view name, std::size_t max_length) {
  if (name.empty() || name.size() > max_length) return false;
  const auto alnum = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'); };
  if (!alnum(name.front())) return false;
  for (const char c : name) {
    if (!alnum(c) && c != '.' && c != '_' && c != '-' && c != '+') return false;
  }
  return true;
}

std::string shell_quoted(std::string_view text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace rcsim
