#pragma once
// The libFuzzer side of a harness (tests/fuzz/*_fuzz.cpp): runs an entry point on one input and
// turns an exception that escaped it (not a refusal, fuzz_support.hpp) into a crash libFuzzer
// reports and saves; and writes a harness's generated seeds when scripts/fuzz.sh asks for them.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cxxabi.h>
#include <exception>
#include <filesystem>
#include <memory>
#include <typeinfo>
#include <utility>
#include <vector>

#include "fuzz/fuzz_support.hpp"

namespace rcsim::fuzz {

inline int run_one(void (*entry)(Input), const std::uint8_t* data, std::size_t size) {
  try {
    entry(Input(data, size));
  } catch (const std::exception& e) {
    int status = 0;
    const std::unique_ptr<char, void (*)(void*)> type(abi::__cxa_demangle(typeid(e).name(), nullptr, nullptr, &status), std::free);
    std::fprintf(stderr, "==rcsim-fuzz== uncaught %s: %s\n", status == 0 ? type.get() : typeid(e).name(), e.what());
    std::abort();
  }
  return 0;
}

// With RCSIM_FUZZ_WRITE_SEEDS=DIR in the environment: writes the seeds into DIR and exits.
inline void write_seeds_if_asked(const std::vector<std::pair<std::string, std::vector<std::uint8_t>>>& seeds) {
  const char* dir = std::getenv("RCSIM_FUZZ_WRITE_SEEDS");
  if (dir == nullptr) return;
  std::filesystem::create_directories(dir);
  for (const auto& [name, bytes] : seeds) {
    write_file(std::filesystem::path(dir) / name, {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
  }
  std::exit(0);
}

}  // namespace rcsim::fuzz
