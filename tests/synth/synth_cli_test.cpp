// `rcsim synth` as a user runs it: determinism, a readable recording, refusals without output.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "cli/run_rcsim.hpp"
#include "io/recording.hpp"

namespace {

namespace fs = std::filesystem;

using Result = rcsim::testing::CommandResult;

Result run(const std::string& args) { return rcsim::testing::run_rcsim(args); }
std::string read(const fs::path& p) { return rcsim::testing::read_file(p); }

const std::string kScenes = std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/scenes/";

class SynthCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rcsim_synth_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // Nothing but the listed entries in the test directory (no temporary or partial directory).
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  fs::path dir_;
};

TEST_F(SynthCli, SameSeedByteIdenticalOtherSeedDifferent) {
  const std::string scene = kScenes + "standstill_1m.json";
  ASSERT_EQ(run("synth " + scene + " --seed 7 -o " + (dir_ / "a").string()).exit_code, 0);
  ASSERT_EQ(run("synth " + scene + " --seed 7 -o " + (dir_ / "b").string()).exit_code, 0);
  ASSERT_EQ(run("synth " + scene + " --seed 8 -o " + (dir_ / "c").string()).exit_code, 0);
  for (const char* file : {"ego.csv", "objects.csv", "targets.csv"}) {
    EXPECT_EQ(read(dir_ / "a" / file), read(dir_ / "b" / file)) << file;
  }
  EXPECT_NE(read(dir_ / "a" / "targets.csv"), read(dir_ / "c" / "targets.csv"));
  EXPECT_NE(read(dir_ / "a" / "objects.csv"), read(dir_ / "c" / "objects.csv"));
  // recording.json differs only in its name.
  const auto json_a = rcsim::read_recording(dir_ / "a");
  const auto json_b = rcsim::read_recording(dir_ / "b");
  EXPECT_EQ(json_a.source, json_b.source);
}

TEST_F(SynthCli, WritesAReadableRecordingWithProvenance) {
  const auto out = dir_ / "standstill";
  const auto r = run("synth " + kScenes + "standstill_1m.json --seed 1 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const rcsim::Recording rec = rcsim::read_recording(out);
  EXPECT_EQ(rec.name, "standstill");
  EXPECT_EQ(rec.sensors.size(), 2u);
  EXPECT_EQ(rec.source["generator"], "rcsim synth");
  EXPECT_EQ(rec.source["seed"], 1);
  EXPECT_EQ(rec.source["scene"], "standstill_1m.json");
  EXPECT_EQ(rec.cycle_count(), 51);
  EXPECT_FALSE(rec.targets.empty());
  EXPECT_EQ(entries(), std::vector<std::string>{"standstill"});
}

TEST_F(SynthCli, SvgPictureOnRequest) {
  const auto svg = dir_ / "p.svg";
  ASSERT_EQ(run("synth " + kScenes + "standstill_1m.json -o " + (dir_ / "r").string() + " --svg " + svg.string()).exit_code, 0);
  const std::string text = read(svg);
  EXPECT_EQ(text.rfind("<svg", 0), 0u);
  EXPECT_NE(text.find("reference target"), std::string::npos);  // the legend names the reference
  EXPECT_NE(text.find("class=\"box-label\""), std::string::npos);   // the annotated boxes are drawn
}

TEST_F(SynthCli, RefusesBadInputWithoutPartialOutput) {
  const std::string out = (dir_ / "rec").string();
  const auto missing = run("synth " + (dir_ / "nope.json").string() + " -o " + out);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("rcsim: error: " + (dir_ / "nope.json").string() + ": "), std::string::npos) << missing.output;

  const auto bad_seed = run("synth " + kScenes + "standstill_1m.json --seed=-3 -o " + out);
  EXPECT_EQ(bad_seed.exit_code, 2);
  EXPECT_NE(bad_seed.output.find("rcsim: error: --seed: '-3' is not a whole number"), std::string::npos) << bad_seed.output;
  EXPECT_EQ(run("synth " + kScenes + "standstill_1m.json --seed 12x -o " + out).exit_code, 2);

  const std::string orphan = (dir_ / "no_such_dir" / "rec").string();
  const auto no_parent = run("synth " + kScenes + "standstill_1m.json -o " + orphan);
  EXPECT_EQ(no_parent.exit_code, 2);
  EXPECT_NE(no_parent.output.find("rcsim: error: " + orphan + ": "), std::string::npos) << no_parent.output;

  // A scene that is not valid: the scene loader names file and field.
  const auto bad_scene = dir_ / "bad.json";
  std::ofstream(bad_scene) << R"({"format": "rcsim-scene", "version": 1, "duration_s": -1})";
  const auto invalid = run("synth " + bad_scene.string() + " -o " + out);
  EXPECT_EQ(invalid.exit_code, 2);
  EXPECT_NE(invalid.output.find("rcsim: error: " + bad_scene.string()), std::string::npos) << invalid.output;

  EXPECT_EQ(entries(), std::vector<std::string>{"bad.json"});  // no recording, no temporary directory
}

}  // namespace
