// The scene's broad phase (sim/scene_culling.hpp): per time slice, which objects may lie within
// some sensor's reach (view range + reflection radius + 1 m); outside its times or when off, every
// present object.
#include "sim/scene_culling.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "common/angles.hpp"
#include "sim/culling.hpp"
#include "test_support.hpp"

namespace rcsim::scene_culling_test {

// The scene's broad phase: a car beyond every sensor's reach is not selected, one in reach is,
// absent ones never are; outside the cycle times every present object is.
TEST(SceneCulling, SelectsObjectsInReach) {
  const Scene scene = testing::four_cars_scene();
  std::vector<double> radius_m;
  for (const auto& o : scene.objects) radius_m.push_back(reflection_radius_m(o.model));
  const SceneCulling culling(scene, radius_m);
  ASSERT_TRUE(culling.enabled());
  EXPECT_EQ(culling.slice_count(), 4u);  // 1.95 s of cycles in 0.5-s slices
  const std::vector<Vec2> sensor = {Vec2(0.0, 0.0)};
  std::vector<std::uint32_t> selected;
  culling.select(0.0, sensor, scene.objects, selected);
  // "arriving" sweeps 80 -> 70 m in the first slice, beyond 40 m + its 2.5-m radius + 1 m.
  EXPECT_EQ(selected, (std::vector<std::uint32_t>{0, 3}));
  culling.select(1.9, sensor, scene.objects, selected);
  EXPECT_EQ(selected, (std::vector<std::uint32_t>{0, 2}));
  // Outside the scene's cycle times there are no slices: every present object.
  culling.select(5.0, sensor, scene.objects, selected);
  EXPECT_EQ(selected, (std::vector<std::uint32_t>{0, 1, 2}));
  // Off: every present object.
  SceneCulling().select(0.2, sensor, scene.objects, selected);
  EXPECT_EQ(selected, (std::vector<std::uint32_t>{0, 1, 2, 3}));
}

// Standing objects on the x axis and a reflection radius of 2 m each: the reach is srr24's 40 m
// view range + 2 m + 1 m margin (+ 1e-6 of the distance, 43 um here) = 43 m.
Scene standing_at(const std::vector<double>& x_m) {
  Scene scene = testing::single_sensor_scene(1.0);
  for (std::size_t i = 0; i < x_m.size(); ++i) {
    testing::add_object(scene, "pole" + std::to_string(i), "pole", {testing::sample(0, x_m[i], 0, 0, 0)});
  }
  return scene;
}

TEST(SceneCulling, TheReachIsTheViewRangePlusTheRadiusAndAMetreByHand) {
  const Scene scene = standing_at({42.99, 43.01, -42.99, 100.0});
  ASSERT_DOUBLE_EQ(scene.sensors[0].config.fov.max_range_m, 40.0);
  const std::vector<double> radius_m(scene.objects.size(), 2.0);
  const SceneCulling culling(scene, radius_m);
  EXPECT_EQ(culling.slice_count(), 2u);  // cycles 0 .. 1.0 s: ceil(1.0 / 0.5)
  EXPECT_DOUBLE_EQ(culling.slice_s(), 0.5);
  std::vector<std::uint32_t> selected;
  const std::vector<Vec2> origin = {Vec2(0.0, 0.0)};
  culling.select(0.3, origin, scene.objects, selected);
  EXPECT_EQ(selected, (std::vector<std::uint32_t>{0, 2}));  // behind the sensor too: no view wedge here
  // Any sensor's position will do: a second one at x = 60 m reaches 17 .. 103 m.
  const std::vector<Vec2> two = {Vec2(0.0, 0.0), Vec2(60.0, 0.0)};
  culling.select(0.3, two, scene.objects, selected);
  EXPECT_EQ(selected, (std::vector<std::uint32_t>{0, 1, 2, 3}));
  // A larger radius widens the reach: 3 m makes it 44 m.
  const SceneCulling wider(scene, std::vector<double>(scene.objects.size(), 3.0));
  wider.select(0.3, origin, scene.objects, selected);
  EXPECT_EQ(selected, (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST(SceneCulling, AWindowCullsOnlyWithinItAndWithoutSensorsOrRadiiNothingIs) {
  const Scene scene = standing_at({10.0, 100.0});
  const std::vector<double> radius_m(scene.objects.size(), 2.0);
  const std::vector<Vec2> origin = {Vec2(0.0, 0.0)};
  std::vector<std::uint32_t> selected;
  // Scene times [1, 2] only: two slices of 0.5 s; before the window every present object.
  const SceneCulling window(scene, radius_m, 1.0, 2.0);
  ASSERT_TRUE(window.enabled());
  EXPECT_EQ(window.slice_count(), 2u);
  window.select(0.5, origin, scene.objects, selected);
  EXPECT_EQ(selected, (std::vector<std::uint32_t>{0, 1}));
  window.select(1.5, origin, scene.objects, selected);
  EXPECT_EQ(selected, (std::vector<std::uint32_t>{0}));
  // A window of one instant: one slice.
  const SceneCulling instant(scene, radius_m, 1.0, 1.0);
  EXPECT_EQ(instant.slice_count(), 1u);
  instant.select(1.0, origin, scene.objects, selected);
  EXPECT_EQ(selected, (std::vector<std::uint32_t>{0}));
  // Off: a window that ends before it starts, a radius per object missing, no sensors.
  EXPECT_FALSE(SceneCulling(scene, radius_m, 2.0, 1.0).enabled());
  EXPECT_FALSE(SceneCulling(scene, std::vector<double>{2.0}).enabled());
  Scene no_sensors = scene;
  no_sensors.sensors.clear();
  const SceneCulling off(no_sensors, radius_m);
  EXPECT_FALSE(off.enabled());
  off.select(0.5, origin, scene.objects, selected);
  EXPECT_EQ(selected, (std::vector<std::uint32_t>{0, 1}));
}

}  // namespace rcsim::scene_culling_test
