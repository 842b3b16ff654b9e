// Fidelity levels (sim/fidelity.hpp, docs/fidelity.md): each runs and differs from full where it should.
#include <gtest/gtest.h>

#include <SQLiteCpp/SQLiteCpp.h>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "app/cli/run_rcsim.hpp"
#include "replay/replay_fixtures.hpp"
#include "sim/simulation.hpp"

namespace rcsim {
namespace {

struct Counts {
  long long detections = 0, reported = 0, plane_targets = 0, merged = 0;
  bool ids_are_rows = true;
};

// Runs the scene at a level; `merged` counts detections farther than 1 deg in azimuth from every
// ideal target of their cycle (the monopulse merge artefact of two reflectors in one cell, Fig. 10).
Counts run_level(const Scene& scene, Fidelity fidelity, bool noise) {
  SimulationOptions options;
  options.fidelity = fidelity;
  options.noise = noise;
  options.seed = 5;
  Simulation sim(scene, options);
  Counts c;
  for (int k = 0; k < sim.cycle_count(); ++k) {
    sim.run_cycle(k);
    for (std::size_t s = 0; s < sim.sensor_count(); ++s) {
      const auto& st = sim.sensor_state(s);
      c.detections += static_cast<long long>(st.detections.size());
      c.reported += static_cast<long long>(st.reported.size());
      for (const auto& t : st.ideal) c.plane_targets += t.kind == ReflectorKind::Plane ? 1 : 0;
      for (const auto& d : st.detections) {
        double nearest = 1e9;
        for (const auto& t : st.ideal) nearest = std::min(nearest, std::abs(d.azimuth_rad - t.azimuth_rad));
        if (nearest > 1.0 * kPi / 180.0) ++c.merged;
      }
      for (std::size_t i = 0; i < st.reported.size(); ++i) {
        if (st.reported[i].id != static_cast<int>(i)) c.ids_are_rows = false;
      }
    }
  }
  return c;
}

TEST(Fidelity, NamesRoundTrip) {
  for (const auto f : {Fidelity::full, Fidelity::no_monopulse, Fidelity::points_only, Fidelity::no_tracking}) {
    EXPECT_EQ(parse_fidelity(fidelity_name(f)), f);
  }
  EXPECT_FALSE(parse_fidelity("fast").has_value());
  EXPECT_FALSE(parse_fidelity("").has_value());
}

TEST(Fidelity, NoMonopulseHasNoMergeArtefact) {
  const Scene scene = testing::two_cars_scene();
  const Counts full = run_level(scene, Fidelity::full, false);
  const Counts ideal_angle = run_level(scene, Fidelity::no_monopulse, false);
  EXPECT_GT(full.merged, 0) << "the two cars in one cell should give monopulse merge artefacts";
  EXPECT_EQ(ideal_angle.merged, 0);
  EXPECT_GT(ideal_angle.detections, 0);
  // With noise the level still runs and reports targets.
  EXPECT_GT(run_level(scene, Fidelity::no_monopulse, true).reported, 0);
}

TEST(Fidelity, PointsOnlyDropsPlanes) {
  const Scene scene = testing::two_cars_scene();
  const Counts full = run_level(scene, Fidelity::full, true);
  const Counts points = run_level(scene, Fidelity::points_only, true);
  EXPECT_GT(full.plane_targets, 0);
  EXPECT_EQ(points.plane_targets, 0);
  EXPECT_GT(points.detections, 0);
}

TEST(Fidelity, NoTrackingReportsDetections) {
  const Scene scene = testing::two_cars_scene();
  const Counts full = run_level(scene, Fidelity::full, true);
  const Counts direct = run_level(scene, Fidelity::no_tracking, true);
  EXPECT_EQ(direct.reported, direct.detections);
  EXPECT_TRUE(direct.ids_are_rows);
  EXPECT_NE(direct.reported, full.reported);  // the tracker confirms after four measurements
}

TEST(Fidelity, CommandLine) {
  const std::string scene = std::string(RCSIM_SOURCE_DIR) + "/docs/examples/two_in_one_cell.json";
  std::string full_output;
  for (const char* level : {"full", "no_monopulse", "points_only", "no_tracking"}) {
    const auto r = testing::run_rcsim("simulate " + scene + " --seed 2 --fidelity " + level, false);
    EXPECT_EQ(r.exit_code, 0) << level;
    EXPECT_FALSE(r.output.empty()) << level;
    if (std::string(level) == "full") {
      full_output = r.output;
    } else {
      EXPECT_NE(r.output, full_output) << level;
    }
  }
  EXPECT_EQ(testing::run_rcsim("stream " + scene + " --to 127.0.0.1:9 --speed max --fidelity no_monopulse").exit_code, 0);
  EXPECT_EQ(testing::run_rcsim("simulate " + scene + " --fidelity turbo").exit_code, 2);
  const std::string recording = std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/two_in_one_cell";
  EXPECT_EQ(testing::run_rcsim("replay " + recording + " --db /dev/null --fidelity turbo").exit_code, 2);
  EXPECT_EQ(testing::run_rcsim("stream " + scene + " --fidelity turbo").exit_code, 2);
}

TEST(Fidelity, ReplayStoresLevel) {
  const auto dir = std::filesystem::temp_directory_path() / ("rcsim_fidelity_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string db = (dir / "report.sqlite").string();
  const std::string recording = std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/two_in_one_cell";
  const auto r = testing::run_rcsim("replay " + recording + " --db " + db + " --fidelity no_monopulse");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  {
    SQLite::Database d(db);
    SQLite::Statement q(d, "SELECT level, parameters FROM runs");
    ASSERT_TRUE(q.executeStep());
    EXPECT_EQ(q.getColumn(0).getString(), "tracks");
    const auto parameters = nlohmann::json::parse(q.getColumn(1).getString());
    EXPECT_EQ(parameters.at("fidelity").at("level"), "no_monopulse");
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rcsim
