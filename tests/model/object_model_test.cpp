// Paper II-A/B, Figs. 6-7: the visibility function decided on squares and the plane-reflector
// sectors tested by cross products, each against the angle definition it replaces in the cycle.
#include "model/object_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/angles.hpp"
#include "common/rng.hpp"
#include "sim/visibility.hpp"

namespace rcsim {
namespace {

PlaneReflector arc(double start_rad, double span_rad) {
  PlaneReflector plane;
  plane.set_arc(start_rad, span_rad);
  return plane;
}

Vec2 direction(double angle_rad, double length) { return length * Vec2(std::cos(angle_rad), std::sin(angle_rad)); }

// The angle version, fed with atan2 of the direction vector as the sensor cycle used to do.
bool covers_by_atan2(const PlaneReflector& plane, const Vec2& d_O) {
  return plane.covers_direction(std::atan2(d_O.y(), d_O.x()));
}

std::vector<PlaneReflector> test_arcs() {
  std::vector<PlaneReflector> arcs = {
      // The passenger car's planes: front (apex 0), rear (apex pi: the arc spans +-pi), sides.
      plane_from_chord("front", {2.2, -0.75}, {2.2, 0.75}, 0.1, 1.0),
      plane_from_chord("rear", {-2.2, 0.75}, {-2.2, -0.75}, 0.1, 0.8),
      plane_from_chord("side_left", {-1.7, 0.88}, {1.7, 0.88}, 0.02, 0.7),
      plane_from_chord("side_right", {1.7, -0.88}, {-1.7, -0.88}, 0.02, 0.7),
      // A half circle (sagitta = half the chord), more than a half circle across +-pi and not,
      // a half circle set directly, and the whole circle.
      plane_from_chord("half", {1.0, -0.5}, {1.0, 0.5}, 0.5, 1.0),
      arc(0.5 * kPi, 1.5 * kPi),
      arc(-0.75 * kPi, 1.5 * kPi),
      arc(-0.5 * kPi, kPi),
      arc(0.3, kTwoPi),
  };
  Rng rng(11, 0);
  for (int i = 0; i < 40; ++i) arcs.push_back(arc(rng.uniform(-2.0 * kTwoPi, 2.0 * kTwoPi), rng.uniform(0.0, kTwoPi)));
  // Arcs that end on or start at +-pi.
  arcs.push_back(arc(kPi, 0.5));
  arcs.push_back(arc(-kPi, 0.5));
  arcs.push_back(arc(kPi - 0.5, 0.5));
  arcs.push_back(arc(0.5 * kPi, 1.5 * kPi));
  return arcs;
}

TEST(PlaneReflector, CrossProductCoverageAgreesWithAtan2OnRandomDirections) {
  Rng rng(5, 0);
  for (const auto& plane : test_arcs()) {
    for (int i = 0; i < 20000; ++i) {
      const Vec2 d = direction(rng.uniform(-kPi, kPi), rng.uniform(1e-3, 1e3));
      ASSERT_EQ(plane.covers_direction(d), covers_by_atan2(plane, d))
          << plane.name << " start " << plane.start_rad << " span " << plane.span_rad << " d " << d.transpose();
    }
  }
}

TEST(PlaneReflector, CrossProductCoverageAgreesAtTheArcEnds) {
  const double eps_rad = 1e-9;
  for (const auto& plane : test_arcs()) {
    const double end_rad = plane.start_rad + plane.span_rad;
    const bool full = plane.span_rad >= kTwoPi;
    for (const double length : {1e-3, 1.0, 70.0}) {
      // Just inside and just outside each end.
      for (const auto& [angle_rad, inside] : {std::pair{plane.start_rad + eps_rad, true}, std::pair{end_rad - eps_rad, true},
                                              std::pair{plane.start_rad - eps_rad, full},
                                              std::pair{end_rad + eps_rad, full}}) {
        const Vec2 d = direction(angle_rad, length);
        EXPECT_EQ(plane.covers_direction(d), inside) << plane.name << " span " << plane.span_rad << " at " << angle_rad;
        EXPECT_EQ(covers_by_atan2(plane, d), inside) << plane.name << " span " << plane.span_rad << " at " << angle_rad;
      }
    }
    // The end directions themselves belong to the arc.
    EXPECT_TRUE(plane.covers_direction(plane.u_start_O)) << plane.name;
    EXPECT_TRUE(plane.covers_direction(plane.u_end_O)) << plane.name;
  }
}

// The visibility function as paper Fig. 6 draws it, by the angle: 1 within the half-width of the
// centre, a raised cosine over the fall-off, 0 beyond.
double visibility_by_angle(double center_rad, double full_halfwidth_rad, double falloff_rad, double alpha_rad) {
  const double delta_rad = std::abs(angle_difference_rad(alpha_rad, center_rad));
  if (delta_rad <= full_halfwidth_rad) return 1.0;
  if (delta_rad >= full_halfwidth_rad + falloff_rad) return 0.0;
  return 0.5 * (1.0 + std::cos(kPi * (delta_rad - full_halfwidth_rad) / falloff_rad));
}

TEST(VisibilityFunction, ZonesOnSquaresAgreeWithTheAngleDefinition) {
  struct Shape {
    double center_deg, full_halfwidth_deg, falloff_deg;
  };
  // Corners and wheels of the passenger car, a lobe across +-180 deg, no fall-off, a fall-off
  // reaching past the back (never 0), and visible from everywhere.
  const Shape shapes[] = {{45, 25, 40}, {-135, 25, 40}, {90, 15, 35}, {170, 20, 10}, {-175, 30, 60},
                          {0, 30, 0},   {60, 100, 120}, {10, 180, 0}, {0, 0, 90}};
  Rng rng(8, 0);
  for (const auto& shape : shapes) {
    const double center_rad = deg_to_rad(shape.center_deg), full_rad = deg_to_rad(shape.full_halfwidth_deg),
                 falloff_rad = deg_to_rad(shape.falloff_deg);
    const VisibilityFunction v{center_rad, full_rad, falloff_rad};
    for (int i = 0; i < 20000; ++i) {
      const double alpha_rad = rng.uniform(-kPi, kPi);
      // Away from the edges by a little more than rounding (no fall-off: a step there).
      const double delta_rad = std::abs(angle_difference_rad(alpha_rad, center_rad));
      if (std::abs(delta_rad - full_rad) < 1e-9 || std::abs(delta_rad - full_rad - falloff_rad) < 1e-9) continue;
      const double length_m = rng.uniform(1e-3, 1e3);
      const double expected = visibility_by_angle(center_rad, full_rad, falloff_rad, alpha_rad);
      const double dx = length_m * std::cos(alpha_rad), dy = length_m * std::sin(alpha_rad);
      EXPECT_NEAR(v.from_direction(dx, dy), expected, 1e-12) << shape.center_deg << " at " << rad_to_deg(alpha_rad);
      EXPECT_NEAR(v(alpha_rad), expected, 1e-12);
      const auto zone = v.zone(dx, dy);
      if (zone.kind == VisibilityFunction::Zone::falloff) {
        EXPECT_NEAR(std::hypot(zone.cos_delta, zone.sin_delta), 1.0, 1e-15);  // unit, for falloff_value
        EXPECT_NEAR(std::atan2(zone.sin_delta, zone.cos_delta), angle_difference_rad(alpha_rad, center_rad), 1e-12);
      } else {
        EXPECT_EQ(zone.kind == VisibilityFunction::Zone::one ? 1.0 : 0.0, expected);
      }
    }
  }
}

TEST(VisibilityFunction, NoDirectionNoVisibility) {
  const VisibilityFunction everywhere{0.0, kPi, 0.0};
  EXPECT_EQ(everywhere.from_direction(1.0, -2.0), 1.0);
  EXPECT_EQ(everywhere.from_direction(0.0, 0.0), 0.0);  // sensor on the reflector
  EXPECT_EQ(everywhere.zone(0.0, 0.0).kind, VisibilityFunction::Zone::zero);
}

TEST(PlaneReflector, SetArcKeepsAnglesAndEndDirections) {
  const PlaneReflector plane = plane_from_chord("front", {2.2, -0.75}, {2.2, 0.75}, 0.1, 1.0);
  // The arc ends are the chord ends (paper II-A: the arc through the chord ends and the apex).
  EXPECT_NEAR((plane.center_O + plane.radius_m * plane.u_start_O - Vec2(2.2, -0.75)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((plane.center_O + plane.radius_m * plane.u_end_O - Vec2(2.2, 0.75)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((plane.arc_point_O(plane.start_rad) - Vec2(2.2, -0.75)).norm(), 0.0, 1e-12);
  // Straight ahead and straight back.
  EXPECT_TRUE(plane.covers_direction(Vec2(1.0, 0.0)));
  EXPECT_FALSE(plane.covers_direction(Vec2(-1.0, 0.0)));
  EXPECT_FALSE(plane.covers_direction(Vec2(0.0, 1.0)));
}

// A polyline template: posts of ERCS 0.5 seen within 60 + 30 deg of the line's left normal, a face
// of 0.1 per metre, every 3 m.
ObjectModel rail_template() {
  ObjectModel m;
  m.name = "rail";
  m.length_m = m.width_m = 0.3;
  PolylineTemplate t;
  t.spacing_m = 3.0;
  t.post_ercs = 0.5;
  t.post_visibility = VisibilityFunction(0.0, deg_to_rad(60.0), deg_to_rad(30.0));
  t.face_ercs_per_m = 0.1;
  m.polyline = t;
  return m;
}

TEST(Polyline, PostsEverySpacingAlongTheLineAndAroundCorners) {
  // An L: (0,0) -> (4,0) -> (4,4), 8 m long: posts at arc lengths 0, 3, 6: (0,0), (3,0), (4,2).
  const ObjectModel m = expand_polyline(rail_template(), {{0.0, 0.0}, {4.0, 0.0}, {4.0, 4.0}});
  ASSERT_EQ(m.points.size(), 3u);
  EXPECT_NEAR((m.points[0].p_OR_O - Vec2(0.0, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((m.points[1].p_OR_O - Vec2(3.0, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((m.points[2].p_OR_O - Vec2(4.0, 2.0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(m.points[2].name, "post_2");
  // Visibility centred on the left normal: +y on the first leg (90 deg), -x on the second (180).
  EXPECT_NEAR(m.points[0].visibility.center_rad(), 0.5 * kPi, 1e-12);
  EXPECT_NEAR(std::abs(m.points[2].visibility.center_rad()), kPi, 1e-12);
  EXPECT_DOUBLE_EQ(m.points[0].ercs(0.5 * kPi), 0.5);
  EXPECT_DOUBLE_EQ(m.points[0].ercs(-0.5 * kPi), 0.0);  // from the right: nothing
  // Faces: each 4 m leg in ceil(4 / 3) = 2 pieces of 2 m, ERCS 0.1 x 2 = 0.2.
  ASSERT_EQ(m.planes.size(), 4u);
  for (const auto& p : m.planes) EXPECT_DOUBLE_EQ(p.ercs, 0.2);
  EXPECT_EQ(m.planes[3].name, "face_3");
  // The first piece, (0,0) to (2,0), bulges 1 cm to the left: seen from (1, 10) its reflection
  // point is the apex (1, 0.01); from the right (1, -10) there is none.
  const auto hit = plane_reflection_point_O(m.planes[0], Vec2(1.0, 10.0));
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR((*hit - Vec2(1.0, 0.01)).norm(), 0.0, 1e-9);
  EXPECT_FALSE(plane_reflection_point_O(m.planes[0], Vec2(1.0, -10.0)).has_value());
  // A polyline occludes nothing: its box is 1 mm.
  EXPECT_EQ(m.length_m, 1e-3);
  EXPECT_EQ(m.polyline_points, 3u);
}

TEST(Polyline, RefusesWhatIsNoPolyline) {
  EXPECT_THROW(expand_polyline(rail_template(), {{0.0, 0.0}}), std::invalid_argument);
  EXPECT_THROW(expand_polyline(rail_template(), {{0.0, 0.0}, {0.0, 0.0}}), std::invalid_argument);
  ObjectModel not_a_template = rail_template();
  not_a_template.polyline.reset();
  EXPECT_THROW(expand_polyline(not_a_template, {{0.0, 0.0}, {1.0, 0.0}}), std::invalid_argument);
}

}  // namespace
}  // namespace rcsim
