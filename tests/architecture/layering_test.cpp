// The layers of docs/architecture.md, checked on the sources: every #include "dir/..." of a
// source file names its own layer or one below it. The static libraries enforce the same at link
// time for calls; this catches a header-only use upwards too, and names the file and line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace rcsim {
namespace {

namespace fs = std::filesystem;

// Layer of a source directory (relative to the source root) and of an include prefix.
const std::map<std::string, std::string> kLayerOfDir{
    {"src/common", "common"},   {"src/io", "io"},
    {"src/model", "world"},     {"src/scene", "world"},
    {"src/sensor", "world"},    {"metrics", "metrics"},
    {"src/sim", "sim"},         {"src/synth", "synth"},
    {"src/traffic", "traffic"}, {"replay/import", "replay_import"},
    {"replay/run", "replay_run"}, {"replay/evaluate", "replay_evaluate"},
    {"replay/calibrate", "replay_calibrate"}, {"replay/profile", "replay_profile"},
    {"replay/store", "replay_store"},       {"replay/verdict", "replay_verdict"},
    {"replay/store/extension", "replay_store_extension"},
    {"replay/campaign", "replay_campaign"}, {"replay/report", "replay_report"},
    {"app/stream", "stream"},
    {"app/cli", "cli"}};

const std::map<std::string, std::string> kLayerOfInclude{
    {"common", "common"},   {"io", "io"},         {"model", "world"},   {"scene", "world"},
    {"sensor", "world"},    {"metrics", "metrics"}, {"sim", "sim"},     {"synth", "synth"},
    {"traffic", "traffic"}, {"replay/import", "replay_import"},       {"replay/run", "replay_run"},
    {"replay/evaluate", "replay_evaluate"},     {"replay/calibrate", "replay_calibrate"},
    {"replay/profile", "replay_profile"},
    {"replay/store", "replay_store"},           {"replay/verdict", "replay_verdict"},
    {"replay/store/extension", "replay_store_extension"},
    {"replay/campaign", "replay_campaign"},
    {"replay/report", "replay_report"},
    {"stream", "stream"},   {"cli", "cli"}};

// What each layer may use besides itself (the DEPS of rcsim_layer in CMakeLists.txt, closed).
const std::map<std::string, std::set<std::string>> kMayUse{
    {"common", {}},
    {"io", {"common"}},
    {"world", {"common"}},
    {"metrics", {"common"}},
    {"sim", {"common", "io", "world"}},
    {"synth", {"common", "io", "world"}},  // never sim: the reference is independent of the model
    {"traffic", {"common", "world"}},
    {"replay_import", {"common", "io", "world"}},
    {"replay_run", {"common", "io", "world", "metrics", "sim", "synth", "replay_import"}},
    {"replay_evaluate", {"common", "io", "world", "metrics", "sim", "synth", "replay_import", "replay_run"}},
    {"replay_calibrate", {"common", "io", "world", "metrics", "sim", "synth", "replay_import", "replay_run"}},
    {"replay_profile",
     {"common", "io", "world", "metrics", "sim", "synth", "replay_import", "replay_run", "replay_calibrate"}},
    {"replay_store",
     {"common", "io", "world", "metrics", "sim", "synth", "replay_import", "replay_run", "replay_evaluate"}},
    // The SQLite extension (build/lib/rcsim.so): the store's tables for SQL clients; nothing uses it.
    {"replay_store_extension",
     {"common", "io", "world", "metrics", "sim", "synth", "replay_import", "replay_run", "replay_evaluate",
      "replay_store"}},
    {"replay_verdict",
     {"common", "io", "world", "metrics", "sim", "synth", "replay_import", "replay_run", "replay_evaluate",
      "replay_store"}},
    {"replay_campaign",
     {"common", "io", "world", "metrics", "sim", "synth", "replay_import", "replay_run", "replay_evaluate",
      "replay_store", "replay_verdict"}},
    {"replay_report",
     {"common", "io", "world", "metrics", "sim", "synth", "replay_import", "replay_run", "replay_evaluate",
      "replay_calibrate", "replay_profile", "replay_store", "replay_verdict", "replay_campaign"}},
    {"stream", {"common", "io", "world", "sim", "replay_import"}},
    {"cli",
     {"common", "io", "world", "metrics", "sim", "synth", "traffic", "replay_import", "replay_run", "replay_evaluate",
      "replay_calibrate", "replay_profile", "replay_store", "replay_verdict", "replay_campaign", "replay_report", "stream"}}};

std::string layer_of_include(const std::string& path) {
  // The longest prefix wins: "replay/run/x.hpp" before "replay".
  std::string best, layer;
  for (const auto& [prefix, l] : kLayerOfInclude) {
    if (path.rfind(prefix + "/", 0) == 0 && prefix.size() > best.size()) best = prefix, layer = l;
  }
  return layer;
}

TEST(Layering, EveryIncludeNamesItsOwnLayerOrOneBelow) {
  const fs::path root = RCSIM_SOURCE_DIR;
  const std::regex include_line(R"re(^\s*#\s*include\s+"([^"]+)")re");
  int files = 0;
  for (const auto& [dir, layer] : kLayerOfDir) {
    ASSERT_TRUE(fs::is_directory(root / dir)) << dir;
    for (const auto& entry : fs::directory_iterator(root / dir)) {
      const auto ext = entry.path().extension();
      if (ext != ".cpp" && ext != ".hpp") continue;
      ++files;
      std::ifstream in(entry.path());
      std::string line;
      for (int number = 1; std::getline(in, line); ++number) {
        std::smatch m;
        if (!std::regex_search(line, m, include_line)) continue;
        const std::string used = layer_of_include(m[1]);
        ASSERT_FALSE(used.empty()) << dir << "/" << entry.path().filename().string() << ":" << number
                                   << ": includes \"" << m[1] << "\", which is in no layer";
        EXPECT_TRUE(used == layer || kMayUse.at(layer).count(used))
            << dir << "/" << entry.path().filename().string() << ":" << number << ": layer " << layer
            << " includes \"" << m[1] << "\" of layer " << used;
      }
    }
  }
  EXPECT_GT(files, 100);
}

// Every source directory under src/, replay/, metrics/ and app/ belongs to a layer.
TEST(Layering, EverySourceDirectoryHasALayer) {
  const fs::path root = RCSIM_SOURCE_DIR;
  for (const char* top : {"src", "replay", "metrics", "app"}) {
    for (const auto& entry : fs::recursive_directory_iterator(root / top)) {
      if (entry.path().extension() != ".cpp") continue;
      const std::string dir = fs::relative(entry.path().parent_path(), root).string();
      EXPECT_TRUE(kLayerOfDir.count(dir)) << dir << " (" << entry.path().filename().string() << ") is in no layer";
    }
  }
}

}  // namespace
}  // namespace rcsim

namespace rcsim {
namespace {

// The folders show the floors: src/ holds only what replay/ may use, app/ only the top (the
// command line and the live replay); nothing in src/ or replay/ uses app/.
TEST(Layering, TheTopLevelFoldersAreTheFloors) {
  const std::set<std::string> top{"stream", "cli"};
  for (const auto& [dir, layer] : kLayerOfDir) {
    EXPECT_EQ(dir.rfind("app/", 0) == 0, top.count(layer) == 1) << dir << " (layer " << layer << ")";
    if (top.count(layer)) continue;
    for (const std::string& used : kMayUse.at(layer)) EXPECT_EQ(top.count(used), 0u) << dir << " uses " << used;
    if (dir.rfind("src/", 0) == 0) {
      for (const std::string& used : kMayUse.at(layer)) EXPECT_NE(used.rfind("replay_", 0), 0u) << dir << " uses " << used;
    }
  }
}

}  // namespace
}  // namespace rcsim
