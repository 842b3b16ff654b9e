// Each radar's own clock read off a keyframed recording (replay/profile/sensor_clocks.hpp): a radar
// at 18.2 Hz whose frames a 15 Hz keyframe clock picks (the nearest in time), driving past posts,
// must come back on its own clock; the aiMotive drive's radars too, where the data is.
#include "replay/profile/sensor_clocks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "common/angles.hpp"
#include "common/input_error.hpp"
#include "common/quantile.hpp"
#include "io/recording.hpp"
#include "refusal.hpp"
#include "replay/import/dataset_importer.hpp"
#include "replay/profile/detection_pool.hpp"
#include "replay/profile/frame_matching.hpp"
#include "test_support.hpp"

namespace rcsim::replay::profile::sensor_clocks_test {
namespace {

constexpr double kSpeed_mps = 30.0, kPeriod_s = 0.055, kPhase_s = 0.004, kKeyframe_s = 1.0 / 15.0;

// The radar frame a keyframe picks: the one nearest in time.
int frame_of(int keyframe) { return static_cast<int>(std::lround((keyframe * kKeyframe_s - kPhase_s) / kPeriod_s)); }
double frame_time_s(int frame) { return kPhase_s + kPeriod_s * frame; }

// The ego drives along x at 30 m/s past posts every 7.3 m at y = ±6 m and ±11 m; its one radar
// looks ahead (srr24's ±75°, 40 m suffice at these ranges; amplitudes well above any threshold).
// Every keyframe holds the frame nearest in time, measured at that frame's own time.
Recording keyframed(int keyframes) {
  Recording rec;
  rec.name = "posts";
  rec.cycle_time_s = kKeyframe_s;
  rec.sensors = {{"front", "srr24", 3.7, 0.0, 0.0}};
  rec.sensors[0].reports = ListLevel::detections;
  for (int k = 0; k < keyframes; ++k) {
    const double t_s = k * kKeyframe_s, frame_s = frame_time_s(frame_of(k));
    rec.ego.push_back({t_s, kSpeed_mps * t_s, 0.0, 0.0, kSpeed_mps, 0.0});
    const double x_sensor_m = kSpeed_mps * frame_s + 3.7;
    for (double x_m = 0.0; x_m < 400.0; x_m += 7.3) {
      for (const double y_m : {-11.0, -6.0, 6.0, 11.0}) {
        const double dx_m = x_m - x_sensor_m, range_m = std::hypot(dx_m, y_m), azimuth_rad = std::atan2(y_m, dx_m);
        if (dx_m < 2.0 || range_m > 38.0) continue;
        rec.targets.push_back({t_s, k, 0, -1, range_m, azimuth_rad, -kSpeed_mps * std::cos(azimuth_rad), 30.0});
      }
    }
  }
  return rec;
}

TEST(SensorClocks, ARadarPickedByKeyframesComesBackOnItsOwnClock) {
  const Recording rec = keyframed(60);
  const std::vector<SensorClock> clocks = estimate_sensor_clocks(rec);
  ASSERT_EQ(clocks.size(), 1u);
  const SensorClock& c = clocks[0];
  EXPECT_EQ(c.sensor, "front");
  EXPECT_NEAR(c.period_s, kPeriod_s, 0.0005);
  EXPECT_EQ(c.steps, 59);
  EXPECT_GE(c.steps_matched, 55);
  // 15 Hz keyframes over an 18.2 Hz radar: a frame skipped every 4 to 5 keyframes.
  int skipping = 0;
  for (int k = 0; k + 1 < 60; ++k) skipping += frame_of(k + 1) - frame_of(k) >= 2;
  EXPECT_EQ(c.steps_skipping, skipping);
  // Every frame's time found to within 2 ms up to one shift for all (the clock's phase: the
  // keyframes' offsets' mean, which the nearest frame makes about 0).
  const double shift_s = c.t_s[0] - frame_time_s(frame_of(0));
  EXPECT_LT(std::abs(shift_s), 0.006);
  for (int k = 0; k < 60; ++k) EXPECT_NEAR(c.t_s[static_cast<std::size_t>(k)] - frame_time_s(frame_of(k)), shift_s, 0.002) << k;
  // The keyframes lie within half a period of the frames on either side.
  EXPECT_GT(c.offset_min_s, -0.5 * kPeriod_s - 0.002);
  EXPECT_LT(c.offset_max_s, 0.5 * kPeriod_s + 0.002);
  EXPECT_GT(c.offset_rms_s, 0.010);
}

TEST(SensorClocks, TheRecordingOnItsOwnClocksIsVersion4WithEachTargetAtItsFramesTime) {
  const Recording rec = keyframed(30);
  const std::vector<SensorClock> clocks = estimate_sensor_clocks(rec);
  const Recording own = on_estimated_clocks(rec, clocks);
  EXPECT_EQ(own.clock, Clock::per_sensor);
  ASSERT_EQ(own.cycle_count(), 30);
  EXPECT_NEAR(own.sensors[0].cycle_time_s, clocks[0].period_s, 1e-12);
  ASSERT_EQ(own.targets.size(), rec.targets.size());
  for (const RecordedTarget& t : own.targets) EXPECT_DOUBLE_EQ(t.t_s, clocks[0].t_s[static_cast<std::size_t>(t.cycle)]);
  EXPECT_EQ(own.ego.size(), rec.ego.size());  // the keyframes' ego rows, an ego log of its own rate
  EXPECT_TRUE(own.source.contains("sensor_clocks"));
  // The static world's shift now agrees with the stamps: every matched step within 2 ms of them.
  const DetectionPool pool = pool_detections({&own});
  const std::vector<FramePair> pairs = match_consecutive_cycles(pool, 0.0, {kPi, 1e9});
  ASSERT_GE(pairs.size(), 25u);
  for (const FramePair& p : pairs) {
    EXPECT_NEAR(p.dt_s, own.cycle_t_s(p.next_cycle) - own.cycle_t_s(p.cycle), 0.002) << p.cycle;
  }
}

TEST(SensorClocks, WhatHasNoClockToReadIsRefused) {
  Recording rec = keyframed(30);
  rec.dir = "posts_dir";
  Recording snapshots = rec;
  snapshots.timeline = Timeline::snapshots;
  EXPECT_NE(testing::refusal_of([&] { estimate_sensor_clocks(snapshots); }).find("posts_dir: timeline: single frames"), std::string::npos);
  Recording unknown = rec;
  unknown.ego_motion_known = false;
  EXPECT_NE(testing::refusal_of([&] { estimate_sensor_clocks(unknown); }).find("ego_motion_known"), std::string::npos);
  const Recording own = on_estimated_clocks(rec, estimate_sensor_clocks(rec));
  EXPECT_NE(testing::refusal_of([&] { estimate_sensor_clocks(own); }).find("own clocks already"), std::string::npos);
  // A standing ego: the static world does not move, no step is timed.
  Recording standing = keyframed(30);
  for (EgoSample& e : standing.ego) e.x_m = 0.0, e.speed_mps = 0.0;
  for (RecordedTarget& t : standing.targets) t.range_rate_mps = 0.0;
  const std::string m = testing::refusal_of([&] { estimate_sensor_clocks(standing); });
  EXPECT_NE(m.find("sensor 'front'"), std::string::npos) << m;
}

// The aiMotive radars: about 18 Hz each (docs/importers.md), every step timed, the keyframes up to
// half a period from the frames they stamp.
TEST(SensorClocks, TheAimotiveRadarsOwnClocks) {
  if (!std::filesystem::exists(testing::kAimotiveRaw)) {
    std::cout << "skipped: no real data at " << testing::kAimotiveRaw << '\n';
    GTEST_SKIP();
  }
  const Recording rec = replay::find_dataset_importer("aimotive").import(testing::kAimotiveRaw.string(), {}).recording;
  const std::vector<SensorClock> clocks = estimate_sensor_clocks(rec);
  ASSERT_EQ(clocks.size(), 2u);
  for (const SensorClock& c : clocks) {
    EXPECT_NEAR(c.period_s, 0.0549, 0.0005) << c.sensor;
    EXPECT_GE(c.steps_matched, 45) << c.sensor;
    EXPECT_LT(c.step_residual_rms_s, 0.002) << c.sensor;
    EXPECT_GE(c.steps_skipping, 8) << c.sensor;
    EXPECT_GT(c.offset_max_s - c.offset_min_s, 0.045) << c.sensor;  // the stamping's ±30 ms
    EXPECT_LT(c.offset_max_s - c.offset_min_s, 0.065) << c.sensor;
  }
  // Stamped by their keyframes, the radars' steps disagree with the static world by the jitter;
  // on their own clocks by about a millisecond (the median: a rare false match of the guard rail's
  // repeating posts is off by a period or more either way).
  const auto disagreement_s = [](const Recording& r) {
    const DetectionPool pool = pool_detections({&r});
    std::vector<double> d;
    for (const FramePair& p : match_consecutive_cycles(pool, 0.0, {kPi, 1e9})) {
      d.push_back(std::abs(p.dt_s - (r.cycle_t_s(p.next_cycle) - r.cycle_t_s(p.cycle))));
    }
    EXPECT_GE(d.size(), 90u);
    return median(d);
  };
  const double keyframed_s = disagreement_s(rec), own_s = disagreement_s(on_estimated_clocks(rec, clocks));
  std::cout << "aiMotive: |timed step - stamps| median " << 1e3 * keyframed_s << " ms keyframed, " << 1e3 * own_s
            << " ms on own clocks\n";
  EXPECT_GT(keyframed_s, 0.010);
  EXPECT_LT(own_s, 0.0015);
}

}  // namespace
}  // namespace rcsim::replay::profile::sensor_clocks_test
