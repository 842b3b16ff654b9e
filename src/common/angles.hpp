#pragma once
// The one place where angles are wrapped (STYLE.md: Stone Soup's Bearing).
#include <cmath>
#include <numbers>

namespace rcsim {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

inline constexpr double deg_to_rad(double angle_deg) { return angle_deg * kPi / 180.0; }
inline constexpr double rad_to_deg(double angle_rad) { return angle_rad * 180.0 / kPi; }

// Wraps an angle to [-pi, pi]. std::remainder returns an angle already in [-pi, pi] unchanged
// (at +-pi the quotient 1/2 rounds to the even 0), so those skip the slow library call.
inline double wrap_angle_rad(double angle_rad) {
  if (std::abs(angle_rad) <= kPi) return angle_rad;
  return std::remainder(angle_rad, kTwoPi);
}

// The angle of the unit vector (cos a, sin a) in [-pi, pi], as atan2(sin a, cos a) to within an
// ulp or two: asin or acos on whichever is well conditioned (derivative at most sqrt 2), each
// about half the cost of glibc's atan2. The input must be a unit vector up to rounding.
inline double angle_of_unit_vector_rad(double cos_a, double sin_a) {
  if (std::abs(sin_a) <= std::abs(cos_a)) {
    const double a = std::asin(sin_a);  // within 45 deg of the x axis or of its opposite
    return cos_a > 0.0 ? a : std::copysign(kPi, sin_a) - a;
  }
  return std::copysign(std::acos(cos_a), sin_a);
}

// Signed difference a - b, wrapped to [-pi, pi]: use for innovations and residuals.
inline double angle_difference_rad(double a_rad, double b_rad) { return wrap_angle_rad(a_rad - b_rad); }

// Weighted mean of two angles through unit vectors.
inline double angle_mean_rad(double a_rad, double b_rad, double weight_b = 0.5) {
  const double c = (1.0 - weight_b) * std::cos(a_rad) + weight_b * std::cos(b_rad);
  const double s = (1.0 - weight_b) * std::sin(a_rad) + weight_b * std::sin(b_rad);
  return std::atan2(s, c);
}

}  // namespace rcsim
