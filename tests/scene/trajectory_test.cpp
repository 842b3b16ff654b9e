#include "scene/trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angles.hpp"
#include "common/rng.hpp"
#include "test_support.hpp"

namespace rcsim {
namespace {

using testing::sample;

TEST(Trajectory, PassesThroughSamplesWithTheirVelocities) {
  const Trajectory t({sample(0, 20, -3, kPi, 5), sample(5, 0, -3, kPi, 3)});
  const auto a = t.state_at(0.0);
  EXPECT_NEAR(a.X_WB.x_m, 20.0, 1e-12);
  EXPECT_NEAR(a.v_WB_W.x(), -5.0, 1e-12);
  const auto b = t.state_at(5.0);
  EXPECT_NEAR(b.X_WB.x_m, 0.0, 1e-12);
  EXPECT_NEAR(b.v_WB_W.x(), -3.0, 1e-12);
  EXPECT_NEAR(std::abs(b.X_WB.yaw_rad), kPi, 1e-12);
}

TEST(Trajectory, VelocityAndYawRateAreDerivativesOfTheMotion) {
  const Trajectory t({sample(0, 0, 0, 0, 10), sample(2, 19, 3, 0.4, 9), sample(4, 36, 10, 0.5, 8)});
  for (double s = 0.1; s < 3.9; s += 0.37) {
    const double h = 1e-5;
    const auto m = t.state_at(s - h), p = t.state_at(s + h), c = t.state_at(s);
    EXPECT_NEAR(c.v_WB_W.x(), (p.X_WB.x_m - m.X_WB.x_m) / (2 * h), 1e-5);
    EXPECT_NEAR(c.v_WB_W.y(), (p.X_WB.y_m - m.X_WB.y_m) / (2 * h), 1e-5);
    EXPECT_NEAR(c.yaw_rate_radps, angle_difference_rad(p.X_WB.yaw_rad, m.X_WB.yaw_rad) / (2 * h), 1e-5);
  }
}

TEST(Trajectory, YawIsUnwrappedAcrossPi) {
  const Trajectory t({sample(0, 0, 0, 3.1, 0), sample(1, 0, 0, -3.1, 0)});
  // The short way round: through pi, not through 0.
  EXPECT_GT(std::abs(t.state_at(0.5).X_WB.yaw_rad), 3.1);
}

TEST(Trajectory, OneSampleMovesOnAtConstantSpeedAndTurnRate) {
  auto s = sample(0, 0, 0, 0, 10);
  s.yaw_rate_radps = 0.5;
  const Trajectory t({s});
  // Circle of radius 20 m: after a quarter turn (pi s) at (20, 20).
  const auto q = t.state_at(kPi);
  EXPECT_NEAR(q.X_WB.x_m, 20.0, 1e-9);
  EXPECT_NEAR(q.X_WB.y_m, 20.0, 1e-9);
  EXPECT_NEAR(q.v_WB_W.x(), 0.0, 1e-9);
  EXPECT_NEAR(q.v_WB_W.y(), 10.0, 1e-9);
  // Before the first sample the same motion runs backwards.
  EXPECT_NEAR(t.state_at(-kPi).X_WB.x_m, -20.0, 1e-9);
}

TEST(Trajectory, ExtrapolatesAfterTheLastSample) {
  const Trajectory t({sample(0, 0, 0, 0, 2), sample(1, 2, 0, 0, 2)});
  EXPECT_NEAR(t.state_at(11.0).X_WB.x_m, 22.0, 1e-9);
  EXPECT_NEAR(t.state_at(-1.0).X_WB.x_m, -2.0, 1e-9);
}

TEST(Trajectory, ParkedObjectStaysPut) {
  const Trajectory t({sample(0, 5, 6, 1.0, 0)});
  const auto s = t.state_at(1e5);
  EXPECT_DOUBLE_EQ(s.X_WB.x_m, 5.0);
  EXPECT_DOUBLE_EQ(s.X_WB.y_m, 6.0);
  EXPECT_DOUBLE_EQ(s.v_WB_W.norm(), 0.0);
}

// position_bounds by hand: a straight segment's Bezier hull and a lone node's reach.
TEST(Trajectory, PositionBoundsByHand) {
  // 0 -> 10 m along x in 1 s at 10 m/s: control points x = 0, 10/3, 20/3, 10 on y = 0, the
  // uniform motion x = 10 t, so the piece over [0.25, 0.5] s spans exactly 2.5 .. 5 m.
  const Trajectory line({sample(0, 0, 0, 0, 10), sample(1, 10, 0, 0, 10)});
  const auto box = line.position_bounds(0.25, 0.5);
  EXPECT_NEAR(box.min().x(), 2.5, 1e-12);
  EXPECT_NEAR(box.max().x(), 5.0, 1e-12);
  EXPECT_DOUBLE_EQ(box.min().y(), 0.0);
  EXPECT_DOUBLE_EQ(box.max().y(), 0.0);
  // After the last node: within 10 m/s * 2 s of (10, 0).
  const auto after = line.position_bounds(2.0, 3.0);
  EXPECT_DOUBLE_EQ(after.min().x(), -10.0);
  EXPECT_DOUBLE_EQ(after.max().x(), 30.0);
  EXPECT_DOUBLE_EQ(after.max().y(), 20.0);
  // An instant: exactly at the last node (no segment holds it alone) and at the first.
  for (const double t_s : {line.end_s(), line.start_s()}) {
    const auto at = line.position_bounds(t_s, t_s);
    ASSERT_FALSE(at.isEmpty());
    EXPECT_EQ(at.squaredExteriorDistance(line.state_at(t_s).X_WB.translation()), 0.0);
  }
  // A lone node at (5, -1), 2 m/s: over [1, 3] s within 2 * 3 = 6 m.
  const Trajectory lone({sample(0, 5, -1, 0.3, 2)});
  const auto l = lone.position_bounds(1.0, 3.0);
  EXPECT_DOUBLE_EQ(l.min().x(), -1.0);
  EXPECT_DOUBLE_EQ(l.max().x(), 11.0);
  EXPECT_DOUBLE_EQ(l.min().y(), -7.0);
  EXPECT_DOUBLE_EQ(l.max().y(), 5.0);
}

// Property: on random trajectories (turns, reversing yaw, stops) and random intervals, before,
// across and after the samples, every evaluated position lies in the box.
TEST(Trajectory, PositionBoundsHoldEveryEvaluatedPosition) {
  Rng rng(17);
  int checked = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<TrajectorySample> samples;
    double t_s = rng.uniform(-5.0, 5.0), x_m = rng.uniform(-1e6, 1e6), y_m = rng.uniform(-100.0, 100.0);
    const int n = 1 + static_cast<int>(rng.uniform(0.0, 6.0));
    for (int i = 0; i < n; ++i) {
      const double yaw_rad = rng.uniform(-kPi, kPi);
      const double speed_mps = rng.uniform01() < 0.2 ? 0.0 : rng.uniform(-5.0, 40.0);
      auto s = sample(t_s, x_m, y_m, yaw_rad, speed_mps);
      if (rng.uniform01() < 0.5) s.yaw_rate_radps = rng.uniform(-1.0, 1.0);
      samples.push_back(s);
      const double dt_s = rng.uniform(0.05, 3.0);
      t_s += dt_s;
      x_m += rng.uniform(-40.0, 40.0) * dt_s;
      y_m += rng.uniform(-40.0, 40.0) * dt_s;
    }
    const Trajectory trajectory(samples);
    for (int k = 0; k < 10; ++k) {
      const double t0_s = rng.uniform(samples.front().t_s - 3.0, t_s + 2.0);
      const double t1_s = t0_s + rng.uniform(0.0, 2.0);
      const auto box = trajectory.position_bounds(t0_s, t1_s);
      ASSERT_FALSE(box.isEmpty());
      for (int j = 0; j <= 40; ++j) {
        const Vec2 p = trajectory.state_at(t0_s + (t1_s - t0_s) * j / 40.0).X_WB.translation();
        const double tolerance_m = 1e-9 * (1.0 + p.cwiseAbs().maxCoeff());
        ASSERT_LE(box.squaredExteriorDistance(p), tolerance_m * tolerance_m) << "trial " << trial << " t " << t0_s;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 200 * 10 * 41);
}

}  // namespace
}  // namespace rcsim
