#pragma once
// What a user mistyped, and what they probably meant: the closest of a list of known names (a
// command, an option, a built-in sensor profile), by edit distance.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace rcsim {

// Edit distance with adjacent transpositions (optimal string alignment): "replya" is 1 from "replay".
std::size_t typing_distance(const std::string& a, const std::string& b);

// The known name `typed` most probably meant: the nearest within a distance that grows with the
// name's length (one typo per three letters, at most three; leading dashes ignored), or the only
// one `typed` begins; nullopt when none is close.
std::optional<std::string> closest_name(const std::string& typed, const std::vector<std::string>& known);

// "a, b, c".
std::string join_names(const std::vector<std::string>& names);

}  // namespace rcsim
