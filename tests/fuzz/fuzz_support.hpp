#pragma once
// What every fuzz entry point shares (docs/fuzzing.md): the input as text, split into the files of
// a bundle; a scratch directory of the process; the fixed base files an input is laid over; and
// the line between a refusal (an exception the command line turns into a message: fine) and a
// finding (anything else: a crash, a sanitizer report, or an exception that should not escape).
//
// Header-only, so that the libFuzzer harnesses (tests/fuzz/*_fuzz.cpp, built with -DRCSIM_FUZZ=ON)
// and the regression test in the ordinary build (tests/fuzz/fuzz_regressions_test.cpp) run the
// same code on the same bytes.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <unistd.h>

#include "common/input_error.hpp"

#ifndef RCSIM_SOURCE_DIR
#error "RCSIM_SOURCE_DIR must name the source tree (the base files are read from tests/fuzz/base/)"
#endif

namespace rcsim::fuzz {

using Input = std::span<const std::uint8_t>;

inline std::string_view as_text(Input data) {
  return {reinterpret_cast<const char*>(data.data()), data.size()};
}

// A bundle is several files in one input, separated by this line (the dictionaries hold it):
// section i replaces file i of the harness's base; an empty or missing section keeps the base's.
inline constexpr std::string_view kSectionSeparator = "\n=====\n";

inline std::vector<std::string_view> split_sections(std::string_view text) {
  std::vector<std::string_view> sections;
  for (;;) {
    const std::size_t at = text.find(kSectionSeparator);
    if (at == std::string_view::npos) break;
    sections.push_back(text.substr(0, at));
    text.remove_prefix(at + kSectionSeparator.size());
  }
  sections.push_back(text);
  return sections;
}

// Section i of `input` if it is there and not empty, else section i of `base`.
inline std::string_view section_or_base(const std::vector<std::string_view>& input, const std::vector<std::string_view>& base,
                                        std::size_t i) {
  if (i < input.size() && !input[i].empty()) return input[i];
  return i < base.size() ? base[i] : std::string_view();
}

// A checked-in base file, tests/fuzz/base/NAME, read once.
inline std::string read_source_file(const std::filesystem::path& relative) {
  const std::filesystem::path path = std::filesystem::path(RCSIM_SOURCE_DIR) / relative;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "fuzz: cannot read %s\n", path.c_str());
    std::abort();
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void write_file(const std::filesystem::path& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
}

// The four files of a recording from their sections (recording.json, ego.csv, objects.csv,
// targets.csv). A CSV section gets the line end every writer puts after its last line where it has
// none (a recording refuses a CSV without one as cut short): the fuzzers vary the rows, not that.
inline void write_recording_sections(const std::filesystem::path& dir, const std::vector<std::string_view>& sections) {
  static constexpr const char* kFiles[] = {"recording.json", "ego.csv", "objects.csv", "targets.csv"};
  for (std::size_t i = 0; i < std::size(kFiles) && i < sections.size(); ++i) {
    std::string text(sections[i]);
    if (i > 0 && !text.empty() && text.back() != '\n') text += '\n';
    write_file(dir / kFiles[i], text);
  }
}

// A directory of this process under the system's temporary directory, removed at exit.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "rcsim_fuzz_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      std::perror("fuzz: mkdtemp");
      std::abort();
    }
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// A fresh (emptied) subdirectory `name` of the process's scratch directory.
inline std::filesystem::path fresh_dir(std::string_view name) {
  static const ScratchDir scratch;
  const std::filesystem::path dir = scratch.path() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A library's own message (std::vector::at's "vector::_M_range_check: ...", std::stod's "stod"):
// an exception that reached the user without naming the file and field, so a finding.
inline bool is_library_message(std::string_view what) {
  static constexpr std::string_view kConversions[] = {"stoi", "stol", "stoul", "stoll", "stoull", "stof", "stod", "stold"};
  for (std::string_view name : kConversions) {
    if (what == name) return true;
  }
  const std::size_t colons = what.find("::");
  if (colons == std::string_view::npos || colons == 0) return false;
  for (char c : what.substr(0, colons)) {
    if (!((c >= 'a' && c <= 'z') || c == '_')) return false;
  }
  return true;
}

// Thrown for what a harness checks beyond "does not crash" (a decoded datagram that does not
// survive encoding again, an imported recording rcsim cannot read back).
class Finding : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

// Runs `body`; returns normally when it succeeds or refuses the input the way rcsim refuses bad
// input: rcsim::InputError, or std::invalid_argument / std::out_of_range with a message of
// rcsim's own ("unknown sensor type ..."). Every other exception propagates: std::bad_alloc and
// std::length_error (a size taken from the input), nlohmann::json's type errors (a value used
// unchecked), library messages (vector::at), Finding.
template <class Body>
void refusals_are_fine(Body&& body) {
  try {
    body();
  } catch (const InputError&) {
  } catch (const std::invalid_argument& e) {
    if (is_library_message(e.what())) throw;
  } catch (const std::out_of_range& e) {
    if (is_library_message(e.what())) throw;
  }
}

}  // namespace rcsim::fuzz
