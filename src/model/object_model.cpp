#include "model/object_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/angles.hpp"

namespace rcsim {

VisibilityFunction::VisibilityFunction(double center_rad, double full_halfwidth_rad, double falloff_rad)
    : center_rad_(center_rad),
      full_halfwidth_rad_(full_halfwidth_rad),
      falloff_rad_(falloff_rad),
      cos_center_(std::cos(center_rad)),
      sin_center_(std::sin(center_rad)),
      cos_full_edge_(std::cos(full_halfwidth_rad)),
      cos_zero_edge_(std::cos(full_halfwidth_rad + falloff_rad)),
      everywhere_(full_halfwidth_rad >= kPi - 1e-12),
      nowhere_beyond_(full_halfwidth_rad + falloff_rad < kPi) {}

double VisibilityFunction::operator()(double alpha_rad) const {
  return from_direction(std::cos(alpha_rad), std::sin(alpha_rad));
}

double VisibilityFunction::falloff_value(double cos_delta, double sin_delta) const {
  const double delta_rad = std::abs(angle_of_unit_vector_rad(cos_delta, sin_delta));
  if (falloff_rad_ <= 0.0) return delta_rad <= full_halfwidth_rad_ ? 1.0 : 0.0;
  const double x = std::clamp((delta_rad - full_halfwidth_rad_) / falloff_rad_, 0.0, 1.0);
  return 0.5 * (1.0 + std::cos(kPi * x));  // raised-cosine fall-off
}

Vec2 PlaneReflector::arc_point_O(double angle_rad) const {
  return center_O + radius_m * Vec2(std::cos(angle_rad), std::sin(angle_rad));
}

void PlaneReflector::set_arc(double start_angle_rad, double span_angle_rad) {
  start_rad = start_angle_rad;
  span_rad = span_angle_rad;
  u_start_O = Vec2(std::cos(start_rad), std::sin(start_rad));
  u_end_O = Vec2(std::cos(start_rad + span_rad), std::sin(start_rad + span_rad));
}

bool PlaneReflector::covers_direction(double angle_rad) const {
  const double from_start_rad = angle_rad - start_rad;
  const double wrapped = from_start_rad - kTwoPi * std::floor(from_start_rad / kTwoPi);  // [0, 2pi)
  return wrapped <= span_rad;
}

double ObjectModel::max_ercs() const {
  double best = 0.0;
  for (const auto& p : points) best = std::max(best, p.ercs_max);
  for (const auto& p : planes) best = std::max(best, p.ercs);
  return best;
}

double ObjectModel::bounding_radius_m() const {
  double r = 0.5 * std::hypot(length_m, width_m);
  for (const auto& p : points) r = std::max(r, p.p_OR_O.norm());
  for (const auto& p : planes) {
    r = std::max({r, p.arc_point_O(p.start_rad).norm(), p.arc_point_O(p.start_rad + p.span_rad).norm(),
                  p.arc_point_O(p.start_rad + 0.5 * p.span_rad).norm()});
  }
  return r;
}

PlaneReflector plane_from_chord(std::string name, const Vec2& from_O, const Vec2& to_O, double sagitta_m,
                                double ercs) {
  const Vec2 chord = to_O - from_O;
  const double half_chord_m = 0.5 * chord.norm();
  if (!(half_chord_m > 0.0)) throw std::invalid_argument("plane reflector chord has zero length");
  if (!(sagitta_m > 0.0) || sagitta_m > half_chord_m) {
    throw std::invalid_argument("plane reflector sagitta must be in (0, half the chord]");
  }
  const Vec2 mid = 0.5 * (from_O + to_O);
  Vec2 normal(chord.y(), -chord.x());
  normal.normalize();
  // The arc bulges away from the object origin.
  if (normal.dot(mid) < 0.0) normal = -normal;
  const double radius_m = (half_chord_m * half_chord_m + sagitta_m * sagitta_m) / (2.0 * sagitta_m);
  PlaneReflector plane;
  plane.name = std::move(name);
  plane.center_O = mid - (radius_m - sagitta_m) * normal;
  plane.radius_m = radius_m;
  const double half_span_rad = std::asin(std::min(1.0, half_chord_m / radius_m));
  const double apex_rad = std::atan2(normal.y(), normal.x());
  // Half-chord at most the radius; for sagitta > radius (more than a half circle) widen the span.
  const double half_rad = sagitta_m > radius_m ? kPi - half_span_rad : half_span_rad;
  plane.set_arc(apex_rad - half_rad, 2.0 * half_rad);
  plane.ercs = ercs;
  return plane;
}

ObjectModel scale_model(const ObjectModel& model, double length_m, double width_m) {
  if (!(length_m > 0.0) || !(width_m > 0.0)) throw std::invalid_argument("scaled size must be positive");
  const double sx = length_m / model.length_m;
  const double sy = width_m / model.width_m;
  const auto scale = [&](const Vec2& p) { return Vec2(p.x() * sx, p.y() * sy); };
  ObjectModel out = model;
  out.length_m = length_m;
  out.width_m = width_m;
  for (auto& p : out.points) p.p_OR_O = scale(p.p_OR_O);
  for (std::size_t i = 0; i < model.planes.size(); ++i) {
    const auto& plane = model.planes[i];
    const Vec2 from = scale(plane.arc_point_O(plane.start_rad));
    const Vec2 to = scale(plane.arc_point_O(plane.start_rad + plane.span_rad));
    const Vec2 apex = scale(plane.arc_point_O(plane.start_rad + 0.5 * plane.span_rad));
    const Vec2 mid = 0.5 * (from + to);
    out.planes[i] = plane_from_chord(plane.name, from, to, std::max((apex - mid).norm(), 1e-9), plane.ercs);
  }
  return out;
}

}  // namespace rcsim
