// The road geometry of traffic/road.hpp: straight, circular and winding reference lines, the lane
// offsets, and the world motion of a vehicle at road coordinates (s, d), all by hand.
#include "traffic/road.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angles.hpp"

namespace rcsim::road_test {

using traffic::Centerline;
using traffic::CenterlinePoint;
using traffic::Road;
using traffic::WorldMotion;
using traffic::world_motion;

TEST(TrafficRoad, StraightAndCircleByHand) {
  // Straight from (1, 2) heading north: s = 5 is (1, 7); s = -1 is behind the start, (1, 1).
  const Centerline straight = Centerline::straight(Vec2(1.0, 2.0), kPi / 2.0, 50.0);
  EXPECT_FALSE(straight.closed());
  EXPECT_DOUBLE_EQ(straight.length_m(), 50.0);
  const CenterlinePoint a = straight.at(5.0);
  EXPECT_NEAR(a.p_WR_W.x(), 1.0, 1e-12);
  EXPECT_NEAR(a.p_WR_W.y(), 7.0, 1e-12);
  EXPECT_DOUBLE_EQ(a.heading_rad, kPi / 2.0);
  EXPECT_EQ(a.curvature_1pm, 0.0);
  EXPECT_NEAR(straight.at(-1.0).p_WR_W.y(), 1.0, 1e-12);

  // Circle of circumference 200 pi: R = 100, from (0, -100) along +x, counter-clockwise.
  const Centerline circle = Centerline::circle(200.0 * kPi);
  EXPECT_TRUE(circle.closed());
  const CenterlinePoint start = circle.at(0.0);
  EXPECT_NEAR(start.p_WR_W.x(), 0.0, 1e-12);
  EXPECT_NEAR(start.p_WR_W.y(), -100.0, 1e-12);
  EXPECT_NEAR(start.heading_rad, 0.0, 1e-12);
  EXPECT_NEAR(start.curvature_1pm, 0.01, 1e-15);
  // A quarter round: (100, 0) heading north; half round: (0, 100) heading west.
  const CenterlinePoint quarter = circle.at(50.0 * kPi);
  EXPECT_NEAR(quarter.p_WR_W.x(), 100.0, 1e-9);
  EXPECT_NEAR(quarter.p_WR_W.y(), 0.0, 1e-9);
  EXPECT_NEAR(quarter.heading_rad, kPi / 2.0, 1e-12);
  const CenterlinePoint half = circle.at(100.0 * kPi);
  EXPECT_NEAR(half.p_WR_W.x(), 0.0, 1e-9);
  EXPECT_NEAR(half.p_WR_W.y(), 100.0, 1e-9);
  EXPECT_NEAR(std::cos(half.heading_rad), -1.0, 1e-12);
  // Three quarters: heading wrapped to -pi/2 (south), not 3 pi / 2.
  EXPECT_NEAR(circle.at(150.0 * kPi).heading_rad, -kPi / 2.0, 1e-12);
}

TEST(TrafficRoad, WindingFollowsItsCurvatureAndIsParametrisedByArcLength) {
  // R = 500 m, wavelength 2000 m: heading = 2000 / (2 pi 500) (1 - cos(2 pi s / 2000)).
  const Centerline road = Centerline::winding(1000.0, 500.0, 2000.0);
  const double amplitude_rad = 2000.0 / (kTwoPi * 500.0);  // 0.6366
  const CenterlinePoint origin = road.at(0.0);
  EXPECT_EQ(origin.p_WR_W, Vec2::Zero());
  EXPECT_NEAR(origin.heading_rad, 0.0, 1e-15);
  EXPECT_NEAR(origin.curvature_1pm, 0.0, 1e-15);
  // Quarter wavelength: the tightest bend, 1/R, heading amplitude x 1.
  EXPECT_NEAR(road.at(500.0).curvature_1pm, 1.0 / 500.0, 1e-12);
  EXPECT_NEAR(road.at(500.0).heading_rad, amplitude_rad, 1e-12);
  // Half wavelength: straight again, heading amplitude x 2.
  EXPECT_NEAR(road.at(1000.0).curvature_1pm, 0.0, 1e-12);
  EXPECT_NEAR(road.at(1000.0).heading_rad, 2.0 * amplitude_rad, 1e-12);
  // Arc length: 0.5 m along s is a chord of 0.5 m in the direction of the heading between.
  for (double s_m = 0.0; s_m < 1000.0; s_m += 37.3) {
    const Vec2 chord = road.at(s_m + 0.5).p_WR_W - road.at(s_m).p_WR_W;
    EXPECT_NEAR(chord.norm(), 0.5, 1e-3) << s_m;
    const double mid_heading_rad = road.at(s_m + 0.25).heading_rad;
    EXPECT_NEAR(angle_difference_rad(std::atan2(chord.y(), chord.x()), mid_heading_rad), 0.0, 2e-3) << s_m;
  }
  // Beyond the end (a vehicle leaving the road) the line goes on 10 m for 10 m of s, in about the
  // last heading (the heading formula runs on: 3e-4 rad off after 10 m here).
  const Vec2 beyond = road.at(1010.0).p_WR_W - road.at(1000.0).p_WR_W;
  EXPECT_NEAR(beyond.norm(), 10.0, 1e-9);
  EXPECT_NEAR(std::atan2(beyond.y(), beyond.x()), 2.0 * amplitude_rad, 1e-3);
}

TEST(TrafficRoad, LanesAreCentredOnTheReferenceLine) {
  Road road;
  road.lane_count = 3;  // 3.5 m lanes: -3.5, 0, 3.5 (lane 0 the rightmost)
  EXPECT_DOUBLE_EQ(road.lane_offset_m(0), -3.5);
  EXPECT_DOUBLE_EQ(road.lane_offset_m(1), 0.0);
  EXPECT_DOUBLE_EQ(road.lane_offset_m(2), 3.5);
  road.lane_count = 2;
  road.lane_width_m = 3.0;  // -1.5, 1.5
  EXPECT_DOUBLE_EQ(road.lane_offset_m(0), -1.5);
  EXPECT_DOUBLE_EQ(road.lane_offset_m(1), 1.5);
  road.lane_count = 1;
  EXPECT_DOUBLE_EQ(road.lane_offset_m(0), 0.0);
}

TEST(TrafficRoad, WorldMotionOnStraightAndCurvedLanes) {
  const Centerline straight = Centerline::straight(Vec2::Zero(), 0.0, 500.0);
  // In the left lane, no lane change: (10, 3.5), along +x at 20 m/s, not turning.
  const WorldMotion lane = world_motion(straight, 10.0, 3.5, 0.0, 0.0, 20.0);
  EXPECT_NEAR(lane.x_m, 10.0, 1e-12);
  EXPECT_NEAR(lane.y_m, 3.5, 1e-12);
  EXPECT_NEAR(lane.yaw_rad, 0.0, 1e-12);
  EXPECT_NEAR(lane.speed_mps, 20.0, 1e-12);
  EXPECT_NEAR(lane.yaw_rate_radps, 0.0, 1e-12);
  // Changing lanes to the left with dd/ds = 0.1, d2d/ds2 = 0.002: yaw atan(0.1), speed
  // 20 sqrt(1.01), yaw rate 20 * 0.002 / (1 + 0.01).
  const WorldMotion change = world_motion(straight, 10.0, 1.0, 0.1, 0.002, 20.0);
  EXPECT_NEAR(change.yaw_rad, std::atan(0.1), 1e-12);
  EXPECT_NEAR(change.speed_mps, 20.0 * std::sqrt(1.01), 1e-12);
  EXPECT_NEAR(change.yaw_rate_radps, 20.0 * 0.002 / 1.01, 1e-12);
  // Standing mid-change: still pointing along the path, no speed, no turning.
  const WorldMotion standing = world_motion(straight, 10.0, 1.0, 0.1, 0.002, 0.0);
  EXPECT_NEAR(standing.yaw_rad, std::atan(0.1), 1e-12);
  EXPECT_EQ(standing.speed_mps, 0.0);
  EXPECT_EQ(standing.yaw_rate_radps, 0.0);
  // On a circle of R = 100, 5 m to the inside: at (0, -95), speed 10 (1 - 5/100) = 9.5 m/s,
  // turning at ds/dt kappa = 0.1 rad/s (= 9.5 m/s on a 95 m radius).
  const WorldMotion inside = world_motion(Centerline::circle(200.0 * kPi), 0.0, 5.0, 0.0, 0.0, 10.0);
  EXPECT_NEAR(inside.x_m, 0.0, 1e-12);
  EXPECT_NEAR(inside.y_m, -95.0, 1e-12);
  EXPECT_NEAR(inside.yaw_rad, 0.0, 1e-12);
  EXPECT_NEAR(inside.speed_mps, 9.5, 1e-12);
  EXPECT_NEAR(inside.yaw_rate_radps, 0.1, 1e-12);
}

}  // namespace rcsim::road_test
