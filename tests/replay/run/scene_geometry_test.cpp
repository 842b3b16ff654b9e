// What the scene's geometry says (replay/run/scene_geometry.hpp), by hand from the paper: a pole
// (ERCS 1) is detectable inside the range where eq. (1) puts it at the threshold, 27.33 m for
// srr24 ((26.5 - 6) / 0.75), and not beyond it, even off boresight; a pole hidden behind a car is not; two cars abreast at one range and speed share a
// resolution cell (Fig. 10) and cars 2 m apart in range do not.
#include "replay/run/scene_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sim/amplitude.hpp"
#include "test_support.hpp"

namespace rcsim::replay {
namespace {

std::vector<char> detectable_now(SceneGeometry& geometry, std::size_t objects) {
  std::vector<char> detectable(objects, 0);
  geometry.run_at(0.0);
  geometry.mark_detectable(0, detectable);
  return detectable;
}

TEST(SceneGeometry, APoleIsDetectableInsideTheRangeOfEquationOneAndNotBeyond) {
  Scene scene = testing::single_sensor_scene();
  const double bound_m = detection_range_bound_m(scene.sensors[0].config.amplitude, 1.0);  // 27.3 m for srr24
  ASSERT_NEAR(bound_m, 27.33, 0.01);
  // The inside pole 0.5 rad off boresight: the antenna pattern does not count, eq. (1) does.
  const double r_m = 0.99 * bound_m;
  testing::add_object(scene, "inside", "pole", {testing::sample(0.0, r_m * std::cos(0.5), r_m * std::sin(0.5), 0.0, 0.0)});
  testing::add_object(scene, "beyond", "pole", {testing::sample(0.0, 1.01 * bound_m, -1.0, 0.0, 0.0)});
  SceneGeometry geometry(scene);
  const auto d = detectable_now(geometry, 2);
  EXPECT_EQ(d[0], 1);
  EXPECT_EQ(d[1], 0);
}

TEST(SceneGeometry, APoleBehindACarIsNotDetectable) {
  Scene scene = testing::single_sensor_scene();
  scene.effects.occlusion = true;
  testing::add_object(scene, "car", "passenger_car", {testing::sample(0.0, 8.0, 0.0, 0.0, 0.0)});
  testing::add_object(scene, "pole", "pole", {testing::sample(0.0, 14.0, 0.0, 0.0, 0.0)});
  SceneGeometry geometry(scene);
  const auto hidden = detectable_now(geometry, 2);
  EXPECT_EQ(hidden[0], 1);
  EXPECT_EQ(hidden[1], 0);
  scene.effects.occlusion = false;  // the same scene without occlusion: the pole shows
  SceneGeometry open(scene);
  EXPECT_EQ(detectable_now(open, 2)[1], 1);
}

TEST(SceneGeometry, CarsAbreastShareACellAndCarsApartInRangeDoNot) {
  Scene abreast = testing::single_sensor_scene();
  testing::add_object(abreast, "left", "passenger_car", {testing::sample(0.0, 12.0, 1.6, 0.0, 0.0)});
  testing::add_object(abreast, "right", "passenger_car", {testing::sample(0.0, 12.0, -1.6, 0.0, 0.0)});
  SceneGeometry geometry(abreast);
  geometry.run_at(0.0);
  const auto& cells = geometry.merge_cells(0);
  ASSERT_FALSE(cells.empty());
  for (const metrics::MergeCell& c : cells) {
    EXPECT_EQ(c.object_a, 0);
    EXPECT_EQ(c.object_b, 1);
    EXPECT_LT(c.azimuth_lo_rad, 0.0);  // the right car's echoes
    EXPECT_GT(c.azimuth_hi_rad, 0.0);  // the left car's
    EXPECT_NEAR(c.range_rate_mps, 0.0, 1e-9);
  }
  Scene apart = testing::single_sensor_scene();
  testing::add_object(apart, "left", "passenger_car", {testing::sample(0.0, 12.0, 1.6, 0.0, 0.0)});
  testing::add_object(apart, "right", "passenger_car", {testing::sample(0.0, 14.0, -1.6, 0.0, 0.0)});
  SceneGeometry other(apart);
  other.run_at(0.0);
  EXPECT_TRUE(other.merge_cells(0).empty());
}

}  // namespace
}  // namespace rcsim::replay
