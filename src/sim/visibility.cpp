#include "sim/visibility.hpp"

#include <cmath>

namespace rcsim {

double point_reflector_ercs(const PointReflector& point, const Vec2& p_OS_O) {
  const Vec2 p_RS_O = p_OS_O - point.p_OR_O;  // reflector -> sensor
  const double norm = p_RS_O.norm();
  if (!(norm > 0.0)) return 0.0;  // sensor on the reflector: no defined impinging angle
  return point.ercs_max * point.visibility.from_unit_direction(p_RS_O.x() / norm, p_RS_O.y() / norm);
}

std::optional<Vec2> plane_reflection_point_O(const PlaneReflector& plane, const Vec2& p_OS_O) {
  const Vec2 p_CS_O = p_OS_O - plane.center_O;
  const double distance_m = p_CS_O.norm();
  if (!(distance_m > plane.radius_m)) return std::nullopt;  // inside or on the circle: no outer reflection
  const double direction_rad = std::atan2(p_CS_O.y(), p_CS_O.x());
  if (!plane.covers_direction(direction_rad)) return std::nullopt;
  return plane.center_O + (plane.radius_m / distance_m) * p_CS_O;
}

}  // namespace rcsim
