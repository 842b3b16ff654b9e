// Paper II-B, Fig. 6 and 7: visibility functions and plane reflection points.
#include "sim/visibility.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angles.hpp"

namespace rcsim {
namespace {

TEST(Visibility, FunctionIsOneThenRaisedCosineThenZero) {
  const VisibilityFunction v{deg_to_rad(45), deg_to_rad(25), deg_to_rad(40)};
  EXPECT_DOUBLE_EQ(v(deg_to_rad(45)), 1.0);
  EXPECT_DOUBLE_EQ(v(deg_to_rad(70)), 1.0);
  EXPECT_NEAR(v(deg_to_rad(90)), 0.5, 1e-12);  // half-way down the fall-off
  EXPECT_NEAR(v(deg_to_rad(0)), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(v(deg_to_rad(110)), 0.0);
  EXPECT_DOUBLE_EQ(v(deg_to_rad(-135)), 0.0);
  // continuity at the edges
  EXPECT_NEAR(v(deg_to_rad(70.001)), 1.0, 1e-6);
  EXPECT_NEAR(v(deg_to_rad(109.999)), 0.0, 1e-6);
}

TEST(Visibility, WrapsAroundPi) {
  const VisibilityFunction v{deg_to_rad(170), deg_to_rad(20), deg_to_rad(10)};
  EXPECT_DOUBLE_EQ(v(deg_to_rad(-175)), 1.0);
}

// The visible reflectors of an object as the sensor cycle visits them (for_each_visible_reflector),
// with the point's ERCS evaluated as the ideal target list does: ercs_max in the zone of 1, times
// the fall-off value in the fall-off (paper II-C).
std::vector<std::pair<VisibleReflector, double>> visible(const ObjectModel& model, const Vec2& p_OS_O, bool planes = true) {
  std::vector<std::pair<VisibleReflector, double>> seen;
  for_each_visible_reflector(model, p_OS_O, planes, [&](const VisibleReflector& r) {
    double ercs = r.ercs;
    if (r.kind == ReflectorKind::Point && r.zone.kind == VisibilityFunction::Zone::falloff) {
      ercs *= r.point->visibility.falloff_value(r.zone.cos_delta, r.zone.sin_delta);
    }
    seen.emplace_back(r, ercs);
  });
  return seen;
}

TEST(Visibility, PointReflectorErcsFromSensorDirection) {
  ObjectModel m;
  PointReflector p;
  p.p_OR_O = {2.3, 0.9};
  p.ercs_max = 2.0;
  p.visibility = {deg_to_rad(45), deg_to_rad(25), deg_to_rad(40)};
  m.points.push_back(p);
  // From 45 deg (the centre of the visibility function): fully visible, no fall-off to evaluate.
  auto seen = visible(m, {12.3, 10.9});
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].first.zone.kind, VisibilityFunction::Zone::one);
  EXPECT_DOUBLE_EQ(seen[0].second, 2.0);
  EXPECT_EQ(seen[0].first.p_OT_O, p.p_OR_O);
  // From 90 deg: half-way down the raised cosine, ERCS 1.
  seen = visible(m, {2.3, 10.9});
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].first.zone.kind, VisibilityFunction::Zone::falloff);
  EXPECT_NEAR(seen[0].second, 1.0, 1e-12);
  EXPECT_TRUE(visible(m, {-7.7, 0.9}).empty());  // from behind (180 deg): not visited at all
  EXPECT_TRUE(visible(m, {2.3, 0.9}).empty());   // sensor on the reflector: no impinging angle
}

TEST(Visibility, PointsFirstThenPlanesOnlyWhenAsked) {
  ObjectModel m;
  m.planes.push_back(plane_from_chord("front", {2.2, -0.75}, {2.2, 0.75}, 0.1, 0.7));
  PointReflector corner;
  corner.p_OR_O = {2.3, 0.9};
  corner.visibility = {0.0, kPi, 0.0};  // seen from everywhere
  m.points.push_back(corner);
  const auto seen = visible(m, {20.0, 0.0});
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].first.kind, ReflectorKind::Point);
  EXPECT_EQ(seen[1].first.kind, ReflectorKind::Plane);
  EXPECT_NEAR(seen[1].first.p_OT_O.x(), 2.3, 1e-12);  // the front apex
  EXPECT_DOUBLE_EQ(seen[1].second, 0.7);
  EXPECT_EQ(visible(m, {20.0, 0.0}, false).size(), 1u);  // Fidelity::points_only
}

TEST(Visibility, PlaneReflectionPointOnTheLineToTheCentre) {
  // Front plane: chord from (2.2, -0.75) to (2.2, 0.75), sagitta 0.1: r = (0.5625 + 0.01)/0.2 = 2.8625
  const PlaneReflector plane = plane_from_chord("front", {2.2, -0.75}, {2.2, 0.75}, 0.1, 1.0);
  EXPECT_NEAR(plane.radius_m, 2.8625, 1e-12);
  EXPECT_NEAR(plane.center_O.x(), 2.3 - 2.8625, 1e-12);
  // Sensor straight ahead: the apex.
  const auto apex = plane_reflection_point_O(plane, {20.0, 0.0});
  ASSERT_TRUE(apex);
  EXPECT_NEAR(apex->x(), 2.3, 1e-12);
  EXPECT_NEAR(apex->y(), 0.0, 1e-12);
  // Sensor off to the side within the sector: the point lies on the arc towards the sensor.
  const Vec2 sensor{10.0, 1.5};
  const auto p = plane_reflection_point_O(plane, sensor);
  ASSERT_TRUE(p);
  EXPECT_NEAR((*p - plane.center_O).norm(), plane.radius_m, 1e-12);
  const Vec2 a = (*p - plane.center_O).normalized(), b = (sensor - plane.center_O).normalized();
  EXPECT_NEAR(a.x() * b.y() - a.y() * b.x(), 0.0, 1e-12);
  // Position 2 of Fig. 7: the line misses the sector.
  EXPECT_FALSE(plane_reflection_point_O(plane, {3.0, 5.0}));
  // Sensor inside the circle or on it: no reflection.
  EXPECT_FALSE(plane_reflection_point_O(plane, {0.0, 0.0}));
  EXPECT_FALSE(plane_reflection_point_O(plane, plane.center_O));
  EXPECT_FALSE(plane_reflection_point_O(plane, plane.arc_point_O(plane.start_rad + 0.5 * plane.span_rad)));
}

TEST(Visibility, ScaledModelKeepsChordEndsAndApex) {
  const PlaneReflector plane = plane_from_chord("front", {2.2, -0.75}, {2.2, 0.75}, 0.1, 1.0);
  ObjectModel m;
  m.length_m = 4.6;
  m.width_m = 1.8;
  m.planes.push_back(plane);
  PointReflector corner;
  corner.p_OR_O = {2.3, 0.9};
  m.points.push_back(corner);
  const ObjectModel s = scale_model(m, 2 * 4.6, 1.8 * 1.5);
  EXPECT_NEAR(s.points[0].p_OR_O.x(), 4.6, 1e-12);
  EXPECT_NEAR(s.points[0].p_OR_O.y(), 1.35, 1e-12);
  const auto& q = s.planes[0];
  EXPECT_NEAR(q.arc_point_O(q.start_rad).x(), 4.4, 1e-9);
  EXPECT_NEAR(std::abs(q.arc_point_O(q.start_rad).y()), 1.125, 1e-9);
  EXPECT_NEAR(q.arc_point_O(q.start_rad + 0.5 * q.span_rad).x(), 4.6, 1e-9);
}


// The diffuse pieces of a face (for_each_diffuse_piece) as (centre, length) pairs.
std::vector<std::pair<Vec2, double>> diffuse_pieces(const PlaneReflector& plane, const Vec2& p_OS_O, double piece_range_m) {
  std::vector<std::pair<Vec2, double>> pieces;
  for_each_diffuse_piece(plane, p_OS_O, DiffusePieceSize{piece_range_m}, [&](const Vec2& p_OT_O, double length_m) {
    pieces.emplace_back(p_OT_O, length_m);
  });
  return pieces;
}

// A nearly straight face: chord (-2, 1) .. (2, 1), 4 m, 1 cm sagitta (circle radius
// (4 + 1e-4) / 0.02 = 200.005 m, centre at (0, 1.01 - 200.005)), bulging towards +y.
PlaneReflector four_metre_face() { return plane_from_chord("side", {-2.0, 1.0}, {2.0, 1.0}, 0.01, 1.0); }

TEST(DiffusePieces, BroadsideIsOnePieceTheWholeChord) {
  const PlaneReflector face = four_metre_face();
  // From (0, 21), 20 m in front of the chord's middle: both ends sqrt(4 + 400) away, range extent 0
  // => ceil(0 / 0.5) = 0, at least 1 piece: the whole 4-m chord, centred at (0, 1).
  const auto pieces = diffuse_pieces(face, {0.0, 21.0}, 0.5);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_NEAR(pieces[0].first.x(), 0.0, 1e-9);
  EXPECT_NEAR(pieces[0].first.y(), 1.0, 1e-9);
  EXPECT_NEAR(pieces[0].second, 4.0, 1e-9);
  // From (1, 21): ends sqrt(1 + 400) = 20.02498 and sqrt(9 + 400) = 20.22375 m away, extent
  // 0.19877 m: 1 piece of 0.5-m range cells, 2 of 0.15-m cells (ceil(1.325)), each 2 m long.
  EXPECT_EQ(diffuse_pieces(face, {1.0, 21.0}, 0.5).size(), 1u);
  const auto two = diffuse_pieces(face, {1.0, 21.0}, 0.15);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_NEAR(two[0].second, 2.0, 1e-9);
  EXPECT_NEAR(std::abs(two[0].first.x()), 1.0, 1e-9);
  EXPECT_NEAR(two[0].first.x() + two[1].first.x(), 0.0, 1e-9);
}

TEST(DiffusePieces, ObliqueViewOnePiecePerRangeCell) {
  const PlaneReflector face = four_metre_face();
  // From (10, 11): the ends (2, 1) and (-2, 1) lie sqrt(64 + 100) = 12.80625 m and
  // sqrt(144 + 100) = 15.62050 m away: range extent 2.81425 m; 0.5-m cells: ceil(5.6285) = 6
  // pieces of 4/6 m, centred at x = 2 - (2k + 1)/3 (from the arc's start, the +x end) on y = 1.
  const auto pieces = diffuse_pieces(face, {10.0, 11.0}, 0.5);
  ASSERT_EQ(pieces.size(), 6u);
  const double first_end_x = (face.center_O + face.radius_m * face.u_start_O).x();
  const double sign = first_end_x > 0.0 ? 1.0 : -1.0;  // the arc's start end, +-2
  EXPECT_NEAR(std::abs(first_end_x), 2.0, 1e-9);
  double total_m = 0.0;
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(pieces[k].first.x(), sign * (2.0 - (2.0 * k + 1.0) / 3.0), 1e-9) << k;
    EXPECT_NEAR(pieces[k].first.y(), 1.0, 1e-9) << k;
    EXPECT_NEAR(pieces[k].second, 4.0 / 6.0, 1e-9) << k;
    total_m += pieces[k].second;
  }
  EXPECT_NEAR(total_m, 4.0, 1e-9);  // the pieces tile the chord
  // 1.4-m cells: ceil(2.01018) = 3 pieces of 4/3 m.
  const auto coarse = diffuse_pieces(face, {10.0, 11.0}, 1.4);
  ASSERT_EQ(coarse.size(), 3u);
  EXPECT_NEAR(coarse[1].first.x(), 0.0, 1e-9);
  EXPECT_NEAR(coarse[1].second, 4.0 / 3.0, 1e-9);
}

TEST(DiffusePieces, AtMostTheMaximumNumberOfPieces) {
  const PlaneReflector face = four_metre_face();
  // 0.1-m cells from (10, 11): ceil(28.14) = 29 > 16: 16 pieces of 0.25 m.
  const auto pieces = diffuse_pieces(face, {10.0, 11.0}, 0.1);
  ASSERT_EQ(pieces.size(), static_cast<std::size_t>(kMaxDiffusePieces));
  EXPECT_EQ(kMaxDiffusePieces, 16);
  for (const auto& [p, length_m] : pieces) EXPECT_NEAR(length_m, 4.0 / 16.0, 1e-9);
  EXPECT_NEAR(std::abs(pieces[0].first.x()), 2.0 - 0.125, 1e-9);
}

TEST(DiffusePieces, AnArrayThatResolvesAzimuthCutsABroadsideFaceIntoBeams) {
  const PlaneReflector face = four_metre_face();  // chord (-2, 1) .. (2, 1)
  // Broadside from (0, 11): no range extent, but the chord spans 2 atan(2 / 10) = 22.62 deg:
  // with 1-deg beams ceil(22.62) = 23 pieces of 4/23 m; without beams one piece.
  std::vector<double> lengths_m;
  for_each_diffuse_piece(face, {0.0, 11.0}, DiffusePieceSize{0.5, deg_to_rad(1.0), 64},
                         [&](const Vec2&, double length_m) { lengths_m.push_back(length_m); });
  ASSERT_EQ(lengths_m.size(), 23u);
  EXPECT_NEAR(lengths_m[0], 4.0 / 23.0, 1e-12);
  EXPECT_EQ(diffuse_pieces(face, {0.0, 11.0}, 0.5).size(), 1u);
  // A profile's own maximum: 16 pieces of 0.25 m.
  lengths_m.clear();
  for_each_diffuse_piece(face, {0.0, 11.0}, DiffusePieceSize{0.5, deg_to_rad(1.0), 16},
                         [&](const Vec2&, double length_m) { lengths_m.push_back(length_m); });
  EXPECT_EQ(lengths_m.size(), 16u);
}

TEST(DiffusePieces, NothingFromBehindTheFace) {
  const PlaneReflector face = four_metre_face();
  EXPECT_TRUE(diffuse_pieces(face, {0.0, -10.0}, 0.5).empty());  // behind, straight
  EXPECT_TRUE(diffuse_pieces(face, {10.0, 0.5}, 0.5).empty());   // behind the chord's line, off to the side
  EXPECT_TRUE(diffuse_pieces(face, face.center_O, 0.5).empty());  // at the circle's centre
  // In front, far off to the side (no specular point there: the line to the centre, 2.7 deg off the apex, misses
  // the +-0.57-deg sector), the face still returns diffuse pieces.
  EXPECT_FALSE(plane_reflection_point_O(face, {10.0, 11.0}));
  EXPECT_FALSE(diffuse_pieces(face, {10.0, 11.0}, 0.5).empty());
}

TEST(DiffusePieces, TheBoxSidesSeenFromFrontLeftAreTheFrontAndTheLeft) {
  // A 4.6 x 1.8 m box seen from (10, 5): the front (x = 2.3) and the left (y = 0.9) face the
  // sensor, the rear and the right do not.
  const auto sides = box_sides(4.6, 1.8);
  std::vector<std::size_t> pieces(4, 0);
  double left_total_m = 0.0;
  for (std::size_t k = 0; k < 4; ++k) {
    for_each_face_piece(sides[k].a_O, sides[k].b_O, sides[k].outward_O, {10.0, 5.0}, DiffusePieceSize{0.075, 0.0, 128},
                        [&](const Vec2& p_OT_O, double length_m) {
                          ++pieces[k];
                          if (k == 2) {
                            EXPECT_NEAR(p_OT_O.y(), 0.9, 1e-12);
                            left_total_m += length_m;
                          }
                        });
  }
  EXPECT_EQ(std::string(kBoxSideNames[0]), "box_front");
  EXPECT_EQ(pieces[1], 0u);
  EXPECT_EQ(pieces[3], 0u);
  // The left side (-2.3, 0.9) .. (2.3, 0.9): ends at sqrt(12.3^2 + 4.1^2) = 12.96534 m and
  // sqrt(7.7^2 + 4.1^2) = 8.72353 m, extent 4.24181 m: ceil(56.5575) = 57 pieces of 4.6/57 m.
  EXPECT_EQ(pieces[2], 57u);
  EXPECT_NEAR(left_total_m, 4.6, 1e-9);
  // The front (2.3, -0.9) .. (2.3, 0.9): ends at sqrt(7.7^2 + 5.9^2) = 9.70052 and
  // sqrt(7.7^2 + 4.1^2) = 8.72353 m, extent 0.97699 m: ceil(13.0265) = 14 pieces.
  EXPECT_EQ(pieces[0], 14u);
  // 0.3 m inset: the left side on y = 0.6, the front unchanged; 2 m inset: on the centre line.
  EXPECT_DOUBLE_EQ(box_sides(4.6, 1.8, 0.3)[2].a_O.y(), 0.6);
  EXPECT_DOUBLE_EQ(box_sides(4.6, 1.8, 0.3)[3].b_O.y(), -0.6);
  EXPECT_DOUBLE_EQ(box_sides(4.6, 1.8, 0.3)[0].b_O.y(), 0.9);
  EXPECT_DOUBLE_EQ(box_sides(4.6, 1.8, 2.0)[2].a_O.y(), 0.0);
  // A guard rail (a polyline template) has no box sides; a car model has.
  ObjectModel rail;
  rail.length_m = 4.0;
  rail.width_m = 0.3;
  rail.polyline_points = 2;
  EXPECT_FALSE(has_box_sides(rail));
  rail.polyline_points = 0;
  EXPECT_TRUE(has_box_sides(rail));
}

}  // namespace
}  // namespace rcsim
