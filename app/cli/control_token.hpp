#pragma once
// The control token of `rcsim stream --control-token-file` and `rcsim listen --control-token-file`
// (docs/stream.md): read from a file, so that it never shows in a process list.
#include <string>

namespace rcsim::cli {

// The token on the first line of `path` (a trailing newline or CR is not part of it); refuses,
// naming the file, one that is not 16 to 64 printable ASCII characters without spaces.
std::string read_control_token(const std::string& path);

}  // namespace rcsim::cli
