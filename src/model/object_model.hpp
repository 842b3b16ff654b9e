#pragma once
// Reflection-center object models (paper section II): point reflection centers with a continuous
// visibility function of the impinging angle, and plane reflectors (circle sectors).
#include <string>
#include <vector>

#include "common/pose2.hpp"

namespace rcsim {

// Continuous visibility of a point reflection center over the impinging angle alpha, measured in
// the object frame from the object's longitudinal axis to the direction reflector -> sensor
// (paper II-B, Fig. 6): 1 within full_halfwidth of the centre direction, a raised-cosine fall to 0
// over falloff beyond that, 0 elsewhere.
class VisibilityFunction {
 public:
  VisibilityFunction() : VisibilityFunction(0.0, 0.0, 0.0) {}
  VisibilityFunction(double center_rad, double full_halfwidth_rad, double falloff_rad);

  double center_rad() const { return center_rad_; }
  double full_halfwidth_rad() const { return full_halfwidth_rad_; }
  double falloff_rad() const { return falloff_rad_; }

  double operator()(double alpha_rad) const;
  // The same for the unit direction (ux, uy) in the object frame; trigonometry only in the fall-off.
  double from_unit_direction(double ux, double uy) const;

 private:
  double center_rad_, full_halfwidth_rad_, falloff_rad_;
  double cos_center_, sin_center_;
  double cos_full_edge_, cos_zero_edge_;  // cos of the angles where it leaves 1 and reaches 0
  bool everywhere_, nowhere_beyond_;
};

struct PointReflector {
  std::string name;
  Vec2 p_OR_O = Vec2::Zero();  // position in the object frame
  double ercs_max = 1.0;        // ERCS where the visibility function is 1 (paper II-C)
  VisibilityFunction visibility;

  // ERCS as the scaled visibility function (paper II-C).
  double ercs(double alpha_rad) const { return ercs_max * visibility(alpha_rad); }
};

// A plane reflector: the arc of a circle (seen in 3-D, part of a vertical cylinder surface), with
// constant ERCS (paper II-A, II-C). The arc runs counter-clockwise from start_rad over span_rad.
struct PlaneReflector {
  std::string name;
  Vec2 center_O = Vec2::Zero();
  double radius_m = 1.0;
  double start_rad = 0.0;
  double span_rad = 0.0;
  double ercs = 1.0;

  Vec2 arc_point_O(double angle_rad) const;
  // Is the direction (from the circle centre, in the object frame) inside the sector?
  bool covers_direction(double angle_rad) const;
};

struct ObjectModel {
  std::string name;
  std::string description;
  double length_m = 0.0;
  double width_m = 0.0;
  std::vector<PointReflector> points;
  std::vector<PlaneReflector> planes;

  double max_ercs() const;
  std::size_t reflector_count() const { return points.size() + planes.size(); }
  // Radius of a circle about the object origin that contains every reflector.
  double bounding_radius_m() const;
};

// A plane reflector from the chord of its arc and the sagitta (how far the arc bulges outward,
// away from the object origin): the form used in the model files.
PlaneReflector plane_from_chord(std::string name, const Vec2& from_O, const Vec2& to_O, double sagitta_m,
                                double ercs);

// The model stretched to another length and width: reflector positions scale with the box;
// plane reflectors keep passing through their scaled chord ends and apex.
ObjectModel scale_model(const ObjectModel& model, double length_m, double width_m);

}  // namespace rcsim
