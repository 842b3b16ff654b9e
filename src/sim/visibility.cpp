#include "sim/visibility.hpp"

#include <cmath>

namespace rcsim {

std::optional<Vec2> plane_reflection_point_O(const PlaneReflector& plane, const Vec2& p_OS_O) {
  const Vec2 p_CS_O = p_OS_O - plane.center_O;
  const double distance2_m2 = p_CS_O.squaredNorm();
  // Inside or on the circle: no outer reflection. The square root only for a hit.
  if (!(distance2_m2 > plane.radius_m * plane.radius_m)) return std::nullopt;
  if (!plane.covers_direction(p_CS_O)) return std::nullopt;
  return plane.center_O + (plane.radius_m / std::sqrt(distance2_m2)) * p_CS_O;
}

}  // namespace rcsim
