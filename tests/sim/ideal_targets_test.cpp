// The ideal target list (sim/ideal_targets.hpp, paper II-B, IV-2/3) by hand: a pole ahead gives
// one target with its range, azimuth, range rate and ERCS; an object behind the sensor gives
// none; points_only leaves the planes out; the mounting offset adds omega x r to the sensor's
// velocity.
#include "sim/ideal_targets.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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


// A face-only object: the 4-m chord (-2, 1) .. (2, 1) with 1 cm sagitta and ERCS 0.8, no points.
SceneObject face_object() {
  SceneObject o;
  o.id = "face";
  o.model_name = "custom";
  o.model.name = "face";
  o.model.length_m = 4.0;
  o.model.width_m = 2.0;
  o.model.planes.push_back(plane_from_chord("side", {-2.0, 1.0}, {2.0, 1.0}, 0.01, 0.8));
  return o;
}

TEST(IdealTargets, DiffusePiecesByHand) {
  // The object turned by +90 deg at (11, -10): object (x, y) -> world (11 - y, -10 + x), so the
  // sensor at the world origin sits at (10, 11) in the object frame, where the face has no
  // specular point but 6 diffuse pieces for 0.5-m cells (tests/sim/visibility_test.cpp), centred at
  // x_O = +-(2 - (2k + 1)/3), y_O = 1 => world (10, -10 + x_O), 4/6 m long.
  World w;
  w.objects.push_back(face_object());
  BodyState s;
  s.X_WB = {11.0, -10.0, kPi / 2};
  w.states.push_back(s);
  w.visited.push_back(0);
  const FieldOfView wide{1.2, 0.2, 40.0};  // +-68.8 deg: the pieces lie at -40 .. -49 deg
  IdealTargetFilter filter;
  filter.diffuse_relative_ercs_per_sqrt_m = 0.1;
  filter.diffuse_piece.piece_range_m = 0.5;
  IdealTargets out;
  compute_ideal_targets(wide, SensorKinematics{}, w.objects, w.states, w.visited, out, filter);
  ASSERT_EQ(out.size(), 6u);
  // ERCS = r x plane ERCS x sqrt(l / 1 m) = 0.1 x 0.8 x sqrt(2/3) = 0.0653197
  const double ercs = 0.1 * 0.8 * std::sqrt(2.0 / 3.0);
  EXPECT_NEAR(ercs, 0.0653197, 1e-7);
  std::vector<double> y_m;
  for (const auto& t : out) {
    EXPECT_EQ(t.kind, ReflectorKind::PlaneDiffuse);
    EXPECT_EQ(t.object_index, 0);
    EXPECT_EQ(t.reflector_index, 0);
    EXPECT_NEAR(t.ercs, ercs, 1e-12);
    EXPECT_NEAR(t.p_WT_W.x(), 10.0, 1e-9);
    EXPECT_NEAR(t.range_m, std::hypot(10.0, t.p_WT_W.y()), 1e-9);
    y_m.push_back(t.p_WT_W.y());
  }
  std::sort(y_m.begin(), y_m.end());
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(y_m[k], -10.0 - 2.0 + (2.0 * k + 1.0) / 3.0, 1e-9) << k;
  // Fidelity::points_only (no planes) has no diffuse pieces either.
  filter.planes = false;
  compute_ideal_targets(wide, SensorKinematics{}, w.objects, w.states, w.visited, out, filter);
  EXPECT_TRUE(out.empty());
  // In +-0.7 rad (40.1 deg) only the nearest piece is in view: y = -8.333 at atan(8.333/10) = 39.8
  // deg; the next, y = -9, lies at 42.0 deg.
  filter.planes = true;
  compute_ideal_targets(kFov, SensorKinematics{}, w.objects, w.states, w.visited, out, filter);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].p_WT_W.y(), -10.0 + 5.0 / 3.0, 1e-9);
}

TEST(IdealTargets, WithoutDiffusePiecesTheOutputIsThePapers) {
  World w;
  w.add("passenger_car", {15.0, 4.0, 0.6});  // seen obliquely: its rear and side face the sensor
  w.add("guide_board", {20.0, -3.0, kPi});
  IdealTargets before, zero, diffuse;
  compute_ideal_targets(kFov, SensorKinematics{}, w.objects, w.states, w.visited, before);
  IdealTargetFilter filter;
  filter.diffuse_piece.piece_range_m = 0.3;
  filter.diffuse_relative_ercs_per_sqrt_m = 0.0;
  compute_ideal_targets(kFov, SensorKinematics{}, w.objects, w.states, w.visited, zero, filter);
  const auto same = [](const IdealTarget& a, const IdealTarget& b) {
    return a.p_WT_W == b.p_WT_W && a.ercs == b.ercs && a.range_m == b.range_m && a.azimuth_rad == b.azimuth_rad &&
           a.range_rate_mps == b.range_rate_mps && a.object_index == b.object_index &&
           a.reflector_index == b.reflector_index && a.kind == b.kind;
  };
  ASSERT_EQ(zero.size(), before.size());
  for (std::size_t i = 0; i < before.size(); ++i) EXPECT_TRUE(same(zero[i], before[i])) << i;
  // With r > 0 the same targets, in the same order, plus PlaneDiffuse ones of ERCS r e sqrt(l).
  filter.diffuse_relative_ercs_per_sqrt_m = 0.1;
  compute_ideal_targets(kFov, SensorKinematics{}, w.objects, w.states, w.visited, diffuse, filter);
  IdealTargets specular;
  int pieces = 0;
  for (const auto& t : diffuse) {
    if (t.kind != ReflectorKind::PlaneDiffuse) {
      specular.push_back(t);
      continue;
    }
    ++pieces;
    const double e = w.objects[static_cast<std::size_t>(t.object_index)].model.planes[static_cast<std::size_t>(t.reflector_index)].ercs;
    EXPECT_GT(t.ercs, 0.0);
    EXPECT_LE(t.ercs, 0.1 * e * std::sqrt(3.4) + 1e-12);  // the longest chord: the car's side, 3.4 m
  }
  EXPECT_GT(pieces, 0);
  ASSERT_EQ(specular.size(), before.size());
  for (std::size_t i = 0; i < before.size(); ++i) EXPECT_TRUE(same(specular[i], before[i])) << i;
}

}  // namespace
}  // namespace rcsim
