// `rcsim simulate` as a user runs it: the same seed gives the same bytes, CSV and JSONL carry the
// same rows, a recording holds what each sensor reports, a bad scene or option is refused naming
// it, and an earlier output survives a failure.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli/run_rcsim.hpp"
#include "io/recording.hpp"
#include "scratch_dir.hpp"

namespace rcsim::simulate_command_test {

namespace fs = std::filesystem;

using Result = rcsim::testing::CommandResult;

Result run(const std::string& args) { return rcsim::testing::run_rcsim(args); }
std::string read(const fs::path& p) { return rcsim::testing::read_file(p); }

const std::string kExamples = std::string(RCSIM_SOURCE_DIR) + "/docs/examples/";

class SimulateCli : public rcsim::testing::ScratchDirTest {
 protected:
  SimulateCli() : ScratchDirTest("simulate_cli") {}
};

TEST_F(SimulateCli, SameSeedByteIdenticalOtherSeedDifferent) {
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

TEST_F(SimulateCli, NoNoiseIgnoresTheSeed) {
  const std::string scene = kExamples + "front_approach.json --no-noise --level detections";
  EXPECT_EQ(run("simulate " + scene + " --seed 1").output, run("simulate " + scene + " --seed 2").output);
}

TEST_F(SimulateCli, CsvAndJsonlCarryTheSameRows) {
  const auto csv = run("simulate " + kExamples + "front_approach.json --level ideal");
  const auto jsonl = run("simulate " + kExamples + "front_approach.json --level ideal --format jsonl");
  ASSERT_EQ(csv.exit_code, 0);
  ASSERT_EQ(jsonl.exit_code, 0);
  const auto lines = [](const std::string& s) { return std::count(s.begin(), s.end(), '\n'); };
  EXPECT_EQ(lines(csv.output), lines(jsonl.output) + 1);  // + the CSV header
  EXPECT_EQ(csv.output.rfind("t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db,object,reflector\n", 0), 0u);
  EXPECT_NE(jsonl.output.find("\"reflector\":\"front\""), std::string::npos);
}

// --format mcap: the scene for Foxglove in one file, written atomically; refused without -o.
TEST_F(SimulateCli, McapWritesOneFileAndNeedsAName) {
  const auto out = dir_ / "s.mcap";
  const auto written = run("simulate " + kExamples + "front_approach.json --format mcap -o " + out.string());
  ASSERT_EQ(written.exit_code, 0) << written.output;
  EXPECT_NE(written.output.find("rcsim simulate: 101 cycles of 2 sensor(s), 408 messages, "), std::string::npos) << written.output;
  EXPECT_EQ(read(out).substr(0, 5), "\x89MCAP");
  const auto no_name = run("simulate " + kExamples + "front_approach.json --format mcap");
  EXPECT_EQ(no_name.exit_code, 2);
  EXPECT_NE(no_name.output.find("--format mcap writes a binary file: name it with -o FILE.mcap"), std::string::npos) << no_name.output;
}

TEST_F(SimulateCli, BadSceneNamesFileAndFieldAndLeavesNoOutput) {
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

TEST_F(SimulateCli, EarlierOutputSurvivesAFailedRun) {
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

// --format recording: the scene as its sensors would have recorded it, a recording replay and
// profile derive read; each sensor at its own level (srr24 tracks, aimotive_lrr detections with
// the radar's cross-section estimate); the same seed gives the same rows; refused without -o or
// with an option that does not apply.
TEST_F(SimulateCli, RecordingFormatWritesWhatEachSensorReports) {
  const auto tracks = dir_ / "tracks", lined = dir_ / "lined", again = dir_ / "again";
  const auto made = run("simulate " + kExamples + "front_approach.json --format recording -o " + tracks.string());
  ASSERT_EQ(made.exit_code, 0) << made.output;
  EXPECT_NE(made.output.find("rcsim simulate: 101 cycles of 2 sensor(s), "), std::string::npos) << made.output;
  const Recording front = read_recording(tracks);
  EXPECT_EQ(front.name, "tracks");
  ASSERT_EQ(front.sensors.size(), 2u);
  EXPECT_EQ(front.sensors[0].reports, ListLevel::tracks);
  EXPECT_TRUE(std::isnan(front.targets.at(0).rcs_dbsm));
  const std::string scene = kExamples + "round_trip/lined_road.json --seed 3 --format recording -o ";
  ASSERT_EQ(run("simulate " + scene + lined.string()).exit_code, 0);
  ASSERT_EQ(run("simulate " + scene + again.string()).exit_code, 0);
  const Recording road = read_recording(lined);
  EXPECT_EQ(road.sensors.at(0).type, "aimotive_lrr");
  EXPECT_EQ(road.sensors.at(0).reports, ListLevel::detections);
  EXPECT_GT(road.targets.size(), 5000u);
  EXPECT_TRUE(std::isfinite(road.targets.at(0).rcs_dbsm));
  EXPECT_EQ(read(lined / "targets.csv"), read(again / "targets.csv"));
  const auto no_dir = run("simulate " + kExamples + "front_approach.json --format recording");
  EXPECT_EQ(no_dir.exit_code, 2);
  EXPECT_NE(no_dir.output.find("--format recording writes a directory: name it with -o RECORDING_DIR"), std::string::npos) << no_dir.output;
  const auto level = run("simulate " + kExamples + "front_approach.json --format recording --level detections -o " + (dir_ / "x").string());
  EXPECT_EQ(level.exit_code, 2);
  EXPECT_NE(level.output.find("--format recording writes what each sensor reports"), std::string::npos) << level.output;
  EXPECT_FALSE(fs::exists(dir_ / "x"));
}

// docs/walkthrough.md, "A pedestrian crossing, in 3D": a radar that measures elevation writes the
// elevation_rad column; one second in, the walker's detections lie 0.26 to 1.54 m above the road
// (11 of them), the gantry's board 6.25 m up; a recording made of it is version 5 with the
// mounting's height and the targets' elevations.
TEST_F(SimulateCli, APedestrianCrossingInThreeDimensionsAsTheWalkthroughShowsIt) {
  const auto csv = dir_ / "crossing.csv";
  const std::string scene = kExamples + "road_users/pedestrian_crossing.json";
  const auto made = run("simulate " + scene + " --level detections --no-noise -o " + csv.string());
  ASSERT_EQ(made.exit_code, 0) << made.output;
  std::istringstream lines(read(csv));
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db,elevation_rad");
  int walker = 0;
  double lowest_m = 1e9, highest_m = -1e9, gantry_m = 0.0;
  while (std::getline(lines, line)) {
    std::vector<double> f;
    std::istringstream fields(line);
    for (std::string cell; std::getline(fields, cell, ',');) f.push_back(cell == "front" ? 0.0 : std::stod(cell));
    ASSERT_EQ(f.size(), 9u) << line;
    const double range_m = f[4], azimuth_rad = f[5], elevation_rad = f[8];
    // In the world: the ego drove 8 m/s x t, the sensor 3.8 m ahead of it and 0.6 m above the road.
    const double x_m = 8.0 * f[0] + 3.8 + range_m * std::cos(elevation_rad) * std::cos(azimuth_rad);
    const double y_m = range_m * std::cos(elevation_rad) * std::sin(azimuth_rad);
    const double z_m = 0.6 + range_m * std::sin(elevation_rad);
    if (f[1] == 0.0 && std::abs(x_m - 49.0) < 1.0 && std::abs(y_m) < 2.0) gantry_m = std::max(gantry_m, z_m);
    if (f[1] != 10.0 || std::abs(x_m - 29.0) > 1.0 || std::abs(y_m - 2.6) > 1.0) continue;
    ++walker;
    lowest_m = std::min(lowest_m, z_m);
    highest_m = std::max(highest_m, z_m);
  }
  EXPECT_EQ(walker, 11);
  EXPECT_NEAR(lowest_m, 0.26, 0.01);
  EXPECT_NEAR(highest_m, 1.54, 0.01);
  EXPECT_NEAR(gantry_m, 6.25, 0.3);
  const auto rec = dir_ / "crossing_rec";
  ASSERT_EQ(run("simulate " + scene + " --format recording -o " + rec.string()).exit_code, 0);
  EXPECT_NE(read(rec / "recording.json").find("\"version\": 5"), std::string::npos);
  const Recording back = read_recording(rec);
  EXPECT_DOUBLE_EQ(back.sensors.at(0).z_m, 0.6);
  EXPECT_TRUE(std::isfinite(back.targets.at(0).elevation_rad));
}

TEST_F(SimulateCli, UnknownLevelIsRefused) {
  const auto r = run("simulate " + kExamples + "front_approach.json --level raw");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--level"), std::string::npos) << r.output;
}

}  // namespace rcsim::simulate_command_test
