#pragma once
// Runs the rcsim binary as a user would, capturing its output.
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace rcsim::testing {

struct CommandResult {
  int exit_code;
  std::string output;  // stdout, and stderr unless separated
};

// `rcsim ARGS` through the shell; stderr joins stdout unless with_stderr is false.
inline CommandResult run_rcsim(const std::string& args, bool with_stderr = true) {
  const std::string command = std::string(RCSIM_BINARY) + " " + args + (with_stderr ? " 2>&1" : " 2>/dev/null");
  CommandResult result{0, {}};
  FILE* pipe = popen(command.c_str(), "r");
  std::array<char, 4096> buffer{};
  while (const std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WEXITSTATUS(status);
  return result;
}

// A whole shell command line (several commands, pipes, redirections), stderr joined to stdout.
inline CommandResult run_shell_command(const std::string& command) {
  CommandResult result{0, {}};
  FILE* pipe = popen(("(" + command + ") 2>&1").c_str(), "r");
  std::array<char, 4096> buffer{};
  while (const std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
  result.exit_code = WEXITSTATUS(pclose(pipe));
  return result;
}

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// `rcsim ARGS` with stderr joined, ended after 60 s should it wait for something (a socket).
inline CommandResult run_rcsim_with_timeout(const std::string& args) {
  return run_shell_command("timeout 60 " + std::string(RCSIM_BINARY) + " " + args);
}

inline bool output_has(const CommandResult& r, const std::string& text) { return r.output.find(text) != std::string::npos; }

}  // namespace rcsim::testing
