#include "model/object_model.hpp"

#include <fmt/format.h>

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
  Vec2 normal(chord.y(), -chord.x());
  if (normal.norm() > 0.0) normal.normalize();
  // The arc bulges away from the object origin.
  if (normal.dot(0.5 * (from_O + to_O)) < 0.0) normal = -normal;
  return plane_from_chord_facing(std::move(name), from_O, to_O, sagitta_m, ercs, normal);
}

PlaneReflector plane_from_chord_facing(std::string name, const Vec2& from_O, const Vec2& to_O, double sagitta_m,
                                       double ercs, const Vec2& normal) {
  const Vec2 chord = to_O - from_O;
  const double half_chord_m = 0.5 * chord.norm();
  if (!(half_chord_m > 0.0)) throw std::invalid_argument("plane reflector chord has zero length");
  if (!(sagitta_m > 0.0) || sagitta_m > half_chord_m) {
    throw std::invalid_argument("plane reflector sagitta must be in (0, half the chord]");
  }
  const Vec2 mid = 0.5 * (from_O + to_O);
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
    out.planes[i].z_m = plane.z_m;  // heights do not scale: a recording's boxes give length and width only
  }
  return out;
}

ObjectModel expand_polyline(const ObjectModel& polyline_model, const std::vector<Vec2>& vertices_O) {
  if (!polyline_model.polyline) throw std::invalid_argument("model \"" + polyline_model.name + "\" is no polyline model");
  if (vertices_O.size() < 2) throw std::invalid_argument("a polyline needs at least two points");
  const PolylineTemplate& t = *polyline_model.polyline;
  ObjectModel out;
  out.name = polyline_model.name;
  out.description = polyline_model.description;
  out.length_m = out.width_m = 1e-3;
  out.height_m = 2.0 * t.z_m;
  out.polyline_points = vertices_O.size();
  // A face this flat: 1 cm over a piece of up to spacing_m (a flat face's specular return
  // comes only from near its normal).
  constexpr double kFaceSagittaM = 0.01;
  double next_post_m = 0.0, walked_m = 0.0;
  for (std::size_t k = 0; k + 1 < vertices_O.size(); ++k) {
    const Vec2 a = vertices_O[k], b = vertices_O[k + 1];
    const double length_m = (b - a).norm();
    if (!(length_m > 0.0)) throw std::invalid_argument(fmt::format("polyline points {} and {} coincide", k, k + 1));
    const Vec2 along = (b - a) / length_m;
    const Vec2 left(-along.y(), along.x());
    const double left_rad = std::atan2(left.y(), left.x());
    for (; t.post_ercs > 0.0 && next_post_m <= walked_m + length_m; next_post_m += t.spacing_m) {
      PointReflector post;
      post.name = fmt::format("post_{}", out.points.size());
      post.p_OR_O = a + (next_post_m - walked_m) * along;
      post.ercs_max = t.post_ercs;
      post.z_m = t.z_m;
      post.visibility = VisibilityFunction(left_rad + t.post_visibility.center_rad(), t.post_visibility.full_halfwidth_rad(),
                                           t.post_visibility.falloff_rad());
      out.points.push_back(std::move(post));
    }
    walked_m += length_m;
    const int pieces = static_cast<int>(std::ceil(length_m / t.spacing_m - 1e-9));
    for (int p = 0; t.face_ercs_per_m > 0.0 && p < pieces; ++p) {
      const Vec2 from = a + (length_m * p / pieces) * along, to = a + (length_m * (p + 1) / pieces) * along;
      const double piece_m = length_m / pieces;
      out.planes.push_back(plane_from_chord_facing(fmt::format("face_{}", out.planes.size()), from, to,
                                                   std::min(kFaceSagittaM, 0.5 * piece_m), t.face_ercs_per_m * piece_m, left));
      out.planes.back().z_m = t.z_m;
    }
  }
  return out;
}

}  // namespace rcsim
