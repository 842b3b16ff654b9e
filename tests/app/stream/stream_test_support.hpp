#pragma once
// Helpers for the loopback tests: reference rows from the simulator, a streamer and listeners
// on threads, child processes with their output in files.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "test_support.hpp"

extern char** environ;

namespace rcsim::stream::testing {

namespace fs = std::filesystem;

using rcsim::testing::simulate_rows;

// Tests that expect every datagram to arrive stream paced, eight times real time: at `--speed
// max` a listener thread descheduled on a loaded machine (sanitizer build, tests in parallel)
// can overflow the kernel's receive buffer, and the datagrams are rightly counted as lost.
constexpr double kLosslessSpeed = 8.0;

inline std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("rcsim_stream_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A child process with stdout and stderr in files.
struct Child {
  pid_t pid = -1;
  // Waits up to timeout; returns the exit status, or -1 (and kills the child) on timeout.
  int wait(std::chrono::milliseconds timeout = std::chrono::seconds(20)) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      int status = 0;
      if (::waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    return -1;
  }
};

inline Child spawn(const std::vector<std::string>& args, const fs::path& out, const fs::path& err) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  Child child;
  if (posix_spawnp(&child.pid, argv[0], &actions, nullptr, argv.data(), environ) != 0) child.pid = -1;
  posix_spawn_file_actions_destroy(&actions);
  return child;
}

// Waits until `file` contains `text` (a child's "listening on" line); returns what it holds.
inline std::string wait_for_text(const fs::path& file, const std::string& text,
                                 std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  std::string content;
  while (std::chrono::steady_clock::now() < end) {
    content = read_file(file);
    if (content.find(text) != std::string::npos) return content;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return content;
}

// The port in "listening on 127.0.0.1:PORT".
inline std::string listening_port(const std::string& log) {
  const std::string key = "listening on 127.0.0.1:";
  const std::size_t at = log.find(key);
  if (at == std::string::npos) return {};
  std::size_t end = at + key.size();
  while (end < log.size() && std::isdigit(static_cast<unsigned char>(log[end]))) ++end;
  return log.substr(at + key.size(), end - at - key.size());
}

}  // namespace rcsim::stream::testing
