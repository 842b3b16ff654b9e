#pragma once
// Visibility check of reflection centers (paper II-B, Fig. 7).
#include <optional>

#include "model/object_model.hpp"

namespace rcsim {

// ERCS of a point reflection center seen from a sensor at p_OS_O (object frame): the scaled
// visibility function of the impinging angle (paper II-C); 0 means invisible. Inline: the sensor
// cycle asks it of every point reflector in range.
inline double point_reflector_ercs(const PointReflector& point, const Vec2& p_OS_O) {
  const Vec2 p_RS_O = p_OS_O - point.p_OR_O;  // reflector -> sensor (none if on the reflector)
  return point.ercs_max * point.visibility.from_direction(p_RS_O.x(), p_RS_O.y());
}

// The reflection point of a plane reflector: where the line from the sensor to the circle centre
// meets the arc; none if that line misses the sector or the sensor is inside the circle (Fig. 7).
std::optional<Vec2> plane_reflection_point_O(const PlaneReflector& plane, const Vec2& p_OS_O);

}  // namespace rcsim
