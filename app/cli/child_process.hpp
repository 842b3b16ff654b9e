#pragma once
// Child processes of rcsim campaign: the shards of run-local, and sbatch for submit. Started
// with posix_spawn (argument vectors, never a shell), waited for by pid.
#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace rcsim::cli {

// Starts `argv` (argv[0] looked up in PATH) with stdout and stderr appended to `log`; returns
// the pid. Throws if it cannot be started.
pid_t spawn_logged(const std::vector<std::string>& argv, const std::filesystem::path& log);

// Waits for the child; its exit status, or 128 + signal if a signal ended it.
int wait_for(pid_t pid);

// Runs `argv` to its end, capturing its stdout (stderr passes through); the exit status as
// wait_for gives it.
int run_captured(const std::vector<std::string>& argv, std::string& stdout_text);

// The running rcsim executable (/proc/self/exe).
std::filesystem::path this_executable();

}  // namespace rcsim::cli
