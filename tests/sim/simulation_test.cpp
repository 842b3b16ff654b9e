// Running a scene cycle by cycle (sim/simulation.hpp): the broad phase decides which objects are
// evaluated, object_state answers for all, cull_within moves the window, and every sensor draws
// from its own random stream.
#include "sim/simulation.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "common/angles.hpp"
#include "test_support.hpp"

namespace rcsim::simulation_test {


// The simulation evaluates only what the broad phase selected, and still answers for every object.
TEST(SimulationCycles, SkipsObjectsOutOfReachButAnswersForEvery) {
  const Scene scene = testing::four_cars_scene();
  SimulationOptions options;
  Simulation simulation(scene, options);
  simulation.run_at(0.0);
  EXPECT_EQ(simulation.snapshot().visited_indices, (std::vector<std::uint32_t>{0, 3}));
  EXPECT_EQ(simulation.snapshot().visited[1], 0);
  EXPECT_DOUBLE_EQ(simulation.object_state(1).X_WB.x_m, 500.0);
  EXPECT_DOUBLE_EQ(simulation.object_state(2).X_WB.x_m, 80.0);
  options.culling = false;
  Simulation unculled(scene, options);
  unculled.run_at(0.0);
  EXPECT_EQ(unculled.snapshot().visited_indices, (std::vector<std::uint32_t>{0, 1, 2, 3}));
}

TEST(SimulationCycles, CullWithinMovesTheBroadPhaseToAWindow) {
  const Scene scene = testing::four_cars_scene();
  Simulation simulation(scene, SimulationOptions{});
  simulation.cull_within(1.0, 2.0);
  // Before the window every present object is visited ("gone" has left at 0.6 s) ...
  simulation.run_at(0.6);
  EXPECT_EQ(simulation.snapshot().visited_indices, (std::vector<std::uint32_t>{0, 1, 2}));
  // ... within it only those in reach: "arriving" is at 80 - 20 x 1.5 = 50 m, within 40 + 2.5 + 1.
  simulation.run_at(1.5);
  EXPECT_EQ(simulation.snapshot().visited_indices, (std::vector<std::uint32_t>{0, 2}));
  EXPECT_EQ(simulation.snapshot().visited[3], 0);
  EXPECT_DOUBLE_EQ(simulation.object_state(2).X_WB.x_m, 50.0);
  // Without culling there is no window to move.
  SimulationOptions off;
  off.culling = false;
  Simulation unculled(scene, off);
  unculled.cull_within(1.0, 2.0);
  unculled.run_at(1.5);
  EXPECT_EQ(unculled.snapshot().visited_indices, (std::vector<std::uint32_t>{0, 1, 2}));
}

// The detections of sensor 0 over the first cycles, as (range, azimuth) pairs.
std::vector<double> first_sensor_detections(const Scene& scene, std::uint64_t seed) {
  SimulationOptions options;
  options.level = ListLevel::detections;
  options.seed = seed;
  Simulation simulation(scene, options);
  std::vector<double> values;
  for (int k = 0; k < 5; ++k) {
    simulation.run_cycle(k);
    for (const Detection& d : simulation.sensor_state(0).detections) {
      values.push_back(d.range_m);
      values.push_back(d.azimuth_rad);
    }
  }
  return values;
}

TEST(SimulationCycles, CyclesRunAtTheirTimesAndEachSensorDrawsFromItsOwnStream) {
  Scene scene = testing::single_sensor_scene(1.0);
  testing::add_object(scene, "car", "passenger_car", {testing::sample(0, 15, 0, kPi, 0)});
  Simulation simulation(scene, SimulationOptions{});
  EXPECT_EQ(simulation.cycle_count(), 26);  // 0, 0.04, ..., 1.0 s
  EXPECT_EQ(simulation.sensor_count(), 1u);
  simulation.run_cycle(3);
  EXPECT_DOUBLE_EQ(simulation.snapshot().t_s, 0.12);  // 3 x 0.04 s
  const std::vector<double> alone = first_sensor_detections(scene, 7);
  ASSERT_FALSE(alone.empty());
  EXPECT_NE(alone, first_sensor_detections(scene, 8));  // the noise is drawn: the seed matters
  // A second sensor (rear-facing, at the back) leaves the first one's draws alone.
  MountedSensor rear = scene.sensors[0];
  rear.id = "rear";
  rear.X_VS = {-1.0, 0.0, kPi};
  scene.sensors.push_back(rear);
  EXPECT_EQ(first_sensor_detections(scene, 7), alone);
}

}  // namespace rcsim::simulation_test
