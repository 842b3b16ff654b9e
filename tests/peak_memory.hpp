#pragma once
// The peak resident memory an action adds, in bytes: the kernel's high-water mark (VmHWM of
// /proc/self/status) reset before it (writing 5 to /proc/self/clear_refs) and read after it. For
// the tests that a hostile input is refused before what it claims is allocated. Returns nullopt
// where the kernel does not allow the reset (the caller then checks the message alone).
#include <cstdint>
#include <fstream>
#include <optional>
#include <string>

namespace rcsim::testing {

inline std::optional<std::int64_t> resident_bytes(const char* key) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind(key, 0) == 0) return std::stoll(line.substr(line.find(':') + 1)) * 1024;  // in kB
  }
  return std::nullopt;
}

template <typename F>
std::optional<std::int64_t> peak_memory_added_by(F&& act) {
  {
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5";
    if (!clear.flush()) {
      act();
      return std::nullopt;
    }
  }
  const std::optional<std::int64_t> before = resident_bytes("VmRSS:");
  act();
  const std::optional<std::int64_t> peak = resident_bytes("VmHWM:");
  if (!before || !peak) return std::nullopt;
  return *peak - *before;
}

}  // namespace rcsim::testing
