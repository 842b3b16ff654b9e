#pragma once
// The command line of the programs in bench/: --help (or -h) prints the usage and ends with 0;
// an unknown option, a wrong number of arguments or a number that is none prints the usage and
// ends with 2 (as rcsim does, README "Exit status"), before anything is written.
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

namespace rcsim::bench_tools {

struct ToolUsage {
  const char* name;         // the executable, e.g. "rcsim_make_long_recording"
  const char* arguments;    // e.g. "OUTPUT_DIR [DURATION_S=3600] [SEED=1]"
  const char* description;  // what it does, a few lines
  std::size_t min_arguments = 1;
  std::size_t max_arguments = 1;
};

inline void print_tool_usage(std::ostream& out, const ToolUsage& usage) {
  out << "usage: " << usage.name << ' ' << usage.arguments << "\n\n" << usage.description << '\n';
}

inline bool is_help_argument(const std::string& argument) { return argument == "--help" || argument == "-h"; }

// A refusal: what is wrong, then the usage, on stderr; the exit status to end with.
inline int refuse_command_line(const ToolUsage& usage, const std::string& why) {
  std::cerr << usage.name << ": " << why << '\n';
  print_tool_usage(std::cerr, usage);
  return 2;
}

// The positional arguments, or nullopt with `exit_status` set: 0 after --help, 2 after a wrong
// command line. An argument starting with '-' is an option, and the only options are -h, --help.
inline std::optional<std::vector<std::string>> tool_arguments(int argc, char** argv, const ToolUsage& usage,
                                                              int& exit_status) {
  std::vector<std::string> arguments(argv + 1, argv + argc);
  for (const std::string& argument : arguments) {
    if (is_help_argument(argument)) {
      print_tool_usage(std::cout, usage);
      exit_status = 0;
      return std::nullopt;
    }
  }
  for (const std::string& argument : arguments) {
    if (argument.size() > 1 && argument[0] == '-') {
      exit_status = refuse_command_line(usage, "unknown option '" + argument + "'");
      return std::nullopt;
    }
  }
  if (arguments.size() < usage.min_arguments || arguments.size() > usage.max_arguments) {
    const std::string expected = usage.min_arguments == usage.max_arguments
                                     ? std::to_string(usage.min_arguments)
                                     : std::to_string(usage.min_arguments) + " to " + std::to_string(usage.max_arguments);
    exit_status = refuse_command_line(usage, "takes " + expected + " arguments, got " + std::to_string(arguments.size()));
    return std::nullopt;
  }
  return arguments;
}

// The whole text as a number of type T (from_chars: no sign for unsigned types, no trailing text).
template <typename T>
std::optional<T> number_argument(const std::string& text) {
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace rcsim::bench_tools
