// Target classes (metrics/target_class.hpp), by hand from Kellner et al. 2013, eq. (2): a
// stationary point at azimuth theta shows a sensor moving with v_S the range rate
// -(v_x cos theta + v_y sin theta).
#include "metrics/target_class.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rcsim::metrics {
namespace {

constexpr double kGate_mps = 0.5;

TEST(TargetClass, StationaryRangeRateIsMinusTheSensorVelocityOnTheLineOfSight) {
  EXPECT_DOUBLE_EQ(stationary_range_rate_mps({30.0, 0.0}, 0.0), -30.0);        // dead ahead: approaching at ego speed
  EXPECT_NEAR(stationary_range_rate_mps({30.0, 0.0}, M_PI / 3.0), -15.0, 1e-12);  // cos 60 deg = 1/2
  EXPECT_NEAR(stationary_range_rate_mps({-30.0, 0.0}, 0.0), 30.0, 1e-12);       // a rear radar: receding
  EXPECT_NEAR(stationary_range_rate_mps({0.0, 2.0}, M_PI / 2.0), -2.0, 1e-12);  // sideways motion
}

TEST(TargetClass, BackgroundWithinTheGateOtherBeyondObjectFirst) {
  const Vec2 v_S(30.0, 0.0);
  // At 60 deg a stationary point shows -15 m/s: 0.4 m/s off is background, 0.6 m/s off other.
  EXPECT_EQ(classify_target(-1, -15.4, M_PI / 3.0, v_S, kGate_mps), TargetClass::stationary_background);
  EXPECT_EQ(classify_target(-1, -14.6, M_PI / 3.0, v_S, kGate_mps), TargetClass::stationary_background);
  EXPECT_EQ(classify_target(-1, -15.6, M_PI / 3.0, v_S, kGate_mps), TargetClass::other);
  EXPECT_EQ(classify_target(-1, -14.4, M_PI / 3.0, v_S, kGate_mps), TargetClass::other);
  // A car ahead driving at the ego's speed: range rate 0, far from -30: other unless on a box.
  EXPECT_EQ(classify_target(-1, 0.0, 0.0, v_S, kGate_mps), TargetClass::other);
  // On a box it is the object's, whatever its speed (a parked car is an object, not background).
  EXPECT_EQ(classify_target(3, -30.0, 0.0, v_S, kGate_mps), TargetClass::object);
  EXPECT_EQ(classify_target(0, 5.0, 0.0, v_S, kGate_mps), TargetClass::object);
}

TEST(TargetClass, NamesAreThoseStoredInTheReport) {
  EXPECT_EQ(target_class_name(TargetClass::object), "object");
  EXPECT_EQ(target_class_name(TargetClass::stationary_background), "background");
  EXPECT_EQ(target_class_name(TargetClass::other), "other");
}

}  // namespace
}  // namespace rcsim::metrics
