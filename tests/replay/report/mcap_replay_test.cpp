// One stored run as MCAP for Foxglove (replay/report/mcap_replay.cpp): the topics and their
// message counts by hand, the ego's transform from a sensor's pose and mounting, targets in their
// sensor's frame coloured by class, a summary run; and, where the test tools are installed
// (scripts/test-tools.sh), the file read by the format's own reader with every foxglove.* message
// checked against Foxglove's published JSON schema.
#include "replay/report/mcap_replay.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "app/cli/run_rcsim.hpp"
#include "io/mcap_reader.hpp"
#include "io/recording.hpp"
#include "replay/replay_fixtures.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"

namespace rcsim::mcap_replay_test {

namespace fs = std::filesystem;
using Json = nlohmann::json;

class McapReplay : public rcsim::testing::ScratchDirTest {
 protected:
  McapReplay() : ScratchDirTest("mcap_replay") {}
  // Replays a bundled recording into r.sqlite (full, then summary) and writes run `run` as MCAP.
  fs::path replay_and_write(const std::string& recording, int run, const std::string& store = "full") {
    const std::string db_path = (dir_ / "r.sqlite").string();
    const auto r = rcsim::testing::run_rcsim("replay " + std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/" + recording +
                                             " --db " + db_path + " --store " + store + " --again");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const auto db = replay::open_report_database_for_reading(db_path);
    const fs::path path = dir_ / ("run" + std::to_string(run) + ".mcap");
    std::ofstream out(path, std::ios::binary);
    counts = replay::write_run_mcap(*db, run, out);
    return path;
  }
  replay::McapReplayCounts counts;
};

TEST(McapReplayNames, TopicsNameTheSensorsFrame) {
  EXPECT_EQ(replay::mcap_replay_topic("front", "recorded"), "/rcsim/front/recorded");
  EXPECT_EQ(replay::mcap_replay_topic("", "boxes"), "/rcsim/boxes");
}

TEST_F(McapReplay, EveryCycleHasItsTargetsBoxesEgoAndFiguresPerSensor) {
  const fs::path path = replay_and_write("two_in_one_cell", 1);
  mcap::Reader reader(path);
  std::map<std::string, int> per_topic;
  std::map<std::string, int> targets_by_colour;
  Json first_ego, first_mount;
  reader.for_each_message([&](const mcap::Message& m, const mcap::Channel& c, const mcap::Schema* s) {
    ++per_topic[c.topic];
    ASSERT_NE(s, nullptr) << c.topic;
    const Json body = Json::parse(m.data);
    if (c.topic == "/tf" && body["child_frame_id"] == "ego" && first_ego.is_null()) first_ego = body;
    if (c.topic == "/tf" && body["parent_frame_id"] == "ego" && first_mount.is_null()) first_mount = body;
    if (c.topic.ends_with("/recorded") || c.topic.ends_with("/simulated")) {
      EXPECT_EQ(s->name, "foxglove.SceneUpdate");
      for (const auto& shape : body["entities"][0][c.topic.ends_with("/recorded") ? "spheres" : "cubes"]) {
        ++targets_by_colour[shape["color"].dump()];
      }
    }
    if (c.topic.ends_with("/figures")) {
      EXPECT_EQ(s->name, "rcsim.CycleFigures");
    }
  });
  // 126 cycles of 2 sensors (front_left, front_right): per sensor a message a cycle on recorded,
  // simulated and figures, one view field; boxes a cycle; /tf the ego a cycle and 2 mountings.
  EXPECT_EQ(counts.cycles, 126);
  EXPECT_EQ(counts.sensors, 2);
  for (const std::string sensor : {"front_left", "front_right"}) {
    for (const std::string what : {"recorded", "simulated", "figures"}) EXPECT_EQ(per_topic["/rcsim/" + sensor + "/" + what], 126) << sensor << what;
    EXPECT_EQ(per_topic["/rcsim/" + sensor + "/view_field"], 1);
  }
  EXPECT_EQ(per_topic["/rcsim/boxes"], 126);
  for (const auto& [id, channel] : reader.channels()) {
    EXPECT_EQ(channel.metadata, (std::map<std::string, std::string>{{"format", "rcsim-mcap-replay"}, {"version", "1"}})) << channel.topic;
  }
  EXPECT_EQ(per_topic["/tf"], 126 + 2);
  EXPECT_EQ(counts.messages, 1 + 1 + 126 * (1 + 1 + 2 * 3) + 2);
  // The first ego pose in the world, X_WS X_VS^-1: the recording's first ego row, ego.csv's
  // (-3.5827 m, -1.1596 m, 0.5 rad), its yaw as (0, 0, sin 0.25, cos 0.25).
  ASSERT_FALSE(first_ego.is_null());
  EXPECT_EQ(first_ego["parent_frame_id"], "world");
  EXPECT_NEAR(first_ego["translation"]["x"].get<double>(), -3.5827, 1e-9);
  EXPECT_NEAR(first_ego["translation"]["y"].get<double>(), -1.1596, 1e-9);
  EXPECT_NEAR(first_ego["rotation"]["z"].get<double>(), std::sin(0.25), 1e-9);
  EXPECT_NEAR(first_ego["rotation"]["w"].get<double>(), std::cos(0.25), 1e-9);
  // A mounting, yaw as a quaternion about z: (0, 0, sin(yaw / 2), cos(yaw / 2)), of unit length.
  ASSERT_FALSE(first_mount.is_null());
  const double qz = first_mount["rotation"]["z"], qw = first_mount["rotation"]["w"];
  EXPECT_NEAR(qz * qz + qw * qw, 1.0, 1e-12);
  // Coloured by class: the recorded object targets blue (#1f5fbf: 31, 95, 191 / 255), others teal.
  EXPECT_GT(targets_by_colour[Json({{"r", 31 / 255.0}, {"g", 95 / 255.0}, {"b", 191 / 255.0}, {"a", 1.0}}).dump()], 0);
  EXPECT_GT(targets_by_colour[Json({{"r", 12 / 255.0}, {"g", 166 / 255.0}, {"b", 120 / 255.0}, {"a", 1.0}}).dump()], 0);
}

// Issue 49, by hand: a recorded target at range 10 m, azimuth 0, elevation asin(0.1) lies
// 10 · 0.1 = 1 m above the sensor's plane and 10 · cos(asin 0.1) = √99 = 9.9499 m ahead in it.
// The sensors measure elevation (imaging_3d.json), so the simulated targets are lifted too.
TEST_F(McapReplay, TargetsWithAnElevationAreLiftedAndTheirHorizontalDistanceShortened) {
  const fs::path rec = dir_ / "standstill_3d";
  fs::copy(fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic/standstill_1m", rec, fs::copy_options::recursive);
  fs::copy_file(fs::path(RCSIM_SOURCE_DIR) / "docs/examples/road_users/imaging_3d.json", rec / "imaging_3d.json");
  Json recording = Json::parse(std::ifstream(rec / "recording.json"));
  for (Json& sensor : recording["sensors"]) sensor["type"] = "imaging_3d.json";
  std::ofstream(rec / "recording.json") << recording.dump(2);
  std::stringstream targets_in;
  targets_in << std::ifstream(rec / "targets.csv").rdbuf();
  std::string line, targets_out;
  for (int i = 0; std::getline(targets_in, line); ++i) {
    if (i == 0) {
      targets_out += line + ",elevation_rad\n";
    } else if (i == 1) {  // 0.120000,3,front_right,0,1.2662,0.358640,...: range 10 m, azimuth 0
      std::vector<std::string> f;
      std::stringstream fields(line);
      for (std::string x; std::getline(fields, x, ',');) f.push_back(x);
      f[4] = "10.0000";
      f[5] = "0.000000";
      for (const auto& x : f) targets_out += x + ",";
      targets_out += "0.1001674211615598\n";  // asin(0.1)
    } else {
      targets_out += line + ",0.0\n";
    }
  }
  std::ofstream(rec / "targets.csv") << targets_out;
  const std::string db_path = (dir_ / "r3d.sqlite").string();
  const auto r = rcsim::testing::run_rcsim("replay " + rec.string() + " --db " + db_path);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto db = replay::open_report_database_for_reading(db_path);
  const fs::path path = dir_ / "r3d.mcap";
  {
    std::ofstream out(path, std::ios::binary);
    replay::write_run_mcap(*db, 1, out);
  }
  mcap::Reader reader(path);
  int lifted_recorded = 0, lifted_simulated = 0, simulated = 0;
  reader.for_each_message([&](const mcap::Message& m, const mcap::Channel& c, const mcap::Schema*) {
    const bool is_recorded = c.topic.ends_with("/recorded"), is_simulated = c.topic.ends_with("/simulated");
    if (!is_recorded && !is_simulated) return;
    const Json body = Json::parse(m.data);
    for (const auto& shape : body["entities"][0][is_recorded ? "spheres" : "cubes"]) {
      const Json& p = shape["pose"]["position"];
      const double x = p["x"], y = p["y"], z = p["z"];
      if (is_simulated) {
        ++simulated;
        lifted_simulated += std::abs(z) > 1e-3;
      } else if (std::abs(z) > 1e-9) {
        ++lifted_recorded;
        EXPECT_EQ(c.topic, "/rcsim/front_right/recorded");
        EXPECT_NEAR(z, 1.0, 1e-6);  // elevations are stored as float32
        EXPECT_NEAR(x, std::sqrt(99.0), 1e-6);
        EXPECT_NEAR(y, 0.0, 1e-9);
      }
    }
  });
  EXPECT_EQ(lifted_recorded, 1);
  EXPECT_GT(simulated, 0);
  EXPECT_GT(lifted_simulated, 0);
}

TEST_F(McapReplay, ASummaryRunHasItsFiguresAndViewFieldsButNoTargets) {
  replay_and_write("standstill_1m", 1, "full");
  const fs::path path = replay_and_write("standstill_1m", 2, "summary");
  mcap::Reader reader(path);
  int shapes = 0, figures = 0;
  reader.for_each_message([&](const mcap::Message& m, const mcap::Channel& c, const mcap::Schema*) {
    const Json body = Json::parse(m.data);
    if (c.topic.ends_with("/recorded") || c.topic.ends_with("/simulated")) {
      shapes += static_cast<int>(body["entities"][0]["spheres"].size() + body["entities"][0]["cubes"].size());
    }
    figures += c.topic.ends_with("/figures");
  });
  EXPECT_EQ(shapes, 0);
  EXPECT_EQ(figures, 51 * 2);
}

// Issue 50, item 5: on sensors' own clocks each sensor's targets are written at its own cycles
// only, at their times, kept until its next (lifetime 0): visible all of its cycle time, never
// blanked by another sensor's cycle. --clock log puts the times on the log's clock.
TEST_F(McapReplay, OnOwnClocksEachSensorsTargetsAreWrittenAtItsOwnCyclesOnly) {
  Recording own = testing::on_own_clocks(read_recording(fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / "two_in_one_cell"), {1, 2},
                                         {0, 1}, 1);
  const std::uint64_t first_ns = 1'700'000'000'000'000'000;
  own.source["first_timestamp_ns"] = first_ns;
  write_recording(dir_ / "own", own);
  const std::string db_path = (dir_ / "own.sqlite").string();
  const auto r = rcsim::testing::run_rcsim("replay " + (dir_ / "own").string() + " --db " + db_path);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto db = replay::open_report_database_for_reading(db_path);
  const fs::path path = dir_ / "own.mcap";
  {
    std::ofstream out(path, std::ios::binary);
    replay::write_run_mcap(*db, 1, out, replay::McapClock::log);
  }
  std::map<std::string, std::vector<std::uint64_t>> times;  // per sensor: its recorded entities' times
  mcap::Reader reader(path);
  reader.for_each_message([&](const mcap::Message& m, const mcap::Channel& c, const mcap::Schema*) {
    if (!c.topic.ends_with("/recorded")) return;
    const Json entity = Json::parse(m.data)["entities"][0];
    EXPECT_EQ(entity["lifetime"], Json({{"sec", 0}, {"nsec", 0}})) << c.topic;
    times[c.topic].push_back(m.log_time_ns);
  });
  for (int s = 0; s < 2; ++s) {
    std::vector<std::uint64_t> cycles;
    for (int k = 0; k < own.cycle_count(); ++k) {
      if (own.cycle_sensor(k) == s) cycles.push_back(first_ns + static_cast<std::uint64_t>(std::llround(own.cycle_t_s(k) * 1e9)));
    }
    const std::string topic = replay::mcap_replay_topic(own.sensors[static_cast<std::size_t>(s)].id, "recorded");
    ASSERT_EQ(times[topic].size(), cycles.size()) << topic;
    for (std::size_t k = 0; k < cycles.size(); ++k) EXPECT_NEAR(static_cast<double>(times[topic][k]), static_cast<double>(cycles[k]), 1e3) << k;
  }
  // A run whose recording came from no log has no log clock.
  replay_and_write("standstill_1m", 1);
  const auto synthetic = replay::open_report_database_for_reading((dir_ / "r.sqlite").string());
  std::ostringstream sink;
  EXPECT_THROW(replay::write_run_mcap(*synthetic, 1, sink, replay::McapClock::log), std::invalid_argument);
}

TEST_F(McapReplay, TheFormatsOwnReaderAndFoxglovesSchemasAcceptTheFile) {
  const fs::path tool = fs::path(RCSIM_SOURCE_DIR) / "tests" / "tools" / "mcap";
  if (std::system("command -v node > /dev/null 2>&1") != 0 || !fs::exists(tool / "node_modules" / "@mcap" / "core")) {
    GTEST_SKIP() << "the MCAP test tool is not installed (scripts/test-tools.sh: Node.js and npm ci in tests/tools/mcap)";
  }
  const fs::path path = replay_and_write("two_in_one_cell", 1);
  const auto checked = rcsim::testing::run_shell_command("node " + (tool / "check_mcap.js").string() + " " + path.string());
  ASSERT_EQ(checked.exit_code, 0) << checked.output;
  const Json report = Json::parse(checked.output);
  EXPECT_EQ(report["problems"].size(), 0u) << checked.output;
  EXPECT_EQ(report["streamed"], counts.messages);
  EXPECT_EQ(report["counts"]["/rcsim/front_left/recorded"], 126);
  EXPECT_EQ(report["schemas"], Json({"foxglove.SceneUpdate:jsonschema", "foxglove.FrameTransform:jsonschema", "rcsim.CycleFigures:jsonschema"}));
  // Issue 50, item 8: a summary run's figures (nulls where it computed none) meet the file's own
  // rcsim.CycleFigures schema.
  const fs::path summary = replay_and_write("two_in_one_cell", 2, "summary");
  const auto checked_summary = rcsim::testing::run_shell_command("node " + (tool / "check_mcap.js").string() + " " + summary.string());
  ASSERT_EQ(checked_summary.exit_code, 0) << checked_summary.output;
  EXPECT_EQ(Json::parse(checked_summary.output)["problems"].size(), 0u) << checked_summary.output;
}

}  // namespace rcsim::mcap_replay_test
