// The propagation of synth/propagation.hpp: the box-crossing test for occlusion, the antenna,
// elevation, two-ray and IF factors by hand, one pole's echo assembled from them, and occlusion
// and the back-and-forth echoes on whole bodies.
#include "synth/propagation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "common/angles.hpp"
#include "synth/scatterers.hpp"

namespace rcsim::synth::propagation_test {


// A placed box of 4 m x 2 m (its scatterers are not used by segment_crosses_box).
PlacedBody box_at(const ScattererBody& body, double x_m, double y_m, double yaw_rad) {
  PlacedBody placed{&body, {}};
  placed.state.X_WB = {x_m, y_m, yaw_rad};
  return placed;
}

TEST(SynthPropagation, SegmentCrossesBoxSlabTest) {
  ScattererBody body;
  body.length_m = 4.0;
  body.width_m = 2.0;
  const PlacedBody ahead = box_at(body, 10.0, 0.0, 0.0);  // x in [8, 12], y in [-1, 1]
  EXPECT_TRUE(segment_crosses_box(Vec2(0.0, 0.0), Vec2(20.0, 0.0), ahead, 0.0));
  EXPECT_FALSE(segment_crosses_box(Vec2(0.0, 1.5), Vec2(20.0, 1.5), ahead, 0.0));  // passes beside
  EXPECT_FALSE(segment_crosses_box(Vec2(0.0, 0.0), Vec2(7.9, 0.0), ahead, 0.0));   // ends before
  EXPECT_TRUE(segment_crosses_box(Vec2(0.0, 0.0), Vec2(8.1, 0.0), ahead, 0.0));    // ends inside
  EXPECT_TRUE(segment_crosses_box(Vec2(9.0, 0.5), Vec2(11.0, 0.5), ahead, 0.0));   // wholly inside
  // Diagonal through a corner region: from (6, -3) to (14, 5) passes (9, 0), inside.
  EXPECT_TRUE(segment_crosses_box(Vec2(6.0, -3.0), Vec2(14.0, 5.0), ahead, 0.0));
  // Shrunk by 0.05 m the box starts at 8.05: a ray ending at 8.04 no longer touches it.
  EXPECT_TRUE(segment_crosses_box(Vec2(0.0, 0.0), Vec2(8.04, 0.0), ahead, 0.0));
  EXPECT_FALSE(segment_crosses_box(Vec2(0.0, 0.0), Vec2(8.04, 0.0), ahead, 0.05));
  // Shrunk to nothing: never crossed.
  EXPECT_FALSE(segment_crosses_box(Vec2(0.0, 0.0), Vec2(20.0, 0.0), ahead, 1.0));
  // Turned by 90 deg the box spans y in [-2, 2]: the ray at y = 1.5 now hits it.
  EXPECT_TRUE(segment_crosses_box(Vec2(0.0, 1.5), Vec2(20.0, 1.5), box_at(body, 10.0, 0.0, kPi / 2.0), 0.0));
}

TEST(SynthPropagation, AntennaElevationTwoRayAndIfFactorsByHand) {
  SynthConfig config;
  const Propagator p(config);
  // Boresight: sum 1, delta 0.
  const auto [sum0, delta0] = p.antenna(0.0, 0.0);
  EXPECT_NEAR(sum0.real(), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(delta0), 0.0, 1e-12);
  // 30 deg: element si(pi/4) cos 30 = 0.900316 x 0.866025 = 0.779697, two way 0.607927;
  // half the pair phase pi * 0.5 * 0.5 = pi/4: sum 0.607927 cos(pi/4), delta j 0.607927 sin(pi/4).
  const double two_way = std::pow(std::sin(kPi / 4.0) / (kPi / 4.0) * std::cos(kPi / 6.0), 2.0);
  EXPECT_NEAR(two_way, 0.607927, 1e-6);
  const auto [sum30, delta30] = p.antenna(kPi / 6.0, 0.0);
  EXPECT_NEAR(sum30.real(), two_way * std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(delta30.imag(), two_way * std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(p.antenna(-kPi / 6.0, 0.0).second.imag(), -two_way * std::sqrt(0.5), 1e-12);  // left/right
  // Elevation: 1 in the plane, half power (1/sqrt 2) at 12 deg, the 0.12 floor far off.
  EXPECT_DOUBLE_EQ(p.elevation_pattern(0.0), 1.0);
  EXPECT_NEAR(p.elevation_pattern(deg_to_rad(12.0)), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(p.elevation_pattern(deg_to_rad(-12.0)), std::sqrt(0.5), 1e-12);
  EXPECT_DOUBLE_EQ(p.elevation_pattern(deg_to_rad(80.0)), 0.12);
  // Two-ray: at the sensor's own height without ground reflection exactly 1; far away with
  // Gamma = -0.6 the paths cancel to (1 - 0.6)^2 = 0.16 (path difference 2 h_s h / d -> 0).
  SynthConfig no_ground;
  no_ground.propagation.ground_reflection = 0.0;
  EXPECT_NEAR(std::abs(Propagator(no_ground).two_ray_factor(10.0, 0.5, 0.0) - 1.0), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(p.two_ray_factor(1.0e5, 0.5, 0.0)), 0.16, 1e-3);
  // IF gain: 3 m is the high-pass corner (second order: 1/sqrt 2); the equalizer there 0.1/sqrt(1.01);
  // the low-pass (3/55)^6 is negligible: 0.070360.
  EXPECT_NEAR(p.if_gain(3.0), 0.1 / std::sqrt(1.01) * std::sqrt(0.5), 1e-9);
  // Beyond the 55 m low-pass corner the sixth order takes over: from 55 m to 110 m the low-pass
  // goes from 1/sqrt(2) to 1/sqrt(1 + 2^12) and the equalizer from 1.833/sqrt(4.361) to
  // 3.667/sqrt(14.44) (x 1.09895); the high-pass is 1 to 1e-5 at both: ratio 0.024281.
  EXPECT_NEAR(p.if_gain(110.0) / p.if_gain(55.0), 0.024281, 1e-5);
}

TEST(SynthPropagation, PoleEchoAssembledFromTheFactors) {
  SynthConfig config;
  config.propagation.ground_reflection = 0.0;  // free space
  const Propagator p(config);
  const ScattererBody pole = make_body("pole", 0.1, 0.1);  // unit point 0.6 m up
  SensorState sensor;  // at the origin, 0.5 m up, looking along +x
  BodyState state;
  state.X_WB = {10.0, 0.0, 0.0};
  state.v_WB_W = Vec2(-5.0, 0.0);  // coming closer at 5 m/s
  const auto echoes = p.echoes(sensor, {PlacedBody{&pole, state}}, {});
  ASSERT_EQ(echoes.size(), 1u);
  const Echo& e = echoes[0];
  // Slant range hypot(10, 0.1); the radial rate -5 x 10 / slant range; on boresight.
  const double range_m = std::hypot(10.0, 0.1);
  EXPECT_NEAR(e.range_m, range_m, 1e-12);
  EXPECT_NEAR(e.range_rate_mps, -5.0 * 10.0 / range_m, 1e-12);
  EXPECT_NEAR(e.azimuth_rad, 0.0, 1e-12);
  // sqrt(sigma) x (10 / R)^2 x two-ray x antenna x IF gain.
  const double elevation_rad = std::atan2(0.1, 10.0);
  const std::complex<double> expected = (10.0 / range_m) * (10.0 / range_m) * p.two_ray_factor(10.0, 0.6, 0.1) *
                                        p.antenna(0.0, elevation_rad).first * p.if_gain(range_m);
  EXPECT_NEAR(std::abs(e.sum - expected), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(e.delta), 0.0, 1e-12);
  // The sensor moving towards a static pole sees the same rate.
  sensor.v_WS_W = Vec2(5.0, 0.0);
  state.v_WB_W = Vec2::Zero();
  EXPECT_NEAR(p.echoes(sensor, {PlacedBody{&pole, state}}, {})[0].range_rate_mps, -5.0 * 10.0 / range_m, 1e-12);
  // Behind the sensor (outside the +-70 deg illuminated sector) and beyond 70 m: nothing.
  state.X_WB = {-10.0, 0.0, 0.0};
  EXPECT_TRUE(p.echoes(sensor, {PlacedBody{&pole, state}}, {}).empty());
  state.X_WB = {75.0, 0.0, 0.0};
  EXPECT_TRUE(p.echoes(sensor, {PlacedBody{&pole, state}}, {}).empty());
  // A world scatterer (clutter) is static: its rate is the sensor's own motion.
  WorldScatterer clutter;
  clutter.scatterer.height_m = 0.5;
  clutter.p_WC_W = Vec2(8.0, 0.0);
  const auto from_clutter = p.echoes(sensor, {}, {clutter});
  ASSERT_EQ(from_clutter.size(), 1u);
  EXPECT_NEAR(from_clutter[0].range_m, 8.0, 1e-12);
  EXPECT_NEAR(from_clutter[0].range_rate_mps, -5.0, 1e-12);
}

TEST(SynthPropagation, NearerBodyHidesTheOneBehind) {
  const SynthConfig config;
  const Propagator p(config);
  const ScattererBody pole = make_body("pole", 0.1, 0.1);
  const ScattererBody car = make_body("passenger_car", 4.6, 1.8);
  SensorState sensor;  // at the origin, looking along +x
  BodyState behind, wall;
  behind.X_WB = {15.0, 0.0, 0.0};
  wall.X_WB = {8.0, 0.0, kPi / 2};  // a car broadside across the line of sight
  const auto alone = p.echoes(sensor, {PlacedBody{&pole, behind}}, {});
  ASSERT_EQ(alone.size(), 1u);
  const auto hidden = p.echoes(sensor, {PlacedBody{&pole, behind}, PlacedBody{&car, wall}}, {});
  for (const auto& e : hidden) EXPECT_LT(e.range_m, 10.0);
}

TEST(SynthPropagation, BackAndForthEchoesAtShortRangeOnly) {
  const SynthConfig config;
  const Propagator p(config);
  const ScattererBody car = make_body("passenger_car", 4.6, 1.8);
  SensorState sensor;
  BodyState near_car, far_car;
  near_car.X_WB = {1.0 + 2.3, 0.0, kPi};  // front 1 m ahead, facing the sensor
  far_car.X_WB = {6.0 + 2.3, 0.0, kPi};
  const auto count_beyond = [](const std::vector<Echo>& echoes, double r_m) {
    int n = 0;
    for (const auto& e : echoes) n += e.range_m > r_m && std::abs(std::remainder(e.range_m, 1.0)) < 0.05 ? 1 : 0;
    return n;
  };
  const auto near_echoes = p.echoes(sensor, {PlacedBody{&car, near_car}}, {});
  double direct = 0.0, double_bounce = 0.0;
  for (const auto& e : near_echoes) {
    if (std::abs(e.range_m - 1.0) < 0.02) direct = std::max(direct, std::abs(e.sum));
    if (std::abs(e.range_m - 2.0) < 0.04) double_bounce = std::max(double_bounce, std::abs(e.sum));
  }
  EXPECT_GT(direct, 0.0);
  EXPECT_GT(double_bounce, 0.0);
  EXPECT_GT(count_beyond(near_echoes, 1.9), 0);
  for (const auto& e : p.echoes(sensor, {PlacedBody{&car, far_car}}, {})) EXPECT_LT(e.range_m, 11.0);
}

}  // namespace rcsim::synth::propagation_test
