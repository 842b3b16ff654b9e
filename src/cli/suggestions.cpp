#include "cli/suggestions.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <limits>

namespace rcsim::cli {

namespace {

bool is_option_like(const std::string& argument) { return argument.size() > 1 && argument[0] == '-'; }

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

// "rcsim campaign plan": the command's words, the executable named as the user knows it.
std::string command_path(const CLI::App& app) {
  const CLI::App* parent = app.get_parent();
  return parent == nullptr ? std::string("rcsim") : command_path(*parent) + " " + app.get_name();
}

// The commands parsed, outermost first.
std::vector<const CLI::App*> parsed_chain(const CLI::App& root) {
  std::vector<const CLI::App*> chain{&root};
  for (;;) {
    const std::vector<CLI::App*> parsed = chain.back()->get_subcommands();
    if (parsed.empty()) return chain;
    chain.push_back(parsed.front());
  }
}

std::vector<std::string> option_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* option : app.get_options()) {
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
    for (const std::string& name : option->get_snames()) names.push_back("-" + name);
  }
  return names;
}

std::vector<std::string> subcommand_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) names.push_back(sub->get_name());
  return names;
}

std::string join_names(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

std::string unknown_option_message(const CLI::App& app, const std::string& argument) {
  const std::string typed = argument.substr(0, argument.find('='));  // --sed=1: the name alone
  const std::string path = command_path(app);
  if (const auto meant = closest_name(typed, option_names(app))) {
    return fmt::format("{}: unknown option '{}'; did you mean '{}'? ({} --help)", path, typed, *meant, path);
  }
  return fmt::format("{}: unknown option '{}' ({} --help lists the options)", path, typed, path);
}

std::string unexpected_word_message(const CLI::App& app, const std::string& argument) {
  const std::string path = command_path(app);
  const std::vector<std::string> commands = subcommand_names(app);
  if (commands.empty()) return fmt::format("{}: unexpected argument '{}' ({} --help)", path, argument, path);
  if (const auto meant = closest_name(argument, commands)) {
    return fmt::format("{}: unknown command '{}'; did you mean '{}'? ({} --help)", path, argument, *meant, path);
  }
  return fmt::format("{}: unknown command '{}' (commands: {}; {} --help)", path, argument, join_names(commands), path);
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

std::optional<std::string> unknown_argument_message(const CLI::App& root) {
  const std::vector<const CLI::App*> chain = parsed_chain(root);
  for (auto app = chain.rbegin(); app != chain.rend(); ++app) {
    const std::vector<std::string> left = (*app)->remaining(false);
    if (left.empty()) continue;
    // "rcsim replya --seed 1": the command is what went wrong, not its options.
    const bool word_first = !is_option_like(left.front());
    if (word_first && !subcommand_names(**app).empty()) return unexpected_word_message(**app, left.front());
    const auto option = std::find_if(left.begin(), left.end(), is_option_like);
    return option != left.end() ? unknown_option_message(**app, *option) : unexpected_word_message(**app, left.front());
  }
  return std::nullopt;
}

}  // namespace rcsim::cli
