#pragma once
// The recordings a command works on: the ones named, else every directory with a recording.json
// in ./recordings_synthetic (sorted by name).
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "common/input_error.hpp"

namespace rcsim::cli {

inline std::vector<std::filesystem::path> recording_dirs(const std::vector<std::string>& named) {
  std::vector<std::filesystem::path> dirs(named.begin(), named.end());
  if (!dirs.empty()) return dirs;
  const std::filesystem::path bundled = "recordings_synthetic";
  if (std::filesystem::is_directory(bundled)) {
    for (const auto& entry : std::filesystem::directory_iterator(bundled)) {
      if (std::filesystem::is_regular_file(entry.path() / "recording.json")) dirs.push_back(entry.path());
    }
  }
  if (dirs.empty()) {
    throw InputError("recordings_synthetic", "", "no recording named and none found here; name RECORDING_DIRs");
  }
  std::sort(dirs.begin(), dirs.end());
  return dirs;
}

}  // namespace rcsim::cli
