#pragma once
// The one place where angles are wrapped (STYLE.md: Stone Soup's Bearing).
#include <cmath>
#include <numbers>

namespace rcsim {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

inline constexpr double deg_to_rad(double angle_deg) { return angle_deg * kPi / 180.0; }
inline constexpr double rad_to_deg(double angle_rad) { return angle_rad * 180.0 / kPi; }

// Wraps an angle to [-pi, pi].
inline double wrap_angle_rad(double angle_rad) { return std::remainder(angle_rad, kTwoPi); }

// Signed difference a - b, wrapped to [-pi, pi]: use for innovations and residuals.
inline double angle_difference_rad(double a_rad, double b_rad) { return wrap_angle_rad(a_rad - b_rad); }

// Weighted mean of two angles through unit vectors.
inline double angle_mean_rad(double a_rad, double b_rad, double weight_b = 0.5) {
  const double c = (1.0 - weight_b) * std::cos(a_rad) + weight_b * std::cos(b_rad);
  const double s = (1.0 - weight_b) * std::sin(a_rad) + weight_b * std::sin(b_rad);
  return std::atan2(s, c);
}

}  // namespace rcsim
