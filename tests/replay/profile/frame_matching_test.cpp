// Stationary detections matched from a cycle to the next (replay/profile/frame_matching.hpp), on a
// sensor driving past a grid of posts at a known speed: the time step from the world's shift, who
// is seen again, the range residuals, and which cycles are never paired.
#include "replay/profile/frame_matching.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/angles.hpp"

namespace rcsim::replay::profile::frame_matching_test {

constexpr double kSpeed_mps = 10.0;
constexpr double kThreshold_db = 15.0;

// 12 posts at x 20, 23, 26, 29 m and y -4, 0, 4 m: 3 m apart along the motion, more than the
// 0.5-m gate plus a cycle's 0.5 m of travel.
std::vector<Vec2> posts() {
  std::vector<Vec2> out;
  for (const double x_m : {20.0, 23.0, 26.0, 29.0}) {
    for (const double y_m : {-4.0, 0.0, 4.0}) out.emplace_back(x_m, y_m);
  }
  return out;
}

// Cycle k of a sensor driving along x at 10 m/s (0.05 s a cycle), seeing post i with amplitude
// 20 + i dB (stationary, its radial speed the static world's); posts with seen[i] false are
// missed; range_offset_m adds to post 0's range, rate_offset_mps to its radial speed.
PooledCycle cycle_at(int k, const std::vector<bool>& seen, double range_offset_m = 0.0, int sensor = 0, int recording = 0,
                     double rate_offset_mps = 0.0) {
  PooledCycle c;
  c.recording = recording, c.sensor = sensor, c.cycle = k, c.sensor_cycle = k, c.t_s = 0.05 * k;
  c.X_WV = {0.5 * k, 0.0, 0.0};
  c.v_S_S = Vec2(kSpeed_mps, 0.0);
  c.valid_fit = true;
  const std::vector<Vec2> world = posts();
  for (std::size_t i = 0; i < world.size(); ++i) {
    if (!seen[i]) continue;
    const Vec2 p = world[i] - Vec2(0.5 * k, 0.0);
    PooledDetection d;
    d.range_m = p.norm() + (i == 0 ? range_offset_m : 0.0), d.azimuth_rad = std::atan2(p.y(), p.x());
    d.amplitude_db = 20.0 + static_cast<double>(i), d.stationary_residual_mps = 0.0;
    d.range_rate_mps = -kSpeed_mps * std::cos(d.azimuth_rad) + (i == 0 ? rate_offset_mps : 0.0);
    c.detections.push_back(d);
  }
  // A moving car beside the posts: not stationary (NaN residual), never matched.
  PooledDetection car;
  car.range_m = 24.0 + 0.1 * k, car.azimuth_rad = 0.05, car.amplitude_db = 30.0;
  c.detections.push_back(car);
  return c;
}

const std::vector<bool> kAll(12, true);
const ViewLimits kView{deg_to_rad(60.0), 100.0};

TEST(ProfileFrameMatching, TheStepTheRedetectionsAndTheResidualsOfADrivePastPosts) {
  // Cycle 1 misses post 11; cycle 2 sees post 0 0.1 m too far and 0.22 m/s too fast.
  std::vector<bool> without_11 = kAll;
  without_11[11] = false;
  DetectionPool pool;
  pool.cycles = {cycle_at(0, kAll), cycle_at(1, without_11), cycle_at(2, kAll, 0.1, 0, 0, 0.22)};
  const std::vector<FramePair> pairs = match_consecutive_cycles(pool, kThreshold_db, kView);
  ASSERT_EQ(pairs.size(), 2u);
  // Every post moved 0.5 m against a speed of 10 m/s: 0.05 s (the median of the posts' own shifts).
  EXPECT_NEAR(pairs[0].dt_s, 0.05, 1e-9);
  EXPECT_NEAR(pairs[1].dt_s, 0.05, 1e-9);
  // Cycle 0 -> 1: all 12 posts inside the view, post 11 (margin 20 + 11 - 15 = 16 dB) not seen again.
  ASSERT_EQ(pairs[0].redetections.size(), 12u);
  for (std::size_t i = 0; i < 12; ++i) {
    EXPECT_DOUBLE_EQ(pairs[0].redetections[i].margin_db, 5.0 + static_cast<double>(i));
    EXPECT_EQ(pairs[0].redetections[i].seen, i != 11) << i;
  }
  ASSERT_EQ(pairs[0].matches.size(), 11u);
  for (const MatchedDetection& m : pairs[0].matches) {
    EXPECT_NEAR(m.range_m, 0.0, 1e-9);
    EXPECT_NEAR(m.range_rate_mps, 0.0, 1e-9);
  }
  // Cycle 1 -> 2: the 11 posts cycle 1 saw, all seen again; post 0's range 0.1 m long and its
  // radial speed 0.22 m/s fast (about the matches' median, 0: 0.22), at its margins (5 dB both).
  ASSERT_EQ(pairs[1].redetections.size(), 11u);
  for (const Redetection& r : pairs[1].redetections) EXPECT_TRUE(r.seen);
  ASSERT_EQ(pairs[1].matches.size(), 11u);
  EXPECT_NEAR(pairs[1].matches[0].range_m, 0.1, 1e-9);
  EXPECT_NEAR(pairs[1].matches[0].range_rate_mps, 0.22, 1e-9);
  EXPECT_DOUBLE_EQ(pairs[1].matches[0].margin_earlier_db, 5.0);
  EXPECT_DOUBLE_EQ(pairs[1].matches[0].margin_later_db, 5.0);
  for (std::size_t i = 1; i < 11; ++i) {
    EXPECT_NEAR(pairs[1].matches[i].range_m, 0.0, 1e-9) << i;
    EXPECT_NEAR(pairs[1].matches[i].range_rate_mps, 0.0, 1e-9) << i;
  }
}

TEST(ProfileFrameMatching, OnlyPostsWellInsideTheViewCountAsRedetections) {
  // Counted where the post is predicted in the later cycle, 0.5 m nearer: x 19.5, 22.5, 25.5,
  // 28.5 m. A view of +-20 deg (0.9 of it: 18 deg) holds all; one of +-12 deg (10.8 deg) leaves
  // out the two at (19.5, +-4) m, atan(4 / 19.5) = 11.6 deg, and keeps (22.5, +-4) m at 10.1 deg.
  DetectionPool pool;
  pool.cycles = {cycle_at(0, kAll), cycle_at(1, kAll)};
  EXPECT_EQ(match_consecutive_cycles(pool, kThreshold_db, {deg_to_rad(20.0), 100.0})[0].redetections.size(), 12u);
  EXPECT_EQ(match_consecutive_cycles(pool, kThreshold_db, {deg_to_rad(12.0), 100.0})[0].redetections.size(), 10u);
  // Nor beyond 0.9 of the maximum range: 0.9 x 28 m = 25.2 m keeps the 6 at x 19.5 and 22.5 m
  // (at most 22.85 m away) and leaves out those at 25.5 m and beyond.
  const std::vector<FramePair> near = match_consecutive_cycles(pool, kThreshold_db, {deg_to_rad(60.0), 28.0});
  EXPECT_EQ(near[0].redetections.size(), 6u);
  EXPECT_EQ(near[0].matches.size(), 12u);  // the matches take every one
}

// The largest period of which the steps are whole multiples: 55 ms from steps of one and two
// periods with 1-ms noise, its least-squares value; none when the steps share no period.
TEST(ProfileFrameMatching, TheFundamentalPeriodOfStepsSkippingFrames) {
  const std::vector<double> steps_s{0.055, 0.056, 0.054, 0.110, 0.055, 0.109, 0.055, 0.055, 0.111, 0.054, 0.056};
  // sum(k d) / sum(k^2) with k = 1, 1, 1, 2, 1, 2, 1, 1, 2, 1, 1: 1.155 / 21.
  const std::optional<double> period_s = fundamental_period(steps_s);
  ASSERT_TRUE(period_s.has_value());
  EXPECT_NEAR(*period_s, 1.155 / 21.0, 1e-12);
  EXPECT_FALSE(fundamental_period({0.05, 0.0731, 0.0889, 0.0613, 0.0517, 0.0977, 0.0703, 0.0571, 0.0823, 0.0659}).has_value());
}

TEST(ProfileFrameMatching, WhatIsNeverPaired) {
  // Two sensors, cycles held sensor after sensor: each paired with its own next cycle only.
  DetectionPool two;
  two.cycles = {cycle_at(0, kAll, 0.0, 0), cycle_at(0, kAll, 0.0, 1), cycle_at(1, kAll, 0.0, 0), cycle_at(1, kAll, 0.0, 1)};
  EXPECT_EQ(match_consecutive_cycles(two, kThreshold_db, kView).size(), 2u);
  // Sensors on their own clocks (recording v4): the cycles numbered across both sensors, each
  // sensor's next cycle by its own count; the pair says whose cycles it joined.
  DetectionPool own = two;
  for (std::size_t i = 0; i < own.cycles.size(); ++i) own.cycles[i].cycle = static_cast<int>(i);
  const std::vector<FramePair> own_pairs = match_consecutive_cycles(own, kThreshold_db, kView);
  ASSERT_EQ(own_pairs.size(), 2u);
  EXPECT_EQ(own_pairs[0].sensor, 0);
  EXPECT_EQ(own_pairs[0].cycle, 0);
  EXPECT_EQ(own_pairs[0].next_cycle, 2);
  EXPECT_EQ(own_pairs[1].next_cycle, 3);
  EXPECT_NEAR(own_pairs[1].dt_s, 0.05, 1e-9);
  // Single frames: none.
  DetectionPool snapshots = two;
  snapshots.snapshots = true;
  EXPECT_TRUE(match_consecutive_cycles(snapshots, kThreshold_db, kView).empty());
  // A cycle without a stationary fit; 4 stationary detections (fewer than 5); a gap of a cycle;
  // the next recording's first cycle: none.
  DetectionPool unfit;
  unfit.cycles = {cycle_at(0, kAll), cycle_at(1, kAll)};
  unfit.cycles[1].valid_fit = false;
  EXPECT_TRUE(match_consecutive_cycles(unfit, kThreshold_db, kView).empty());
  std::vector<bool> four(12, false);
  four[0] = four[1] = four[2] = four[3] = true;
  DetectionPool sparse;
  sparse.cycles = {cycle_at(0, kAll), cycle_at(1, four)};
  EXPECT_TRUE(match_consecutive_cycles(sparse, kThreshold_db, kView).empty());
  DetectionPool skipped;
  skipped.cycles = {cycle_at(0, kAll), cycle_at(2, kAll)};
  EXPECT_TRUE(match_consecutive_cycles(skipped, kThreshold_db, kView).empty());
  DetectionPool two_recordings;
  two_recordings.cycles = {cycle_at(0, kAll, 0.0, 0, 0), cycle_at(1, kAll, 0.0, 0, 1)};
  EXPECT_TRUE(match_consecutive_cycles(two_recordings, kThreshold_db, kView).empty());
}

}  // namespace rcsim::replay::profile::frame_matching_test
