// A box as one sensor sees it (metrics/sensor_view.hpp), by hand: nearest contour point, range,
// azimuth and radial speed; distance to the box; association to the nearest box within the gate.
#include "metrics/sensor_view.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angles.hpp"

namespace rcsim::metrics {
namespace {

TEST(SensorView, NearestContourPointOfABoxAheadAndItsRadialSpeed) {
  // Sensor at the world origin looking along +x; ego at rest. A 4 x 2 m box centred 12 m ahead,
  // 1 m to the left, driving towards the sensor at 5 m/s: the nearest point is the right end of
  // its front edge, (10, 0).
  const Pose2 X_WS{0.0, 0.0, 0.0};
  BodyState ego;
  BodyState object;
  object.X_WB = {12.0, 1.0, kPi};  // heading -x
  object.v_WB_W = {-5.0, 0.0};
  const BoxInSensor box = box_in_sensor(3, X_WS, ego, object, 4.0, 2.0);
  EXPECT_EQ(box.object, 3);
  EXPECT_NEAR(box.p_SN_S.x(), 10.0, 1e-12);
  EXPECT_NEAR(box.p_SN_S.y(), 0.0, 1e-12);
  EXPECT_NEAR(box.range_m, 10.0, 1e-12);
  EXPECT_NEAR(box.azimuth_rad, 0.0, 1e-12);
  EXPECT_NEAR(box.range_rate_mps, -5.0, 1e-12);  // approaching
  EXPECT_DOUBLE_EQ(box.half_length_m, 2.0);
}

TEST(SensorView, DistanceToTheBoxIsZeroInsideAndEuclideanOutside) {
  BodyState ego, object;
  object.X_WB = {10.0, 0.0, 0.0};
  const BoxInSensor box = box_in_sensor(0, Pose2{0.0, 0.0, 0.0}, ego, object, 4.0, 2.0);
  EXPECT_DOUBLE_EQ(distance_to_box_m(box, {10.5, 0.5}), 0.0);
  EXPECT_NEAR(distance_to_box_m(box, {7.0, 0.0}), 1.0, 1e-12);          // 1 m short of the rear
  EXPECT_NEAR(distance_to_box_m(box, {13.0, 2.0}), std::sqrt(2.0), 1e-12);  // off a corner
}

TEST(SensorView, ATargetBelongsToTheNearestBoxWithinTheGate) {
  BodyState ego, a, b;
  a.X_WB = {10.0, 0.0, 0.0};
  b.X_WB = {10.0, 3.0, 0.0};
  const std::vector<BoxInSensor> boxes{box_in_sensor(0, Pose2{}, ego, a, 4.0, 2.0),
                                       box_in_sensor(1, Pose2{}, ego, b, 4.0, 2.0)};
  EXPECT_EQ(nearest_box(boxes, {10.0, 1.4}, 1.0), 0);  // 0.4 m from a, 0.6 m from b
  EXPECT_EQ(nearest_box(boxes, {10.0, 1.6}, 1.0), 1);
  EXPECT_EQ(nearest_box(boxes, {10.0, 6.5}, 1.0), -1);  // 2.5 m from b: beyond the gate
}

}  // namespace
}  // namespace rcsim::metrics
