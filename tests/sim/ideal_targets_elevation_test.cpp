// The ideal target list in 3D and the road users' swing (sim/ideal_targets.hpp; docs/model.md,
// "Elevation" and "Road users") by hand: heights through the mounting and its pitch, the view in
// elevation, a planar radar that ignores heights, and the radial speeds of a walking leg and a
// turning wheel over one period.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim/ideal_targets.hpp"
#include "test_support.hpp"

namespace rcsim {
namespace elevation_test {

// +-0.7 rad in azimuth, 0.2..40 m, +-0.3 rad in elevation (a radar that measures it).
FieldOfView view_3d() {
  FieldOfView fov{0.7, 0.2, 40.0};
  fov.elevation_half_rad = 0.3;
  return fov;
}

struct World3d {
  std::vector<SceneObject> objects;
  std::vector<BodyState> states;
  std::vector<std::uint32_t> visited;
  void add(const std::string& model, const Pose2& X_WO, double speed_mps = 0.0) {
    SceneObject o;
    o.id = model;
    o.model_name = model;
    o.model = testing::library().at(model);
    objects.push_back(o);
    BodyState s;
    s.X_WB = X_WO;
    s.v_WB_W = speed_mps * heading_vector(X_WO.yaw_rad);
    states.push_back(s);
    visited.push_back(static_cast<std::uint32_t>(visited.size()));
  }
  IdealTargets targets(const FieldOfView& fov, const SensorKinematics& sensor) const {
    IdealTargets out;
    compute_ideal_targets(fov, sensor, objects, states, visited, out);
    return out;
  }
};

// The pole's reflector stands 0.5 m above the road (pole.json).
TEST(IdealTargetsElevation, APoleSeenFromAMountingAboveByHand) {
  World3d w;
  w.add("pole", {10.0, 0.0, kPi}, 3.0);  // 10 m ahead, coming at 3 m/s
  SensorKinematics sensor;
  sensor.z_WS_m = 1.5;  // 1 m above the pole's reflector
  const IdealTargets out = w.targets(view_3d(), sensor);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].range_m, std::sqrt(101.0), 1e-12);  // the slant range
  EXPECT_NEAR(out[0].azimuth_rad, 0.0, 1e-12);
  EXPECT_NEAR(out[0].elevation_rad, std::atan2(-1.0, 10.0), 1e-12);  // below the boresight
  // The level velocity along the slant line of sight: -3 x 10 / sqrt(101).
  EXPECT_NEAR(out[0].range_rate_mps, -3.0 * 10.0 / std::sqrt(101.0), 1e-12);
  EXPECT_DOUBLE_EQ(out[0].z_WT_m, 0.5);
}

TEST(IdealTargetsElevation, APitchDownRaisesEveryElevationByItsAngle) {
  World3d w;
  w.add("pole", {10.0, 0.0, 0.0});
  SensorKinematics sensor;
  sensor.z_WS_m = 1.5;
  sensor.pitch_rad = 0.05;  // boresight 0.05 rad down: the pole lies 0.05 rad less below it
  const IdealTargets out = w.targets(view_3d(), sensor);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].elevation_rad, std::atan2(-1.0, 10.0) + 0.05, 1e-12);
  EXPECT_NEAR(out[0].range_m, std::sqrt(101.0), 1e-12);  // a rotation keeps the range
  EXPECT_NEAR(out[0].azimuth_rad, 0.0, 1e-12);
}

TEST(IdealTargetsElevation, AReflectorAboveTheViewInElevationIsNotSeenAndAPlanarRadarIgnoresHeights) {
  World3d w;
  w.add("pole", {2.0, 0.0, 0.0});  // 0.5 m high, 2 m ahead
  SensorKinematics sensor;
  sensor.z_WS_m = 1.5;  // atan(1 / 2) = 0.46 rad below: outside +-0.3
  EXPECT_TRUE(w.targets(view_3d(), sensor).empty());
  // A planar radar: no heights, the pole at 2 m on its boresight, elevation 0.
  const IdealTargets planar = w.targets(FieldOfView{0.7, 0.2, 40.0}, sensor);
  ASSERT_EQ(planar.size(), 1u);
  EXPECT_DOUBLE_EQ(planar[0].range_m, 2.0);
  EXPECT_DOUBLE_EQ(planar[0].elevation_rad, 0.0);
}

// The radial speeds of one reflector of `model` (named) over one period of its swing, sampled at
// n evenly spaced times: a walker or rider coming straight at the sensor at speed_mps.
std::vector<double> radial_speeds_over(const std::string& model, const std::string& reflector, double speed_mps,
                                       double period_s, int n) {
  World3d w;
  w.add(model, {10.0, 0.0, kPi}, speed_mps);
  const auto& points = w.objects[0].model.points;
  const auto k = static_cast<int>(std::find_if(points.begin(), points.end(), [&](const PointReflector& p) {
                                    return p.name == reflector;
                                  }) - points.begin());
  std::vector<double> speeds;
  for (int i = 0; i < n; ++i) {
    SensorKinematics sensor;
    sensor.t_s = period_s * i / n;
    for (const IdealTarget& t : w.targets(FieldOfView{0.7, 0.2, 40.0}, sensor)) {
      if (t.kind == ReflectorKind::Point && t.reflector_index == k) speeds.push_back(t.range_rate_mps);
    }
  }
  return speeds;
}

// pedestrian.json: a leg swings with k = 1 over a gait of 1.1 s, so its speed along the heading
// runs over v (1 + cos): from 0 to 2 v, about the torso's v; an arm's (k = 0.6) from 0.4 v to 1.6 v.
// The leg stands 0.1 m and the arm 0.25 m to the side: their line of sight is cos = 10 / hypot(10, y).
TEST(IdealTargetsElevation, AWalkingLegSwingsFromStandToTwiceTheBodysSpeedOverAGait) {
  const double v_mps = 1.4;
  const double leg_los = 10.0 / std::hypot(10.0, 0.1), arm_los = 10.0 / std::hypot(10.0, 0.25);
  const std::vector<double> leg = radial_speeds_over("pedestrian", "leg_left", v_mps, 1.1, 1000);
  ASSERT_EQ(leg.size(), 1000u);
  // Coming at the sensor: radial speeds negative. Phase 0 at t = 0: the leg at 2 v.
  EXPECT_NEAR(leg[0], -2.0 * v_mps * leg_los, 1e-12);
  EXPECT_NEAR(leg[500], 0.0, 1e-12);  // half a gait later it stands
  EXPECT_NEAR(*std::min_element(leg.begin(), leg.end()), -2.0 * v_mps * leg_los, 1e-12);
  EXPECT_NEAR(*std::max_element(leg.begin(), leg.end()), 0.0, 1e-12);
  double mean = 0.0;
  for (const double s : leg) mean += s / static_cast<double>(leg.size());
  EXPECT_NEAR(mean, -v_mps * leg_los, 1e-12);  // over a whole gait, the torso's speed
  const std::vector<double> arm = radial_speeds_over("pedestrian", "arm_left", v_mps, 1.1, 1000);
  EXPECT_NEAR(*std::min_element(arm.begin(), arm.end()), -1.6 * v_mps * arm_los, 1e-12);
  EXPECT_NEAR(*std::max_element(arm.begin(), arm.end()), -0.4 * v_mps * arm_los, 1e-12);
  EXPECT_NEAR(arm[0], -0.4 * v_mps * arm_los, 1e-12);  // phase 180: back while the left leg is forward
  const std::vector<double> torso = radial_speeds_over("pedestrian", "torso", v_mps, 1.1, 10);
  for (const double s : torso) EXPECT_NEAR(s, -v_mps, 1e-12);
}

// cyclist.json: a spoke point turns with its wheel (R = 0.34 m): period 2 pi R / v, speed along
// the heading v (1 + 0.6 cos).
TEST(IdealTargetsElevation, ASpokeTurnsWithItsWheelOncePerTwoPiRadiiTravelled) {
  const double v_mps = 5.0, period_s = kTwoPi * 0.34 / v_mps;
  const std::vector<double> spoke = radial_speeds_over("cyclist", "spoke_front_a", v_mps, period_s, 400);
  ASSERT_EQ(spoke.size(), 400u);
  EXPECT_NEAR(spoke[0], -1.6 * v_mps, 1e-12);
  EXPECT_NEAR(spoke[200], -0.4 * v_mps, 1e-12);
  EXPECT_NEAR(*std::max_element(spoke.begin(), spoke.end()) - *std::min_element(spoke.begin(), spoke.end()),
              2.0 * 0.6 * v_mps, 1e-12);
}

TEST(IdealTargetsElevation, AStandingPedestrianDoesNotSwing) {
  const std::vector<double> leg = radial_speeds_over("pedestrian", "leg_left", 0.0, 1.1, 50);
  ASSERT_EQ(leg.size(), 50u);
  for (const double s : leg) EXPECT_EQ(s, 0.0);
}

}  // namespace elevation_test
}  // namespace rcsim
