// The ideal target list (sim/ideal_targets.hpp, paper II-B, IV-2/3) by hand: a pole ahead gives
// one target with its range, azimuth, range rate and ERCS; an object behind the sensor gives
// none; points_only leaves the planes out; the mounting offset adds omega x r to the sensor's
// velocity.
#include "sim/ideal_targets.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"

namespace rcsim {
namespace {

const FieldOfView kFov{0.7, 0.2, 40.0};  // +-0.7 rad, 0.2..40 m

struct World {
  std::vector<SceneObject> objects;
  std::vector<BodyState> states;
  std::vector<std::uint32_t> visited;
  void add(const std::string& model, const Pose2& X_WO, const Vec2& v_W = Vec2::Zero()) {
    SceneObject o;
    o.id = model;
    o.model_name = model;
    o.model = testing::library().at(model);
    objects.push_back(o);
    BodyState s;
    s.X_WB = X_WO;
    s.v_WB_W = v_W;
    states.push_back(s);
    visited.push_back(static_cast<std::uint32_t>(visited.size()));
  }
};

TEST(IdealTargets, APoleAheadByHand) {
  World w;
  w.add("pole", {8.0, 6.0, 0.0}, {-3.0, 0.0});  // 10 m away at atan2(6, 8), approaching along -x
  SensorKinematics sensor;  // at the origin, looking along +x, standing
  IdealTargets out;
  compute_ideal_targets(kFov, sensor, w.objects, w.states, w.visited, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].range_m, 10.0, 1e-12);
  EXPECT_NEAR(out[0].azimuth_rad, std::atan2(6.0, 8.0), 1e-12);
  EXPECT_NEAR(out[0].sin_azimuth, 0.6, 1e-12);
  EXPECT_NEAR(out[0].range_rate_mps, -3.0 * 0.8, 1e-12);  // the velocity projected on the line of sight
  EXPECT_DOUBLE_EQ(out[0].ercs, 1.0);  // the reference reflector (paper III-B)
  EXPECT_EQ(out[0].object_index, 0);
}

TEST(IdealTargets, NothingBehindTheSensorOrBeyondItsRange) {
  World w;
  w.add("pole", {-5.0, 0.0, 0.0});
  w.add("pole", {45.0, 0.0, 0.0});
  w.add("pole", {5.0, 5.0, 0.0});  // 0.785 rad off the boresight: outside +-0.7
  IdealTargets out;
  compute_ideal_targets(kFov, SensorKinematics{}, w.objects, w.states, w.visited, out);
  EXPECT_TRUE(out.empty());
}

TEST(IdealTargets, PointsOnlyLeavesThePlanesOut) {
  World w;
  w.add("passenger_car", {15.0, 0.0, kPi});  // its front towards the sensor
  IdealTargets all, points;
  compute_ideal_targets(kFov, SensorKinematics{}, w.objects, w.states, w.visited, all);
  IdealTargetFilter filter;
  filter.planes = false;
  compute_ideal_targets(kFov, SensorKinematics{}, w.objects, w.states, w.visited, points, filter);
  int planes = 0;
  for (const auto& t : all) planes += t.kind == ReflectorKind::Plane;
  EXPECT_GT(planes, 0);
  EXPECT_EQ(points.size() + static_cast<std::size_t>(planes), all.size());
  for (const auto& t : points) EXPECT_EQ(t.kind, ReflectorKind::Point);
  // The front plane's reflection point is on the car's front face, 15 - 2.3 m away (Fig. 3 model).
  for (const auto& t : all) {
    if (t.kind == ReflectorKind::Plane && std::abs(t.azimuth_rad) < 1e-9) {
      EXPECT_NEAR(t.range_m, 15.0 - 0.5 * w.objects[0].model.length_m, 0.2);
    }
  }
}

TEST(IdealTargets, TheMountingOffsetAddsOmegaCrossR) {
  BodyState ego;
  ego.v_WB_W = {10.0, 0.0};
  ego.yaw_rate_radps = 0.5;
  const SensorKinematics k = sensor_kinematics(ego, Pose2{3.0, 1.0, 0.2});
  EXPECT_NEAR(k.X_WS.x_m, 3.0, 1e-12);
  EXPECT_NEAR(k.X_WS.yaw_rad, 0.2, 1e-12);
  EXPECT_NEAR(k.v_WS_W.x(), 10.0 - 0.5 * 1.0, 1e-12);
  EXPECT_NEAR(k.v_WS_W.y(), 0.5 * 3.0, 1e-12);
}

}  // namespace
}  // namespace rcsim
