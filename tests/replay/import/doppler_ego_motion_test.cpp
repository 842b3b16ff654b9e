// Ego motion from the stationary world's Doppler (replay/import/doppler_ego_motion.hpp), on
// targets computed by hand from v_r = -cos(el) (v_Sx cos(az) + v_Sy sin(az)) (Kellner et al. 2013):
// the fit recovers the sensor velocity and rejects moving targets; two sensors give speed and
// yaw rate; one sensor alone gives the speed; the track integrates the pose.
#include "replay/import/doppler_ego_motion.hpp"

#include "common/angles.hpp"
#include "common/range_rate_wrap.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rcsim::replay {
namespace {

// The velocity over the ground of a sensor mounted at X_VS on a vehicle with speed v and yaw
// rate w (no lateral speed at the origin), in the sensor's frame.
Vec2 sensor_velocity_S(const Pose2& X_VS, double v_mps, double w_radps) {
  return rotate(-X_VS.yaw_rad, Vec2(v_mps - w_radps * X_VS.y_m, w_radps * X_VS.x_m));
}

// Stationary targets over the view field, and `moving` targets with their own radial speeds.
std::vector<DopplerTarget> targets_for(const Vec2& v_S_S, int stationary, int moving) {
  std::vector<DopplerTarget> targets;
  for (int i = 0; i < stationary; ++i) {
    const double az = -0.3 + 0.6 * i / (stationary - 1), el = 0.01 * (i % 3);
    targets.push_back({az, el, -std::cos(el) * (v_S_S.x() * std::cos(az) + v_S_S.y() * std::sin(az))});
  }
  for (int i = 0; i < moving; ++i) targets.push_back({0.05 * i, 0.0, -2.0 - 1.5 * i});  // cars, not the world
  return targets;
}

TEST(DopplerEgoMotion, OneSensorsVelocityAndItsStationaryTargets) {
  const Vec2 v_S_S(29.9, -0.4);
  const auto targets = targets_for(v_S_S, 20, 6);
  const SensorVelocityFit fit = fit_sensor_velocity(targets, {});
  ASSERT_TRUE(fit.valid);
  EXPECT_NEAR(fit.v_S_S.x(), 29.9, 1e-9);
  EXPECT_NEAR(fit.v_S_S.y(), -0.4, 1e-9);
  ASSERT_EQ(fit.inliers.size(), 20u);  // exactly the stationary ones
  EXPECT_EQ(fit.inliers.back(), 19u);
  EXPECT_NEAR(fit.residual_rms_mps, 0.0, 1e-9);
}

TEST(DopplerEgoMotion, AnImagingRadarsFrameIsFittedFromABoundedSampleOfPairs) {
  // 10,000 targets, a third of them moving: every pair (5e7 hypotheses of 1e4 residuals each)
  // took hours; 2,048 drawn pairs find the stationary world as exactly.
  const Vec2 v_S_S(12.5, 0.8);
  auto targets = targets_for(v_S_S, 6700, 0);
  for (int i = 0; i < 3300; ++i) targets.push_back({-0.3 + 0.6 * (i % 97) / 96.0, 0.0, 1.0 + 0.01 * i});  // receding
  DopplerFitParameters parameters;
  const SensorVelocityFit fit = fit_sensor_velocity(targets, parameters);
  ASSERT_TRUE(fit.valid);
  EXPECT_NEAR(fit.v_S_S.x(), 12.5, 1e-6);
  EXPECT_NEAR(fit.v_S_S.y(), 0.8, 1e-6);
  EXPECT_EQ(fit.inliers.size(), 6700u);
  // The same frame gives the same fit (the pairs are drawn with a fixed seed).
  EXPECT_EQ(fit_sensor_velocity(targets, parameters).v_S_S, fit.v_S_S);
}

TEST(DopplerEgoMotion, AFewTargetsAreFittedFromEveryPair) {
  // 64 targets have 2,016 pairs, within the budget: every pair is tried, the sample drive's frames
  // (55 targets at most) too, so their fit is the exhaustive one.
  const auto targets = targets_for(Vec2(20.0, 0.0), 40, 24);
  DopplerFitParameters exhaustive, sampled;
  sampled.max_hypotheses = 64;  // fewer than the 2,016 pairs: drawn
  const SensorVelocityFit a = fit_sensor_velocity(targets, exhaustive), b = fit_sensor_velocity(targets, sampled);
  ASSERT_TRUE(a.valid && b.valid);
  EXPECT_NEAR(a.v_S_S.x(), 20.0, 1e-9);
  EXPECT_EQ(a.inliers.size(), 40u);
  EXPECT_NEAR(b.v_S_S.x(), 20.0, 1e-9);
}

TEST(DopplerEgoMotion, TooFewStationaryTargetsIsNoFit) {
  EXPECT_FALSE(fit_sensor_velocity(targets_for(Vec2(10.0, 0.0), 3, 0), {}).valid);
  EXPECT_FALSE(fit_sensor_velocity({}, {}).valid);
}

TEST(DopplerEgoMotion, TwoSensorsGiveSpeedAndYawRate) {
  const std::vector<Pose2> X_VS{{3.8, 0.0, -0.012}, {-1.1, 0.0, 3.1346}};
  const double v = 30.0, w = 0.1;
  std::vector<std::vector<DopplerTarget>> targets;
  std::vector<SensorVelocityFit> fits;
  for (const Pose2& m : X_VS) {
    targets.push_back(targets_for(sensor_velocity_S(m, v, w), 15, 4));
    fits.push_back(fit_sensor_velocity(targets.back(), {}));
  }
  const EgoMotionFit ego = fit_ego_motion(targets, fits, X_VS);
  ASSERT_TRUE(ego.valid);
  EXPECT_NEAR(ego.speed_mps, 30.0, 1e-9);
  EXPECT_NEAR(ego.yaw_rate_radps, 0.1, 1e-9);
  EXPECT_EQ(ego.inliers, 30u);
  // Each sensor alone, under the same Ackermann condition, implies the same speed.
  EXPECT_NEAR(speed_from_one_sensor_mps(fits[0], X_VS[0]), 30.0, 1e-9);
  EXPECT_NEAR(speed_from_one_sensor_mps(fits[1], X_VS[1]), 30.0, 1e-9);
}

TEST(DopplerEgoMotion, TrackIntegratesThePoseAndTakesAGivenYawRate) {
  const std::vector<Pose2> X_VS{{3.8, 0.0, 0.0}, {-1.1, 0.0, 3.14159}};
  std::vector<double> t_s;
  std::vector<std::vector<std::vector<DopplerTarget>>> targets;
  for (int k = 0; k < 30; ++k) {
    t_s.push_back(0.1 * k);
    targets.push_back({targets_for(sensor_velocity_S(X_VS[0], 20.0, 0.0), 12, 2),
                       targets_for(sensor_velocity_S(X_VS[1], 20.0, 0.0), 12, 2)});
  }
  targets[5][0].resize(2);  // one cycle with too few targets in one sensor: the other still fits
  const DopplerEgoTrack track = ego_track_from_doppler(t_s, targets, X_VS, {"front", "back"});
  ASSERT_EQ(track.samples.size(), 30u);
  EXPECT_NEAR(track.samples[29].x_m, 20.0 * 2.9, 1e-6);
  EXPECT_NEAR(track.samples[29].y_m, 0.0, 1e-6);
  EXPECT_NEAR(track.samples[12].speed_mps, 20.0, 1e-9);
  EXPECT_EQ(track.report["cycles_fitted"], 30);
  EXPECT_EQ(track.report["yaw_rate_source"], "Doppler");
  EXPECT_NEAR(track.report["speed_difference_mps"]["mean"].get<double>(), 0.0, 1e-9);

  const std::vector<double> yaw_rate(30, 0.05);
  const DopplerEgoTrack turning = ego_track_from_doppler(t_s, targets, X_VS, {"front", "back"}, &yaw_rate);
  EXPECT_NEAR(turning.samples[29].yaw_rad, 0.05 * 2.9, 1e-9);
  EXPECT_NEAR(turning.report["doppler_yaw_rate_minus_used_radps"]["mean"].get<double>(), -0.05, 1e-9);
}

// An imaging radar's aliased Doppler (the Astyx interval [-5.2374, 5.1562), 10.3936 m/s wide):
// 12 m/s forward, stationary points at azimuths 0, 10, ..., 50 deg (elevation 0): range rate
// -12 cos(az) = -12, -11.8177, -11.2763, -10.3923, -9.1925, -7.7135, read wrapped (+10.3936 or
// +20.7872): -1.6064, -1.4241, -0.8827, -10.3923 + 10.3936 = 0.0013, 1.2011, 2.6801.
TEST(DopplerEgoMotion, AnAliasedSpeedIsTheOneThatAlignsEveryAngle) {
  constexpr double kMin = -5.2374, kMax = 5.1562;
  std::vector<DopplerTarget> targets;
  for (int k = 0; k < 60; ++k) {
    const double az = deg_to_rad(10.0 * (k % 6)) * (k % 2 == 0 ? 1.0 : -1.0);
    targets.push_back({az, 0.0, wrap_range_rate_mps(-12.0 * std::cos(az), kMin, kMax)});
  }
  EXPECT_NEAR(targets[0].range_rate_mps, -1.6064, 1e-4);
  EXPECT_NEAR(targets[3].range_rate_mps, 0.0013, 1e-4);
  // 20 movers that agree on nothing: the fit keeps to the stationary world.
  for (int k = 0; k < 20; ++k) targets.push_back({deg_to_rad(3.0 * k - 30.0), 0.0, -5.0 + 0.5 * k});
  const AliasedSpeedFit fit = fit_speed_aliased(targets, 0.0, kMin, kMax);
  ASSERT_TRUE(fit.valid);
  EXPECT_NEAR(fit.speed_mps, 12.0, 0.01);  // a mover within 0.1 m/s of the line pulls a little
  EXPECT_EQ(fit.candidates, 80u);
  EXPECT_GE(fit.inliers, 60u);
  EXPECT_LE(fit.inliers, 62u);  // a mover may fall within 0.1 m/s by chance
  // Standing: every point at 0, speed 0 exactly.
  std::vector<DopplerTarget> standing(30, DopplerTarget{0.2, 0.05, 0.0});
  const AliasedSpeedFit still = fit_speed_aliased(standing, 0.0, kMin, kMax);
  ASSERT_TRUE(still.valid);
  EXPECT_EQ(still.speed_mps, 0.0);
  // Too few points agree: not valid.
  EXPECT_FALSE(fit_speed_aliased(std::vector<DopplerTarget>(5, DopplerTarget{0.2, 0.0, 0.0}), 0.0, kMin, kMax).valid);
}

}  // namespace
}  // namespace rcsim::replay
