// Tests mirror the sources file by file (docs/architecture.md): every source of the product has a
// test named for it in the same place under tests/ (`src/` dropped), NAME_test.cpp or
// NAME_ASPECT_test.cpp, and every test there is named for a source (.cpp or header) of its folder.
// Tests of a user's path through several layers live apart, in the folders of kCrossCutting.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace rcsim::tests_mirror_sources_test {

namespace fs = std::filesystem;

// Not a mirror of a source folder: end-to-end runs of the binary, the golden run, hard cases,
// the fuzzers' regressions, the architecture itself, and the test build's hooks.
const std::set<std::string> kCrossCutting = {"architecture", "end_to_end", "fuzz", "golden", "hard_cases", "hooks"};

// The product's source folders, and where their tests are.
struct MirroredTop {
  std::string sources;  // relative to the checkout
  std::string tests;    // relative to tests/
};
const std::vector<MirroredTop> kTops = {{"src", ""}, {"metrics", "metrics"}, {"replay", "replay"}, {"app", "app"}};

bool starts_with_name(const std::string& test_stem, const std::string& source_stem) {
  return test_stem == source_stem || test_stem.rfind(source_stem + "_", 0) == 0;
}

// The stems (file names without extension) of the files with one of `extensions` in `dir`.
std::vector<std::string> stems_in(const fs::path& dir, const std::set<std::string>& extensions) {
  std::vector<std::string> stems;
  if (!fs::is_directory(dir)) return stems;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_regular_file() && extensions.count(entry.path().extension().string()) != 0) {
      stems.push_back(entry.path().stem().string());
    }
  }
  return stems;
}

std::vector<std::string> test_stems_in(const fs::path& dir) {
  std::vector<std::string> stems;
  for (const std::string& stem : stems_in(dir, {".cpp"})) {
    if (stem.size() > 5 && stem.compare(stem.size() - 5, 5, "_test") == 0) stems.push_back(stem.substr(0, stem.size() - 5));
  }
  return stems;
}

TEST(TestsMirrorSources, EverySourceHasATestNamedForIt) {
  const fs::path root = RCSIM_SOURCE_DIR;
  int sources = 0;
  for (const MirroredTop& top : kTops) {
    for (const auto& entry : fs::recursive_directory_iterator(root / top.sources)) {
      if (!entry.is_regular_file() || entry.path().extension() != ".cpp") continue;
      const std::string stem = entry.path().stem().string();
      if (stem == "main") continue;  // app/cli/main.cpp only calls run_command_line
      ++sources;
      const fs::path folder = fs::relative(entry.path().parent_path(), root / top.sources);
      const fs::path test_dir = root / "tests" / top.tests / folder;
      const std::vector<std::string> tests = test_stems_in(test_dir);
      const bool tested = std::any_of(tests.begin(), tests.end(), [&](const std::string& t) { return starts_with_name(t, stem); });
      EXPECT_TRUE(tested) << fs::relative(entry.path(), root).string() << " has no test named for it in "
                          << fs::relative(test_dir, root).string() << "/ (" << stem << "_test.cpp)";
    }
  }
  EXPECT_GT(sources, 150);
}

TEST(TestsMirrorSources, EveryTestInAMirroredFolderIsNamedForASourceThere) {
  const fs::path root = RCSIM_SOURCE_DIR;
  const fs::path tests_root = root / "tests";
  int tests = 0;
  for (const auto& entry : fs::recursive_directory_iterator(tests_root)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = entry.path().filename().string();
    if (name.size() < 9 || name.compare(name.size() - 9, 9, "_test.cpp") != 0) continue;
    const fs::path folder = fs::relative(entry.path().parent_path(), tests_root);
    if (kCrossCutting.count(folder.begin()->string()) != 0) continue;
    ++tests;
    // tests/app/cli/ mirrors app/cli/, tests/replay/run/ replay/run/, tests/sim/ src/sim/.
    const std::string first = folder.begin()->string();
    const fs::path source_dir = (first == "metrics" || first == "replay" || first == "app") ? root / folder : root / "src" / folder;
    const std::string stem = name.substr(0, name.size() - 9);
    const std::vector<std::string> sources = stems_in(source_dir, {".cpp", ".hpp"});
    const bool named = std::any_of(sources.begin(), sources.end(), [&](const std::string& s) { return starts_with_name(stem, s); });
    EXPECT_TRUE(named) << fs::relative(entry.path(), root).string() << " is named for no source in "
                       << fs::relative(source_dir, root).string() << "/; a test across layers goes to tests/end_to_end/";
  }
  EXPECT_GT(tests, 150);
}

}  // namespace rcsim::tests_mirror_sources_test
