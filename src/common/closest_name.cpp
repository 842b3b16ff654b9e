#include "common/closest_name.hpp"

#include <algorithm>
#include <limits>

namespace rcsim {
namespace {

std::string without_dashes(const std::string& name) { return name.substr(std::min(name.find_first_not_of('-'), name.size())); }

// How far a name may be from what was typed: one typo per three letters, at most three; one or
// two letters only with other dashes ("--o": "-o") or swapped ("--bd": "--db"), else any short
// name would do.
bool within_typos(const std::string& typed, const std::string& name, std::size_t distance) {
  if (typed.size() <= 2) {
    return distance == 0 || (distance == 1 && typed.size() == name.size() && std::is_permutation(typed.begin(), typed.end(), name.begin()));
  }
  return distance <= std::clamp<std::size_t>(typed.size() / 3, 1, 3);
}

}  // namespace

std::size_t typing_distance(const std::string& a, const std::string& b) {
  // d[i][j]: distance between the first i letters of a and the first j of b.
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

std::optional<std::string> closest_name(const std::string& typed, const std::vector<std::string>& known) {
  const std::string word = without_dashes(typed);
  std::optional<std::string> nearest, only_extension;
  std::size_t nearest_distance = std::numeric_limits<std::size_t>::max(), extensions = 0;
  for (const std::string& name : known) {
    const std::string candidate = without_dashes(name);
    const std::size_t distance = typing_distance(word, candidate);
    if (distance < nearest_distance && within_typos(word, candidate, distance)) nearest_distance = distance, nearest = name;
    if (word.size() >= 3 && candidate.starts_with(word)) ++extensions, only_extension = name;
  }
  if (nearest) return nearest;
  if (extensions == 1) return only_extension;
  return std::nullopt;
}

std::string join_names(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

}  // namespace rcsim
