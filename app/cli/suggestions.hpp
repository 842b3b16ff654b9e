#pragma once
// What a user mistyped on the command line, and what they probably meant: an option or a command
// that no command took, named with the closest known name (README, "Exit status": status 2).
#include <CLI/CLI.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "common/closest_name.hpp"

namespace rcsim::cli {

// After a failed parse: the first argument that no command took, with a suggestion, e.g.
// "rcsim replay: unknown option '--sed'; did you mean '--seed'? (rcsim replay --help)";
// nullopt when every argument was taken (the parse failed for another reason).
std::optional<std::string> unknown_argument_message(const CLI::App& root);

}  // namespace rcsim::cli
