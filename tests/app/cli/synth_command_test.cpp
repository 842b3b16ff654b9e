// `rcsim synth` as a user runs it: determinism, a readable recording, refusals without output.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "app/cli/run_rcsim.hpp"
#include "io/recording.hpp"

namespace synth_command_test {

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
  EXPECT_NE(bad_seed.output.find("--seed: must be a whole number in 0..9223372036854775807, got '-3'"), std::string::npos) << bad_seed.output;
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

// A scene of one sensor of the given type and a car standing straight ahead at the given
// distance from the sensor, the ego standing; further sensors of type `other_type` if given.
std::string synth_cli_car_ahead_scene(const std::string& type, double car_range_m, const std::string& other_type = "") {
  const double sensor_x_m = 3.7;
  std::string sensors = R"({"id": "front", "type": ")" + type + R"(", "x_m": 3.7, "y_m": 0, "yaw_rad": 0})";
  if (!other_type.empty()) {
    sensors += R"(, {"id": "corner", "type": ")" + other_type + R"(", "x_m": 3.6, "y_m": 0.8, "yaw_rad": 0.6})";
  }
  // The car's box centre: its rear face (half of 4.6 m) at car_range_m from the sensor.
  const std::string car_x_m = std::to_string(sensor_x_m + car_range_m + 2.3);
  return R"({"format": "rcsim-scene", "version": 1, "duration_s": 1.0,
  "ego": {"trajectory": [{"t_s": 0, "x_m": 0, "y_m": 0, "yaw_rad": 0, "speed_mps": 0}],
          "sensors": [)" + sensors + R"(]},
  "objects": [{"id": "car", "model": "passenger_car",
               "trajectory": [{"t_s": 0, "x_m": )" + car_x_m + R"(, "y_m": 0, "yaw_rad": 3.14159265, "speed_mps": 0}]}]})";
}

// aimotive_lrr was synthesised as the 24 GHz srr24 (40 m range, 2.4e10 Hz) under its own name
// (issue 31): now a 77 GHz radar that sees a car at 120 m and reports raw detections.
TEST_F(SynthCli, AimotiveLrrIsSynthesisedAsA77GhzLongRangeRadar) {
  const auto scene = dir_ / "lrr.json";
  std::ofstream(scene) << synth_cli_car_ahead_scene("aimotive_lrr", 120.0);
  const auto out = dir_ / "lrr";
  const auto r = run("synth " + scene.string() + " --seed 3 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const rcsim::Recording rec = rcsim::read_recording(out);
  ASSERT_EQ(rec.sensors.size(), 1u);
  EXPECT_EQ(rec.sensors[0].type, "aimotive_lrr");
  EXPECT_EQ(rec.sensors[0].reports, rcsim::ListLevel::detections);
  EXPECT_NEAR(rec.cycle_time_s, 0.0554, 1e-12);  // its own cycle time
  EXPECT_EQ(rec.cycle_count(), 19);               // 0 .. 0.9972 s
  const auto& chain = rec.source["signal_chain"]["front"];
  EXPECT_EQ(chain["carrier_hz"].get<double>(), 77.0e9);
  EXPECT_EQ(chain["max_range_m"].get<double>(), 180.0);
  EXPECT_NEAR(chain["range_bin_m"].get<double>(), 1.4, 0.01);
  // The car's rear at 120 m is detected in most cycles (the srr24 design stopped at 40 m); no
  // detection lies beyond the sensor's 180 m; detections have no track ids.
  std::vector<int> car_cycles(static_cast<std::size_t>(rec.cycle_count()), 0);
  for (const auto& t : rec.targets) {
    EXPECT_LE(t.range_m, 180.0);
    EXPECT_EQ(t.id, -1);
    if (std::abs(t.range_m - 120.0) < 2.0 && std::abs(t.range_rate_mps) < 0.5) car_cycles[static_cast<std::size_t>(t.cycle)] = 1;
  }
  int detected = 0;
  for (const int c : car_cycles) detected += c;
  EXPECT_GE(detected, 15) << "of " << rec.cycle_count() << " cycles";
  // The annotator labels what the sensor sees: the car at 120 m is in objects.csv.
  ASSERT_EQ(rec.objects.size(), 1u);
  EXPECT_EQ(rec.boxes[0].size(), static_cast<std::size_t>(rec.cycle_count()));
}

// srr24 (0.04 s) and aimotive_lrr (0.0554 s) cannot share one recording's cycle clock: refused,
// naming the scene, both sensors and their cycle times, before any output.
TEST_F(SynthCli, RefusesMixedCycleTimesNamingTheSensors) {
  const auto scene = dir_ / "mixed.json";
  std::ofstream(scene) << synth_cli_car_ahead_scene("srr24", 20.0, "aimotive_lrr");
  const auto r = run("synth " + scene.string() + " -o " + (dir_ / "rec").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("rcsim: error: " + scene.string() + ": ego.sensors: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"front\" (srr24) 0.04 s"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"corner\" (aimotive_lrr) 0.0554 s"), std::string::npos) << r.output;
  EXPECT_EQ(entries(), std::vector<std::string>{"mixed.json"});
}

// A profile the reference cannot be made into (a frame longer than its cycle) is refused naming
// the scene, the sensor and the profile.
TEST_F(SynthCli, RefusesASensorItCannotSynthesiseNamingIt) {
  std::string profile = read(fs::path(RCSIM_SOURCE_DIR) / "src" / "sensor" / "sensors" / "srr24.json");
  profile.replace(profile.find("\"srr24\""), 7, "\"fast_srr\"");
  profile.replace(profile.find("\"cycle_time_s\": 0.04"), 20, "\"cycle_time_s\": 0.005");
  std::ofstream(dir_ / "fast_srr.json") << profile;
  const auto scene = dir_ / "fast.json";
  std::ofstream(scene) << synth_cli_car_ahead_scene("fast_srr.json", 10.0);
  const auto r = run("synth " + scene.string() + " -o " + (dir_ / "rec").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("rcsim: error: " + scene.string() + ": ego.sensors: sensor \"front\": sensor profile "
                          "\"fast_srr\" cannot be synthesised: "),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("cycle time of 0.005 s"), std::string::npos) << r.output;
  EXPECT_EQ(entries(), (std::vector<std::string>{"fast.json", "fast_srr.json"}));
}

}  // namespace synth_command_test
