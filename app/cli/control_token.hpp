#pragma once
// The control token of `rcsim stream --control-token-file` and `rcsim listen --control-token-file`
// (docs/stream.md): read from a file, so that it never shows in a process list.
#include <optional>
#include <string>

namespace rcsim::cli {

// The token on the first line of `path` (a trailing newline or CR is not part of it); refuses,
// naming the file, one that is not 16 to 64 printable ASCII characters without spaces.
// Printed to stderr as a warning (not refused: a token shared by a group is a choice, docs/stream.md)
// where other users may read it (mode o+r) or change it (g+w, o+w), so that it is not taken
// without a word (issue 51).
std::string read_control_token(const std::string& path);

// That warning, or nullopt for a file only its owner (and group, reading) may use.
std::optional<std::string> control_token_file_warning(const std::string& path);

}  // namespace rcsim::cli
