#include "cli/suggestions.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <limits>

#include "common/closest_name.hpp"

namespace rcsim::cli {

namespace {

bool is_option_like(const std::string& argument) { return argument.size() > 1 && argument[0] == '-'; }

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
