#include "scene/trajectory.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angles.hpp"
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

}  // namespace
}  // namespace rcsim
