// The rcsim command as a user runs it: determinism, output files, refusals.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "scratch_dir.hpp"
#include "cli/run_rcsim.hpp"

namespace {

namespace fs = std::filesystem;

using Result = rcsim::testing::CommandResult;

Result run(const std::string& args) { return rcsim::testing::run_rcsim(args); }
std::string read(const fs::path& p) { return rcsim::testing::read_file(p); }

const std::string kExamples = std::string(RCSIM_SOURCE_DIR) + "/docs/examples/";

class Cli : public rcsim::testing::ScratchDirTest {
 protected:
  Cli() : ScratchDirTest("cli") {}
};

TEST_F(Cli, SameSeedByteIdenticalOtherSeedDifferent) {
  for (const char* level : {"detections", "tracks"}) {
    const auto a = dir_ / "a.csv", b = dir_ / "b.csv", c = dir_ / "c.csv";
    const std::string scene = kExamples + "front_approach.json --level " + level;
    ASSERT_EQ(run("simulate " + scene + " --seed 7 -o " + a.string()).exit_code, 0);
    ASSERT_EQ(run("simulate " + scene + " --seed 7 -o " + b.string()).exit_code, 0);
    ASSERT_EQ(run("simulate " + scene + " --seed 8 -o " + c.string()).exit_code, 0);
    EXPECT_GT(read(a).size(), 1000u);
    EXPECT_EQ(read(a), read(b)) << level;
    EXPECT_NE(read(a), read(c)) << level;
  }
}

TEST_F(Cli, NoNoiseIgnoresTheSeed) {
  const std::string scene = kExamples + "front_approach.json --no-noise --level detections";
  EXPECT_EQ(run("simulate " + scene + " --seed 1").output, run("simulate " + scene + " --seed 2").output);
}

TEST_F(Cli, CsvAndJsonlCarryTheSameRows) {
  const auto csv = run("simulate " + kExamples + "front_approach.json --level ideal");
  const auto jsonl = run("simulate " + kExamples + "front_approach.json --level ideal --format jsonl");
  ASSERT_EQ(csv.exit_code, 0);
  ASSERT_EQ(jsonl.exit_code, 0);
  const auto lines = [](const std::string& s) { return std::count(s.begin(), s.end(), '\n'); };
  EXPECT_EQ(lines(csv.output), lines(jsonl.output) + 1);  // + the CSV header
  EXPECT_EQ(csv.output.rfind("t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db,object,reflector\n", 0), 0u);
  EXPECT_NE(jsonl.output.find("\"reflector\":\"front\""), std::string::npos);
}

TEST_F(Cli, BadSceneNamesFileAndFieldAndLeavesNoOutput) {
  const auto scene = dir_ / "bad.json";
  std::string text = read(kExamples + "front_approach.json");
  text.replace(text.find("\"passenger_car\""), 15, "\"hovercraft\"");
  std::ofstream(scene) << text;
  const auto out = dir_ / "out.csv";
  const auto r = run("simulate " + scene.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("bad.json: objects[0].model: unknown object model \"hovercraft\""), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(out));
  for (const auto& entry : fs::directory_iterator(dir_)) EXPECT_NE(entry.path().extension(), ".csv") << entry.path();
}

TEST_F(Cli, EarlierOutputSurvivesAFailedRun) {
  const auto out = dir_ / "out.csv";
  ASSERT_EQ(run("simulate " + kExamples + "front_approach.json -o " + out.string()).exit_code, 0);
  const std::string before = read(out);
  const auto scene = dir_ / "truncated.json";
  const std::string text = read(kExamples + "front_approach.json");
  std::ofstream(scene) << text.substr(0, text.size() / 2);
  const auto r = run("simulate " + scene.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("truncated.json: line"), std::string::npos) << r.output;
  EXPECT_EQ(read(out), before);
}

TEST_F(Cli, ModelsListsTheLibrary) {
  const auto r = run("models --json");
  ASSERT_EQ(r.exit_code, 0);
  for (const char* name : {"passenger_car", "truck_trailer", "guide_board", "pole"}) {
    EXPECT_NE(r.output.find(std::string("\"name\": \"") + name + "\""), std::string::npos) << name;
  }
}

TEST_F(Cli, UnknownLevelIsRefused) {
  const auto r = run("simulate " + kExamples + "front_approach.json --level raw");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--level"), std::string::npos) << r.output;
}

// README's exit statuses: a wrong option or value is bad input, 2, whatever CLI11 found (it
// numbers its errors 104 to 114); --help and --version are 0.
TEST_F(Cli, EveryCommandLineErrorIsExitStatusTwoWithAShortMessage) {
  const std::map<std::string, std::string> refused = {
      {"replay x --db y --seed -1", "--seed: must be 0 or more, got -1"},
      {"campaign run-local x -j abc", "--jobs"},
      {"campaign plan " + kExamples + "front_approach.json -o d", "--shards is required"},
      {"simulate " + kExamples + "front_approach.json -o a -o b", "--output"},
      {"listen --port 99999", "--port"},
      {"simulate " + kExamples + "front_approach.json --no-such-option", "--no-such-option"},
      {"no-such-command", "unknown command 'no-such-command'"}};
  for (const auto& [args, message] : refused) {
    const auto r = run(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << ": " << r.output;
    EXPECT_LT(r.output.size(), 400u) << args << ": " << r.output;
  }
  EXPECT_EQ(run("--help").exit_code, 0);
  EXPECT_EQ(run("--version").exit_code, 0);
}


TEST_F(Cli, ModelsSensorsListsTheProfiles) {
  const auto text = run("models --sensors");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  for (const char* name : {"aimotive_lrr", "srr24"}) {
    EXPECT_NE(text.output.find(name), std::string::npos) << name << " in\n" << text.output;
  }
  EXPECT_EQ(text.output.find("passenger_car"), std::string::npos) << "object models listed too";
  const auto json = rcsim::testing::run_rcsim("models --sensors --json", false);
  ASSERT_EQ(json.exit_code, 0);
  const nlohmann::json all = nlohmann::json::parse(json.output);  // throws (and fails) unless JSON
  ASSERT_TRUE(all.is_array());
  std::map<std::string, nlohmann::json> by_name;
  for (const auto& profile : all) by_name[profile.at("name").get<std::string>()] = profile;
  ASSERT_EQ(by_name.count("aimotive_lrr"), 1u);
  ASSERT_EQ(by_name.count("srr24"), 1u);
  EXPECT_EQ(by_name["aimotive_lrr"].at("reports"), "detections");
  EXPECT_EQ(by_name["srr24"].at("reports"), "tracks");
  EXPECT_EQ(by_name["aimotive_lrr"].at("amplitude").at("law"), "radar_equation");
  EXPECT_EQ(by_name["srr24"].at("amplitude").at("law"), "paper_eq1");
  EXPECT_EQ(by_name["aimotive_lrr"].at("carrier_frequency_hz"), 77.0e9);
}

}  // namespace
