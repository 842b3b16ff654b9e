// Effects: multibounce (paper V/VI), occlusion, clutter (paper VI).
#include "sim/effects.hpp"

#include <gtest/gtest.h>

#include "common/angles.hpp"
#include "sim/simulation.hpp"
#include "test_support.hpp"

namespace rcsim {
namespace {

using testing::add_object;
using testing::sample;
using testing::single_sensor_scene;

TEST(Effects, MultibounceDuplicatesAtIntegerMultiples) {
  Scene scene = single_sensor_scene();
  scene.effects.multibounce = true;
  add_object(scene, "near", "pole", {sample(0, 1.0, 0.0, 0, -0.5)});
  add_object(scene, "far", "pole", {sample(0, 5.0, 0.0, 0, 0)});
  SimulationOptions o;
  o.level = OutputLevel::ideal;
  Simulation sim(scene, o);
  sim.run_cycle(0);
  const auto& t = sim.sensor_state(0).ideal;
  ASSERT_EQ(t.size(), 4u);  // near x1, x2, x3; far only direct (beyond 3 m)
  EXPECT_DOUBLE_EQ(t[2].range_m, 2.0);
  EXPECT_DOUBLE_EQ(t[3].range_m, 3.0);
  EXPECT_DOUBLE_EQ(t[3].range_rate_mps, 3.0 * t[0].range_rate_mps);
  EXPECT_NEAR(t[2].ercs, std::pow(10.0, -6.0 / 20.0), 1e-12);  // 6 dB per extra round trip
  EXPECT_NEAR(t[3].ercs, std::pow(10.0, -12.0 / 20.0), 1e-12);
  EXPECT_EQ(t[3].bounce_order, 3);
}

TEST(Effects, SegmentBoxIntersection) {
  const Pose2 box{5.0, 0.0, 0.3};
  EXPECT_TRUE(segment_hits_box({0, 0}, {10, 0}, box, 4.6, 1.8));
  EXPECT_FALSE(segment_hits_box({0, 0}, {2.4, 0}, box, 4.6, 1.8));  // nearest corner at x = 2.54
  EXPECT_FALSE(segment_hits_box({0, 5}, {10, 5}, box, 4.6, 1.8));
  EXPECT_TRUE(segment_hits_box({5, 0}, {5, 0}, box, 4.6, 1.8));  // degenerate segment inside
}

TEST(Effects, OcclusionHidesWhatIsBehindANearerObject) {
  Scene scene = single_sensor_scene();
  add_object(scene, "behind", "pole", {sample(0, 15.0, 0.0, 0, 0)});
  add_object(scene, "car", "passenger_car", {sample(0, 8.0, 0.0, kPi / 2, 0)});
  SimulationOptions o;
  o.level = OutputLevel::ideal;
  {
    Simulation sim(scene, o);
    sim.run_cycle(0);
    bool pole_seen = false;
    for (const auto& t : sim.sensor_state(0).ideal) pole_seen = pole_seen || t.object_index == 0;
    EXPECT_TRUE(pole_seen);
  }
  scene.effects.occlusion = true;
  Simulation sim(scene, o);
  sim.run_cycle(0);
  for (const auto& t : sim.sensor_state(0).ideal) EXPECT_EQ(t.object_index, 1);
  EXPECT_FALSE(sim.sensor_state(0).ideal.empty());
}

TEST(Effects, ClutterRateAndPlacement) {
  const SensorConfig config = builtin_sensor_config("srr24");
  SensorKinematics sensor;
  sensor.v_WS_W = {10.0, 0.0};
  Rng rng(11);
  Detections detections;
  const int cycles = 20000;
  for (int k = 0; k < cycles; ++k) add_clutter(config, sensor, rng, detections);
  EXPECT_NEAR(static_cast<double>(detections.size()) / cycles, config.clutter.false_detections_per_cycle, 0.02);
  for (const auto& d : detections) {
    ASSERT_LE(std::abs(d.azimuth_rad), config.fov.azimuth_half_rad);
    ASSERT_GE(d.amplitude_db, config.amplitude.detection_threshold_db);
    ASSERT_NEAR(d.range_rate_mps, -10.0 * std::cos(d.azimuth_rad), 1e-9);  // stationary
    ASSERT_EQ(d.object_index, -1);
  }
}

TEST(Effects, OffUnlessAsked) {
  Scene scene = single_sensor_scene(2.0);
  add_object(scene, "near", "pole", {sample(0, 1.0, 0.0, 0, 0)});
  Simulation sim(scene, SimulationOptions{OutputLevel::detections, 5, true});
  for (int k = 0; k < sim.cycle_count(); ++k) {
    sim.run_cycle(k);
    EXPECT_EQ(sim.sensor_state(0).detections.size(), 1u);  // no duplicates, no clutter
  }
}

}  // namespace
}  // namespace rcsim
