#pragma once
// What a user mistyped on the command line, and what they probably meant: an option or a command
// that no command took, named with the closest known name (README, "Exit status": status 2).
#include <CLI/CLI.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace rcsim::cli {

// Edit distance with adjacent transpositions (optimal string alignment): "replya" is 1 from "replay".
std::size_t typing_distance(const std::string& a, const std::string& b);

// The known name `typed` most probably meant: the nearest within a distance that grows with the
// name's length, or the only one `typed` begins; nullopt when none is close.
std::optional<std::string> closest_name(const std::string& typed, const std::vector<std::string>& known);

// After a failed parse: the first argument that no command took, with a suggestion, e.g.
// "rcsim replay: unknown option '--sed'; did you mean '--seed'? (rcsim replay --help)";
// nullopt when every argument was taken (the parse failed for another reason).
std::optional<std::string> unknown_argument_message(const CLI::App& root);

}  // namespace rcsim::cli
