// The road under the boxes (replay/import/ground_plane.hpp) by hand: box bottoms on a road 1.5 m
// below a radar pitched 2 deg down give back that height and pitch; too few boxes, or a "road"
// that is no mounting, give none.
#include "replay/import/ground_plane.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angles.hpp"

namespace rcsim::replay::ground_plane_test {

// A snapshot recording of n boxes at 5, 10, 15, ... m, each 1.5 m high, its bottom on the road
// z = tan(pitch) x - h / cos(pitch) of the sensor's pitched frame.
Recording boxes_on_a_road(int n, double h_m, double pitch_rad) {
  Recording rec;
  for (int i = 0; i < n; ++i) {
    const double x_m = 5.0 * (i + 1);
    const double bottom_m = std::tan(pitch_rad) * x_m - h_m / std::cos(pitch_rad);
    RecordingObject o{std::string("o").append(std::to_string(i)), "passenger_car", 4.0, 1.8};
    o.attributes = {{"z_m", bottom_m + 0.75}, {"height_m", 1.5}};
    rec.objects.push_back(o);
    rec.boxes.push_back({AnnotatedBox{static_cast<double>(i), x_m * 0.8, x_m * 0.6, 0.0, 0.0, 0}});  // 0.8, 0.6: hypot = x
  }
  return rec;
}

TEST(GroundPlane, BoxBottomsOnALevelRoadGiveTheMountingsHeightAndPitch) {
  const auto fit = fit_ground_plane(boxes_on_a_road(12, 1.5, deg_to_rad(2.0)));
  ASSERT_TRUE(fit.has_value());
  EXPECT_NEAR(fit->z_m, 1.5, 1e-9);
  EXPECT_NEAR(fit->pitch_rad, deg_to_rad(2.0), 1e-12);
  EXPECT_EQ(fit->boxes, 12);
  EXPECT_NEAR(fit->residual_rms_m, 0.0, 1e-6);
  EXPECT_EQ(describe(*fit), "the road 1.50 m below the radar, pitched 2.00 deg down (a plane through 12 box bottoms, 0.00 m rms)");
}

TEST(GroundPlane, TooFewBoxesOrNoMountingGiveNone) {
  EXPECT_FALSE(fit_ground_plane(boxes_on_a_road(9, 1.5, 0.0)).has_value());
  EXPECT_FALSE(fit_ground_plane(boxes_on_a_road(12, 8.0, 0.0)).has_value());              // 8 m up: no car's radar
  EXPECT_FALSE(fit_ground_plane(boxes_on_a_road(12, 1.5, deg_to_rad(20.0))).has_value()); // pitched 20 deg
  Recording unlabelled = boxes_on_a_road(12, 1.5, 0.0);
  for (auto& o : unlabelled.objects) o.attributes = nlohmann::json::object();  // no heights given
  EXPECT_FALSE(fit_ground_plane(unlabelled).has_value());
}

}  // namespace rcsim::replay::ground_plane_test
