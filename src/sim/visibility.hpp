#pragma once
// Visibility check of reflection centers (paper II-B, Fig. 7): which reflection points of one
// object a sensor sees, and where. The ideal target list (ideal_targets.cpp) visits every object
// through for_each_visible_reflector.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <utility>

#include "model/object_model.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {

// The reflection point of a plane reflector: where the line from the sensor to the circle centre
// meets the arc; none if that line misses the sector or the sensor is inside the circle (Fig. 7).
std::optional<Vec2> plane_reflection_point_O(const PlaneReflector& plane, const Vec2& p_OS_O);

// At most this many diffuse pieces per face and cycle by default (a face spanning more range cells
// is cut into this many longer pieces); a profile may allow more (extended_objects.max_pieces_per_face).
inline constexpr int kMaxDiffusePieces = 16;

// How a face is cut into diffuse pieces: about one range cell each and, for an array that resolves
// azimuth (piece_azimuth_rad > 0), about one beam each, at most max_pieces.
struct DiffusePieceSize {
  double piece_range_m = 1.0;
  double piece_azimuth_rad = 0.0;
  int max_pieces = kMaxDiffusePieces;
};

// The diffuse pieces of a face from a_O to b_O whose outside is towards outward_O, seen from
// p_OS_O (docs/extended-objects.md): the face cut into n equal pieces, n = its range extent seen
// from the sensor over the piece's range (and, where given, its angular extent over the piece's
// azimuth, whichever is more), rounded up, 1 to max_pieces, so that each piece spans about one
// cell. Calls visit(p_OT_O, piece_length_m) at each piece's centre. Nothing when the sensor is not
// in front of the face (on its inner side, or on its line).
template <typename Visit>
void for_each_face_piece(const Vec2& a_O, const Vec2& b_O, const Vec2& outward_O, const Vec2& p_OS_O,
                         const DiffusePieceSize& size, Visit&& visit) {
  const Vec2 mid_O = 0.5 * (a_O + b_O);
  if (!((p_OS_O - mid_O).dot(outward_O) > 0.0)) return;
  const Vec2 p_SA_O = a_O - p_OS_O, p_SB_O = b_O - p_OS_O;
  const double range_extent_m = std::abs(p_SA_O.norm() - p_SB_O.norm());
  double cells = range_extent_m / size.piece_range_m;
  if (size.piece_azimuth_rad > 0.0) {
    const double angle_extent_rad = std::abs(std::atan2(p_SA_O.x() * p_SB_O.y() - p_SA_O.y() * p_SB_O.x(), p_SA_O.dot(p_SB_O)));
    cells = std::max(cells, angle_extent_rad / size.piece_azimuth_rad);
  }
  const int n = std::clamp(static_cast<int>(std::ceil(cells)), 1, size.max_pieces);
  const double length_m = (b_O - a_O).norm() / n;
  for (int k = 0; k < n; ++k) visit(Vec2(a_O + ((k + 0.5) / n) * (b_O - a_O)), length_m);
}

// The diffuse pieces of a plane reflector's face: the chord between the arc's ends, its outside
// from the circle centre to the arc's middle (a half circle's chord passes through the centre, so
// the chord's middle would not do).
template <typename Visit>
void for_each_diffuse_piece(const PlaneReflector& plane, const Vec2& p_OS_O, const DiffusePieceSize& size, Visit&& visit) {
  const Vec2 a_O = plane.center_O + plane.radius_m * plane.u_start_O;
  const Vec2 b_O = plane.center_O + plane.radius_m * plane.u_end_O;
  const Vec2 outward_O = plane.arc_point_O(plane.start_rad + 0.5 * plane.span_rad) - plane.center_O;
  for_each_face_piece(a_O, b_O, outward_O, p_OS_O, size, std::forward<Visit>(visit));
}

// The four sides of an object's box (length along x, width along y, centred on the object's
// origin), in the order of kBoxSideNames: the surface whose diffuse pieces an imaging radar sees
// with extended_objects.diffuse_surface "box" (docs/extended-objects.md). The left and right sides
// lie side_inset_m inside the box (at least on the centre line): a car's body above the wheels is
// narrower than its box, and its roof, hood and boot project inside it.
inline constexpr const char* kBoxSideNames[4] = {"box_front", "box_rear", "box_left", "box_right"};
struct BoxSide {
  Vec2 a_O, b_O, outward_O;
};
// A model has box sides when it has a box and is not a polyline (a guard rail's "box" is its
// template's, not the rail's).
inline bool has_box_sides(const ObjectModel& model) {
  return model.length_m > 0.0 && model.width_m > 0.0 && model.polyline_points == 0 && !model.polyline;
}
inline std::array<BoxSide, 4> box_sides(double length_m, double width_m, double side_inset_m = 0.0) {
  const double x = 0.5 * length_m, y = 0.5 * width_m, y_side = std::max(y - side_inset_m, 0.0);
  return {BoxSide{Vec2(x, -y), Vec2(x, y), Vec2::UnitX()}, BoxSide{Vec2(-x, y), Vec2(-x, -y), -Vec2::UnitX()},
          BoxSide{Vec2(-x, y_side), Vec2(x, y_side), Vec2::UnitY()},
          BoxSide{Vec2(x, -y_side), Vec2(-x, -y_side), -Vec2::UnitY()}};
}

// One visible reflection point of an object, in the object frame.
struct VisibleReflector {
  Vec2 p_OT_O;
  double ercs = 0.0;       // ercs_max for a point (its visibility applied later if in fall-off), ERCS for a plane
  std::size_t index = 0;   // into model.points or model.planes
  ReflectorKind kind = ReflectorKind::Point;
  const PointReflector* point = nullptr;  // points only
  VisibilityFunction::Zone zone;          // points only: one, or falloff (visibility still to evaluate)
};

// Calls visit(const VisibleReflector&) for every point reflector whose visibility function is
// not zero seen from p_OS_O (the impinging direction reflector -> sensor, paper II-C) and, when
// `planes`, for every plane reflector with a reflection point; points first, in model order.
// Inline: the sensor cycle calls it for every object in range.
template <typename Visit>
void for_each_visible_reflector(const ObjectModel& model, const Vec2& p_OS_O, bool planes, Visit&& visit) {
  for (std::size_t k = 0; k < model.points.size(); ++k) {
    const PointReflector& point = model.points[k];
    const Vec2 p_RS_O = p_OS_O - point.p_OR_O;  // reflector -> sensor: the impinging direction
    const auto zone = point.visibility.zone(p_RS_O.x(), p_RS_O.y());
    if (zone.kind == VisibilityFunction::Zone::zero) continue;
    visit(VisibleReflector{point.p_OR_O, point.ercs_max, k, ReflectorKind::Point, &point, zone});
  }
  for (std::size_t k = 0; planes && k < model.planes.size(); ++k) {
    const auto p_OT_O = plane_reflection_point_O(model.planes[k], p_OS_O);
    if (p_OT_O) visit(VisibleReflector{*p_OT_O, model.planes[k].ercs, k, ReflectorKind::Plane, nullptr, {}});
  }
}

}  // namespace rcsim
