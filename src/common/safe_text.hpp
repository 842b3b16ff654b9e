#pragma once
// Names that reach a shell script, a CSV file, a log line or a terminal are checked here: one
// place says which characters could end a line, a field or a command (docs/hardening.md).
#include <optional>
#include <string>
#include <string_view>

namespace rcsim {

// The first character of `text` that breaks a line or controls a terminal: the C0 controls
// (U+0000-U+001F: NUL, tab, newline, carriage return, escape...), DEL, the C1 controls
// (U+0080-U+009F) and the Unicode line and paragraph separators U+2028 and U+2029; or invalid
// UTF-8. Described for a message ("a newline (U+000A) at byte 3"); nullopt if there is none.
std::optional<std::string> find_control_character(std::string_view text);

// `text` with every character find_control_character() would name written out instead: a C0
// control or DEL as \xNN, a C1 control or U+2028/U+2029 as \u{NNNN}, each byte of invalid UTF-8
// as \xNN. What is printed to a terminal passes here once (the command line's error messages), so
// an input's bytes can neither erase a message nor forge a line after it (issue 51).
std::string escape_control_characters(std::string_view text);

// Whether `name` is a plain name: 1 to `max_length` ASCII letters, digits, '.', '_', '-' and '+',
// starting with a letter or digit. Such a name goes unquoted into a shell script, an sbatch option,
// a file name and a CSV field.
bool is_plain_name(std::string_view name, std::size_t max_length = 64);

// `text` single-quoted for a POSIX shell: one word, whatever it holds.
std::string shell_quoted(std::string_view text);

}  // namespace rcsim
