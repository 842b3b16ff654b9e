#include "common/angles.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "common/rng.hpp"

namespace rcsim {
namespace {

// The fast path for angles already in [-pi, pi] must return exactly what std::remainder does.
void expect_same_as_remainder(double angle_rad) {
  const double expected = std::remainder(angle_rad, kTwoPi);
  const double wrapped = wrap_angle_rad(angle_rad);
  if (std::isnan(expected)) {
    EXPECT_TRUE(std::isnan(wrapped)) << angle_rad;
  } else {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(wrapped), std::bit_cast<std::uint64_t>(expected)) << angle_rad;
  }
}

TEST(Angles, WrapIsBitIdenticalToRemainder) {
  const double inf = std::numeric_limits<double>::infinity();
  for (const double a : {0.0, -0.0, kPi, -kPi, std::nextafter(kPi, inf), std::nextafter(-kPi, -inf),
                         std::nextafter(kPi, 0.0), 3 * kPi, -3 * kPi, kTwoPi, -kTwoPi, 1e6, -1e-300,
                         std::numeric_limits<double>::denorm_min(), inf, -inf,
                         std::numeric_limits<double>::quiet_NaN()}) {
    expect_same_as_remainder(a);
  }
  Rng rng(3, 0);
  for (int i = 0; i < 100000; ++i) expect_same_as_remainder(rng.uniform(-4.0 * kPi, 4.0 * kPi));
}

TEST(Angles, AngleOfUnitVectorAgreesWithAtan2) {
  // On the branch points of the helper (multiples of 45 deg), on the axes and at +-pi, then at
  // random: within two ulp of pi of atan2 (asin and acos are used only where well conditioned).
  const double tolerance_rad = 2.0 * std::numeric_limits<double>::epsilon() * kPi;
  const auto check = [&](double angle_rad) {
    const double c = std::cos(angle_rad), s = std::sin(angle_rad);
    EXPECT_NEAR(angle_of_unit_vector_rad(c, s), std::atan2(s, c), tolerance_rad) << angle_rad;
  };
  for (int k = -8; k <= 8; ++k) {
    const double a = k * 0.25 * kPi;
    for (const double eps : {-1e-12, 0.0, 1e-12}) check(a + eps);
  }
  EXPECT_EQ(angle_of_unit_vector_rad(-1.0, 0.0), kPi);    // atan2(+0, -1)
  EXPECT_EQ(angle_of_unit_vector_rad(-1.0, -0.0), -kPi);  // atan2(-0, -1)
  EXPECT_EQ(angle_of_unit_vector_rad(1.0, 0.0), 0.0);
  EXPECT_EQ(angle_of_unit_vector_rad(0.0, 1.0), 0.5 * kPi);
  Rng rng(4, 0);
  for (int i = 0; i < 100000; ++i) check(rng.uniform(-kPi, kPi));
  // A unit vector only up to rounding, as from x / r and y / r.
  for (int i = 0; i < 10000; ++i) {
    const double x = rng.uniform(-50.0, 50.0), y = rng.uniform(-50.0, 50.0);
    const double r = std::hypot(x, y);
    EXPECT_NEAR(angle_of_unit_vector_rad(x / r, y / r), std::atan2(y, x), tolerance_rad) << x << " " << y;
  }
}

TEST(Angles, WrapByHand) {
  EXPECT_DOUBLE_EQ(wrap_angle_rad(1.5 * kPi), -0.5 * kPi);
  EXPECT_DOUBLE_EQ(wrap_angle_rad(-1.5 * kPi), 0.5 * kPi);
  EXPECT_NEAR(angle_difference_rad(deg_to_rad(170), deg_to_rad(-170)), deg_to_rad(-20), 1e-15);
}

}  // namespace
}  // namespace rcsim
