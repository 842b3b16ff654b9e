#pragma once
// Road geometry: a reference line (centre line) parametrised by arc length s, lanes at lateral
// offsets d from it (positive to the left). Vehicles move in road coordinates (s, d); this maps
// them to the world frame W.
#include <vector>

#include "common/pose2.hpp"

namespace rcsim::traffic {

struct CenterlinePoint {
  Vec2 p_WR_W = Vec2::Zero();
  double heading_rad = 0.0;
  double curvature_1pm = 0.0;  // d heading / d s, positive turning left
};

class Centerline {
 public:
  // A straight line from origin along heading.
  static Centerline straight(const Vec2& origin_W, double heading_rad, double length_m);
  // A gently winding road starting at the origin along +x: curvature
  // kappa(s) = sin(2 pi s / wavelength) / min_radius, so that no bend is tighter than min_radius.
  static Centerline winding(double length_m, double min_radius_m, double wavelength_m);
  // A closed circle of the given circumference around the origin, driven counter-clockwise,
  // starting at (0, -R) along +x.
  static Centerline circle(double circumference_m);

  CenterlinePoint at(double s_m) const;
  double length_m() const { return length_m_; }
  bool closed() const { return kind_ == Kind::Circle; }

 private:
  enum class Kind { Straight, Winding, Circle };
  Kind kind_ = Kind::Straight;
  double length_m_ = 0.0;
  Vec2 origin_W_ = Vec2::Zero();
  double heading_rad_ = 0.0;
  double radius_m_ = 0.0;      // circle radius or winding minimum radius
  double wavelength_m_ = 0.0;  // winding
  double table_step_m_ = 1.0;
  std::vector<Vec2> table_W_;  // winding: integrated positions every table_step_m_
};

struct Road {
  Centerline line;
  int lane_count = 1;
  double lane_width_m = 3.5;
  // Lane 0 is the rightmost; lanes are centred on the reference line.
  double lane_offset_m(int lane) const { return (lane - 0.5 * (lane_count - 1)) * lane_width_m; }
};

// The world motion of a vehicle at road position s, lateral offset d, with lateral slope
// dd/ds = slope and its derivative d2d/ds2 = slope_rate_1pm, moving at ds/dt = speed_along_mps.
struct WorldMotion {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;
  double speed_mps = 0.0;
  double yaw_rate_radps = 0.0;
};
WorldMotion world_motion(const Centerline& line, double s_m, double d_m, double slope, double slope_rate_1pm,
                         double speed_along_mps);

}  // namespace rcsim::traffic
