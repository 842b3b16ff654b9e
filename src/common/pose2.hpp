#pragma once
// Planar poses and rigid-body kinematics. Notation (Drake monogram): p_AB_C is the position
// from A to B expressed in frame C; X_AB is the pose of frame B in frame A; v_WB_W the
// velocity of B's origin in the world, expressed in the world.
#include <Eigen/Core>
#include <cmath>

namespace rcsim {

using Vec2 = Eigen::Vector2d;

struct Pose2 {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;

  Vec2 translation() const { return {x_m, y_m}; }
};

// Rotates v by yaw (counter-clockwise).
inline Vec2 rotate(double yaw_rad, const Vec2& v) {
  const double c = std::cos(yaw_rad);
  const double s = std::sin(yaw_rad);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

// p_AP_A from X_AB and p_BP_B.
inline Vec2 transform_point(const Pose2& X_AB, const Vec2& p_BP_B) {
  return X_AB.translation() + rotate(X_AB.yaw_rad, p_BP_B);
}

// p_BP_B from X_AB and p_AP_A.
inline Vec2 inverse_transform_point(const Pose2& X_AB, const Vec2& p_AP_A) {
  return rotate(-X_AB.yaw_rad, p_AP_A - X_AB.translation());
}

// X_AC = X_AB * X_BC.
inline Pose2 compose(const Pose2& X_AB, const Pose2& X_BC) {
  const Vec2 p = transform_point(X_AB, X_BC.translation());
  return {p.x(), p.y(), X_AB.yaw_rad + X_BC.yaw_rad};
}

// X_BA from X_AB.
inline Pose2 inverse(const Pose2& X_AB) {
  const Vec2 p = rotate(-X_AB.yaw_rad, -X_AB.translation());
  return {p.x(), p.y(), -X_AB.yaw_rad};
}

// The unit vector of a heading: (cos yaw, sin yaw).
inline Vec2 heading_vector(double yaw_rad) { return {std::cos(yaw_rad), std::sin(yaw_rad)}; }

// The signed speed along a heading: a velocity's component along it (negative when reversing).
// The one formula of every "speed_mps" a recording holds (ego.csv, objects.csv).
inline double speed_along_heading_mps(const Vec2& v, double yaw_rad) { return v.dot(heading_vector(yaw_rad)); }

// Polar to Cartesian: the point at range_m and azimuth_rad (counter-clockwise from the x axis).
inline Vec2 point_from_polar(double range_m, double azimuth_rad) { return range_m * heading_vector(azimuth_rad); }

// Planar cross product a x b (the z component): positive when b lies counter-clockwise of a,
// within a half turn.
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Planar cross product of a scalar angular rate with a vector: omega x r.
inline Vec2 cross_rate(double rate_radps, const Vec2& r) { return {-rate_radps * r.y(), rate_radps * r.x()}; }

// The motion of a rigid body B in the world W at one instant.
struct BodyState {
  Pose2 X_WB;
  Vec2 v_WB_W = Vec2::Zero();
  double yaw_rate_radps = 0.0;

  // Its signed speed along its heading (ego.csv's and objects.csv's speed_mps).
  double heading_speed_mps() const { return speed_along_heading_mps(v_WB_W, X_WB.yaw_rad); }

  // Velocity of a point P fixed on the body, from its world position.
  Vec2 point_velocity_W(const Vec2& p_WP_W) const {
    return v_WB_W + cross_rate(yaw_rate_radps, p_WP_W - X_WB.translation());
  }
};

}  // namespace rcsim
