// Hard cases of the third dimension and the road users (docs/model.md, "Elevation", "Road users",
// "Things above the road"): an overhead sign gantry approached at 20 m/s, which a planar radar
// reports in the lane and a radar that measures elevation sees at its height and then loses above
// its view; and a walking pedestrian, one target in a coarse Doppler cell and one per limb in a
// fine one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "hard_cases/hard_case_support.hpp"

namespace rcsim {
namespace road_users_test {

using testing::add_object;
using testing::sample;

constexpr double kDeg = kPi / 180.0;

// The ego at 20 m/s along +x from the origin; a gantry across the road 60 m ahead (facing the ego).
Scene gantry_scene(const SensorConfig& config, double z_m) {
  Scene scene = testing::single_sensor_scene(2.9);
  scene.ego = Trajectory({sample(0.0, 0.0, 0.0, 0.0, 20.0), sample(2.9, 58.0, 0.0, 0.0, 20.0)});
  scene.sensors[0].config = config;
  scene.sensors[0].z_m = z_m;
  scene.cycle_time_s = config.cycle_time_s;
  add_object(scene, "gantry", "sign_gantry", {sample(0.0, 60.0, 0.0, kPi, 0.0)});
  return scene;
}

struct GantrySeen {
  double nearest_m = 1e9;     // the nearest horizontal distance at which it was detected
  double lowest_m = 1e9;      // the lowest height it was detected at (sensor height + r sin el)
  double highest_m = -1e9;
  double nearest_in_lane_m = 1e9;  // the nearest at which one lay within the lane (|y| < 1.75 m)
  int detections = 0;
};

GantrySeen drive_under_the_gantry(const SensorConfig& config, double z_m) {
  const Scene scene = gantry_scene(config, z_m);
  SimulationOptions options;
  options.noise = false;
  options.level = ListLevel::detections;
  Simulation sim(scene, options);
  GantrySeen seen;
  for (int k = 0; k < sim.cycle_count(); ++k) {
    sim.run_cycle(k);
    testing::expect_simulation_finite(sim, "gantry");
    const double ego_x_m = sim.snapshot().ego.X_WB.x_m;
    for (const Detection& d : sim.sensor_state(0).detections) {
      if (d.object_index != 0) continue;
      ++seen.detections;
      seen.nearest_m = std::min(seen.nearest_m, 60.0 - ego_x_m);
      const double height_m = z_m + d.range_m * std::sin(d.elevation_rad);
      seen.lowest_m = std::min(seen.lowest_m, height_m);
      seen.highest_m = std::max(seen.highest_m, height_m);
      if (std::abs(d.range_m * std::cos(d.elevation_rad) * std::sin(d.azimuth_rad)) < 1.75) {
        seen.nearest_in_lane_m = std::min(seen.nearest_in_lane_m, 60.0 - ego_x_m);
      }
    }
  }
  return seen;
}

TEST(HardCaseRoadUsers, APlanarRadarReportsAnOverheadGantryInTheLaneToTheEnd) {
  // srr24: planar, 40 m reach; the board (ERCS 3) is detected from about 40 m on, at the road's
  // level, on the lane's centre line, until the ego passes under it.
  const GantrySeen seen = drive_under_the_gantry(builtin_sensor_config("srr24"), 0.5);
  ASSERT_GT(seen.detections, 0);
  EXPECT_LT(seen.nearest_in_lane_m, 5.0);  // still in the lane 5 m before it: the classic false alarm
  EXPECT_DOUBLE_EQ(seen.highest_m, 0.5);  // no heights: at the sensor's level
}

TEST(HardCaseRoadUsers, ARadarThatMeasuresElevationSeesTheGantryAtItsHeightAndLosesItAboveItsView) {
  SensorConfig config = builtin_sensor_config("srr24");
  config.fov.elevation_half_rad = 10.0 * kDeg;
  const GantrySeen seen = drive_under_the_gantry(config, 0.5);
  ASSERT_GT(seen.detections, 0);
  // The beam (5.6 m) and the board (6.25 m) lie 5.1 and 5.75 m above the sensor: they leave a
  // +-10 deg view nearer than 5.1 / tan(10 deg) = 28.9 m (the posts at 3 m, 7 m aside, stay).
  EXPECT_GT(seen.lowest_m, 2.9);
  EXPECT_LT(seen.highest_m, 6.3);
  // Nothing in the lane at road level: every detection within the lane lies above 5 m.
  const Scene scene = gantry_scene(config, 0.5);
  SimulationOptions options;
  options.noise = false;
  options.level = ListLevel::detections;
  Simulation sim(scene, options);
  double nearest_overhead_m = 1e9;
  for (int k = 0; k < sim.cycle_count(); ++k) {
    sim.run_cycle(k);
    for (const Detection& d : sim.sensor_state(0).detections) {
      const double y_m = d.range_m * std::cos(d.elevation_rad) * std::sin(d.azimuth_rad);
      if (d.object_index != 0 || std::abs(y_m) > 3.0) continue;
      EXPECT_GT(0.5 + d.range_m * std::sin(d.elevation_rad), 5.0) << "cycle " << k;
      nearest_overhead_m = std::min(nearest_overhead_m, 60.0 - sim.snapshot().ego.X_WB.x_m);
    }
  }
  EXPECT_GT(nearest_overhead_m, 5.1 / std::tan(10.0 * kDeg) - 0.5);
  EXPECT_LT(nearest_overhead_m, 40.0);
}

// astyx_hires with a threshold low enough for the limbs, no diffuse pieces, 5-deg beams (so that
// azimuth keeps nothing apart) and the given Doppler cell.
SensorConfig limb_counting_profile(double range_rate_cell_mps) {
  SensorConfig config = builtin_sensor_config("astyx_hires");
  config.amplitude.detection_threshold_db = 20.0;
  config.extended_objects.diffuse_relative_ercs_per_sqrt_m = 0.0;
  config.resolution.azimuth_cell_rad = 5.0 * kDeg;
  config.resolution.range_rate_cell_mps = range_rate_cell_mps;
  config.resolution.unambiguous_min_mps = config.resolution.unambiguous_max_mps = 0.0;
  config.resolution.window = SpectralWindow::none;
  return config;
}

int pedestrian_detections(double range_rate_cell_mps) {
  Scene scene = testing::single_sensor_scene(0.5);
  scene.sensors[0].config = limb_counting_profile(range_rate_cell_mps);
  scene.cycle_time_s = 0.1;
  add_object(scene, "walker", "pedestrian", {sample(0.0, 10.0, 0.0, kPi, 1.4), sample(0.5, 9.3, 0.0, kPi, 1.4)});
  SimulationOptions options;
  options.noise = false;
  options.level = ListLevel::detections;
  Simulation sim(scene, options);
  sim.run_cycle(0);  // t = 0: the left leg forward at 2 v, the right one standing
  const auto& detections = sim.sensor_state(0).detections;
  return static_cast<int>(std::count_if(detections.begin(), detections.end(), [](const Detection& d) { return d.object_index == 0; }));
}

TEST(HardCaseRoadUsers, AWalkerIsOneTargetInACoarseDopplerCellAndOnePerLimbInAFineOne) {
  // At t = 0 (phase 0): legs at -2.8 and 0 m/s, arms at -0.56 and -2.24, torso -1.4, all at 10 m.
  EXPECT_EQ(pedestrian_detections(4.0), 1);   // +-2 m/s about the torso's: one cell
  EXPECT_EQ(pedestrian_detections(0.08), 5);  // each its own Doppler cell
}

}  // namespace road_users_test
}  // namespace rcsim
