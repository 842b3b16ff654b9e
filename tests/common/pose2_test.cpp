// The planar kinematics helpers of common/pose2.hpp, each formula once: by hand.
#include "common/pose2.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angles.hpp"

namespace rcsim {
namespace {

TEST(Pose2, PolarToCartesianByHand) {
  // 10 m at 30 deg: (10 cos 30, 10 sin 30) = (8.660254, 5).
  const Vec2 p = point_from_polar(10.0, deg_to_rad(30.0));
  EXPECT_NEAR(p.x(), 8.660254037844386, 1e-12);
  EXPECT_NEAR(p.y(), 5.0, 1e-12);
  EXPECT_NEAR(point_from_polar(2.0, -kPi / 2.0).y(), -2.0, 1e-12);
}

TEST(Pose2, TheSpeedAlongTheHeadingIsSigned) {
  // Driving east at 3 m/s, heading east: +3; the same velocity heading west (reversing): -3;
  // heading north-east: 3 cos 45 deg.
  EXPECT_DOUBLE_EQ(speed_along_heading_mps(Vec2(3.0, 0.0), 0.0), 3.0);
  EXPECT_NEAR(speed_along_heading_mps(Vec2(3.0, 0.0), kPi), -3.0, 1e-12);
  EXPECT_NEAR(speed_along_heading_mps(Vec2(3.0, 0.0), kPi / 4.0), 3.0 * std::sqrt(0.5), 1e-12);
  BodyState reversing;
  reversing.X_WB = {5.0, 1.0, kPi / 2.0};
  reversing.v_WB_W = Vec2(0.0, -2.0);
  EXPECT_NEAR(reversing.heading_speed_mps(), -2.0, 1e-12);
}

}  // namespace
}  // namespace rcsim
