// The scatterer bodies and road clutter of synth/scatterers.hpp: the outline against its box, the
// facet's physical-optics response, the body chosen by class and size, and the clutter field's
// independence of where it is looked at from.
#include "synth/scatterers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/angles.hpp"

namespace rcsim::synth::scatterers_test {


int count_kind(const ScattererBody& body, ScattererKind kind) {
  return static_cast<int>(std::count_if(body.scatterers.begin(), body.scatterers.end(),
                                        [kind](const Scatterer& s) { return s.kind == kind; }));
}

TEST(SynthScatterers, CarOutlineTouchesItsBoxAndFacesOutwards) {
  const ScattererBody car = make_body("passenger_car", 4.6, 1.8);
  double max_x = 0.0, max_y = 0.0;
  int facets = 0;
  for (const auto& s : car.scatterers) {
    EXPECT_LE(std::abs(s.p_O.x()), 2.3 + 1e-9);
    EXPECT_LE(std::abs(s.p_O.y()), 0.9 + 1e-9);
    if (s.kind != ScattererKind::facet) continue;
    ++facets;
    max_x = std::max(max_x, std::abs(s.p_O.x()));
    max_y = std::max(max_y, std::abs(s.p_O.y()));
    // The normal points away from the centre.
    EXPECT_GT(s.p_O.dot(Vec2(std::cos(s.axis_rad), std::sin(s.axis_rad))), 0.0);
  }
  EXPECT_GT(facets, 100);  // dense along the contour
  EXPECT_NEAR(max_x, 2.3, 0.01);
  EXPECT_NEAR(max_y, 0.9, 0.01);
}

TEST(SynthScatterers, FacetIsSpecular) {
  Scatterer f;
  f.kind = ScattererKind::facet;
  f.facet_length_m = 0.1;
  f.strength = 0.1 * 0.2;
  const double lambda = 0.0125;
  // Physical optics at normal incidence: sqrt(4 pi) A / lambda.
  EXPECT_NEAR(facet_sqrt_rcs_m(f, 0.0, lambda), std::sqrt(4.0 * kPi) * 0.02 / lambda, 1e-9);
  // First null at sin(theta) = lambda / (2 ds); nothing from behind.
  EXPECT_NEAR(facet_sqrt_rcs_m(f, std::asin(lambda / 0.2), lambda), 0.0, 1e-9);
  EXPECT_EQ(facet_sqrt_rcs_m(f, 2.0, lambda), 0.0);
}

TEST(SynthScatterers, BodyByClassAndSize) {
  // The pole: one unit isotropic point at its centre, 0.6 m up; occluder 1.2 m tall.
  const ScattererBody pole = make_body("pole", 0.1, 0.1);
  ASSERT_EQ(pole.scatterers.size(), 1u);
  EXPECT_EQ(pole.scatterers[0].kind, ScattererKind::isotropic);
  EXPECT_EQ(pole.scatterers[0].p_O, Vec2::Zero());
  EXPECT_DOUBLE_EQ(pole.scatterers[0].strength, 1.0);
  EXPECT_DOUBLE_EQ(pole.scatterers[0].height_m, 0.6);
  EXPECT_DOUBLE_EQ(pole.height_m, 1.2);
  // An unknown class is a pole when small in both directions, else a car body of its box.
  const ScattererBody small = make_body("bollard", 0.3, 0.3);
  EXPECT_EQ(small.scatterers.size(), 1u);
  const ScattererBody unknown = make_body("van", 4.6, 1.8);
  EXPECT_EQ(unknown.scatterers.size(), make_body("passenger_car", 4.6, 1.8).scatterers.size());
  EXPECT_DOUBLE_EQ(unknown.height_m, 1.45);
  // The truck: 4 m occluder; the guide board: two isotropic posts and 2.2 m.
  const ScattererBody truck = make_body("truck_trailer", 16.5, 2.55);
  EXPECT_DOUBLE_EQ(truck.height_m, 4.0);
  EXPECT_DOUBLE_EQ(truck.length_m, 16.5);
  for (const auto& s : truck.scatterers) {
    EXPECT_LE(std::abs(s.p_O.x()), 8.25 + 1e-9);
    EXPECT_LE(std::abs(s.p_O.y()), 1.275 + 1e-9);
  }
  const ScattererBody board = make_body("guide_board", 0.3, 3.0);
  EXPECT_DOUBLE_EQ(board.height_m, 2.2);
  EXPECT_EQ(count_kind(board, ScattererKind::isotropic), 2);
  // A shorter facet wavelength cuts the curved parts finer: more facets, none longer than the
  // 0.1 m face step (along the bulged face the chord is a little longer than its span: 0.1 %).
  const ScattererBody fine = make_body("passenger_car", 4.6, 1.8, 0.004);
  EXPECT_GT(count_kind(fine, ScattererKind::facet), count_kind(make_body("passenger_car", 4.6, 1.8), ScattererKind::facet));
  for (const auto& s : fine.scatterers) EXPECT_LE(s.facet_length_m, 0.1 * 1.001);
}

TEST(SynthScatterers, RoadClutterIsOneFieldWhereverItIsSeenFrom) {
  Clutter clutter;  // 0.02 per m^2 on 8 m tiles
  const auto near_origin = road_clutter_near(clutter, 5, Vec2(0.0, 0.0), 20.0);
  const auto near_ten = road_clutter_near(clutter, 5, Vec2(10.0, 0.0), 20.0);
  // About 0.02 x pi x 20^2 = 25 points in the disc; all in it, on the road, isotropic.
  EXPECT_GT(near_origin.size(), 8u);
  EXPECT_LT(near_origin.size(), 50u);
  for (const auto& w : near_origin) {
    EXPECT_LE(w.p_WC_W.norm(), 20.0);
    EXPECT_EQ(w.scatterer.kind, ScattererKind::isotropic);
    EXPECT_GE(w.scatterer.height_m, 0.02);
    EXPECT_LE(w.scatterer.height_m, 0.15);
  }
  // A point in both discs is found from both centres, the same.
  int shared = 0;
  for (const auto& a : near_origin) {
    if ((a.p_WC_W - Vec2(10.0, 0.0)).norm() > 20.0) continue;
    ++shared;
    const auto same = std::find_if(near_ten.begin(), near_ten.end(), [&](const WorldScatterer& b) {
      return b.p_WC_W == a.p_WC_W && b.scatterer.height_m == a.scatterer.height_m &&
             b.scatterer.strength == a.scatterer.strength;
    });
    EXPECT_NE(same, near_ten.end()) << a.p_WC_W.transpose();
  }
  EXPECT_GT(shared, 3);
  // Another seed, another field; no density, no clutter.
  const auto other = road_clutter_near(clutter, 6, Vec2(0.0, 0.0), 20.0);
  EXPECT_FALSE(other.size() == near_origin.size() && !other.empty() && other[0].p_WC_W == near_origin[0].p_WC_W);
  clutter.density_per_m2 = 0.0;
  EXPECT_TRUE(road_clutter_near(clutter, 5, Vec2(0.0, 0.0), 20.0).empty());
}

}  // namespace rcsim::synth::scatterers_test
