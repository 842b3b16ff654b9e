#include "traffic/road.hpp"

#include <algorithm>
#include <cmath>

#include "common/angles.hpp"

namespace rcsim::traffic {
namespace {

double winding_heading_rad(double s_m, double min_radius_m, double wavelength_m) {
  // heading = integral of kappa = wavelength / (2 pi R) (1 - cos(2 pi s / wavelength))
  return wavelength_m / (kTwoPi * min_radius_m) * (1.0 - std::cos(kTwoPi * s_m / wavelength_m));
}

}  // namespace

Centerline Centerline::straight(const Vec2& origin_W, double heading_rad, double length_m) {
  Centerline c;
  c.kind_ = Kind::Straight;
  c.origin_W_ = origin_W;
  c.heading_rad_ = heading_rad;
  c.length_m_ = length_m;
  return c;
}

Centerline Centerline::winding(double length_m, double min_radius_m, double wavelength_m) {
  Centerline c;
  c.kind_ = Kind::Winding;
  c.length_m_ = length_m;
  c.radius_m_ = min_radius_m;
  c.wavelength_m_ = wavelength_m;
  // Positions by the midpoint rule on the exact heading; 1 m steps (chord error < 1 mm).
  const auto n = static_cast<std::size_t>(std::ceil(length_m / c.table_step_m_)) + 2;
  c.table_W_.resize(n);
  c.table_W_[0] = Vec2::Zero();
  for (std::size_t i = 1; i < n; ++i) {
    const double mid_s_m = (static_cast<double>(i) - 0.5) * c.table_step_m_;
    const double h = winding_heading_rad(mid_s_m, min_radius_m, wavelength_m);
    c.table_W_[i] = c.table_W_[i - 1] + c.table_step_m_ * Vec2(std::cos(h), std::sin(h));
  }
  return c;
}

Centerline Centerline::circle(double circumference_m) {
  Centerline c;
  c.kind_ = Kind::Circle;
  c.length_m_ = circumference_m;
  c.radius_m_ = circumference_m / kTwoPi;
  return c;
}

CenterlinePoint Centerline::at(double s_m) const {
  CenterlinePoint pt;
  switch (kind_) {
    case Kind::Straight:
      pt.heading_rad = heading_rad_;
      pt.p_WR_W = origin_W_ + s_m * Vec2(std::cos(heading_rad_), std::sin(heading_rad_));
      break;
    case Kind::Circle: {
      const double angle_rad = s_m / radius_m_;
      pt.heading_rad = wrap_angle_rad(angle_rad);
      pt.curvature_1pm = 1.0 / radius_m_;
      pt.p_WR_W = Vec2(radius_m_ * std::sin(angle_rad), -radius_m_ * std::cos(angle_rad));
      break;
    }
    case Kind::Winding: {
      pt.heading_rad = winding_heading_rad(s_m, radius_m_, wavelength_m_);
      pt.curvature_1pm = std::sin(kTwoPi * s_m / wavelength_m_) / radius_m_;
      const double u = std::clamp(s_m / table_step_m_, 0.0, static_cast<double>(table_W_.size() - 2));
      const auto i = static_cast<std::size_t>(u);
      const double f = u - static_cast<double>(i);
      // Beyond the table (vehicles leaving the road) continue straight along the last heading.
      const double beyond_m = std::max(0.0, s_m - static_cast<double>(table_W_.size() - 2) * table_step_m_);
      pt.p_WR_W = (1.0 - f) * table_W_[i] + f * table_W_[i + 1] +
               beyond_m * Vec2(std::cos(pt.heading_rad), std::sin(pt.heading_rad));
      break;
    }
  }
  return pt;
}

WorldMotion world_motion(const Centerline& line, double s_m, double d_m, double slope, double slope_rate_1pm,
                         double speed_along_mps) {
  const CenterlinePoint c = line.at(s_m);
  const Vec2 normal_W(-std::sin(c.heading_rad), std::cos(c.heading_rad));
  const Vec2 p_WR_W = c.p_WR_W + d_m * normal_W;
  // Path of the vehicle in road coordinates: dp/ds = (1 - kappa d) t + (dd/ds) n, so its
  // direction is heading + atan2(dd/ds, 1 - kappa d), also when standing.
  const double h = 1.0 - c.curvature_1pm * d_m;
  const double rel_yaw_rad = std::atan2(slope, h);
  WorldMotion m;
  m.x_m = p_WR_W.x();
  m.y_m = p_WR_W.y();
  m.yaw_rad = wrap_angle_rad(c.heading_rad + rel_yaw_rad);
  m.speed_mps = speed_along_mps * std::hypot(h, slope);
  // d/dt [heading + atan(slope / h)] with d(slope)/dt = slope' v and dh/dt = -kappa slope v
  // (the curvature's own change along s is neglected: |kappa'| d is below 1e-6 here).
  const double dh_ds = -c.curvature_1pm * slope;
  const double drel_ds = (slope_rate_1pm * h - slope * dh_ds) / (h * h + slope * slope);
  m.yaw_rate_radps = speed_along_mps * (c.curvature_1pm + drel_ds);
  return m;
}

}  // namespace rcsim::traffic
