// The pooled detections of `rcsim profile derive` (replay/profile/detection_pool.hpp): cycles laid
// out sensor after sensor and recording after recording, the stationary world found by Kellner's
// fit (and its aliased form) on a sensor driving at a known speed, and the refusals.
#include "replay/profile/detection_pool.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "common/range_rate_wrap.hpp"

namespace rcsim::replay::profile::detection_pool_test {

// A recording of `sensors` detection sensors of `type`, `cycles` cycles 0.05 s apart with the
// ego 1 m further along x each; `targets` per cycle and sensor at ranges range_m(i), azimuths
// 0.01 (i % 7) rad.
Recording made_up(int cycles, int targets, ListLevel reports, double (*range_m)(int), int sensors = 1,
                  const std::string& type = "aimotive_lrr") {
  Recording r;
  r.dir = "made_up";
  r.name = "made_up";
  r.cycle_time_s = 0.05;
  for (int s = 0; s < sensors; ++s) r.sensors.push_back({std::string("s").append(std::to_string(s)), type, 3.6, 0.5 * s, 0.1 * s, reports});
  for (int k = 0; k < cycles; ++k) {
    r.ego.push_back({0.05 * k, 1.0 * k, 0.0, 0.0, 0.0, 0.0});
    for (int s = 0; s < sensors; ++s) {
      for (int i = 0; i < targets; ++i) {
        RecordedTarget t;
        t.t_s = 0.05 * k, t.cycle = k, t.sensor = s, t.range_m = range_m(i), t.azimuth_rad = 0.01 * (i % 7), t.amplitude_db = 20.0 + i % 5;
        r.targets.push_back(t);
      }
    }
  }
  return r;
}

double spread(int i) { return 10.0 + i; }

std::string refusal_of(const std::vector<const Recording*>& recordings) {
  try {
    pool_detections(recordings);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no refusal";
}

TEST(ProfileDetectionPool, CyclesSensorAfterSensorRecordingAfterRecording) {
  // Two sensors by 3 cycles by 20, then a second recording of single frames, 2 cycles: 10 sensor
  // cycles, 6 x 20 + 4 x 20 = 200 detections.
  const Recording drive = made_up(3, 20, ListLevel::detections, spread, 2);
  Recording frames = made_up(2, 20, ListLevel::detections, spread, 2);
  frames.timeline = Timeline::snapshots;
  frames.cycle_time_s = 0.1;
  const DetectionPool pool = pool_detections({&drive, &frames});
  EXPECT_EQ(pool.recordings, 2);
  EXPECT_EQ(pool.detections, 200);
  EXPECT_EQ(pool.sensor_type, "aimotive_lrr");
  EXPECT_EQ(pool.amplitude_unit, AmplitudeUnit::snr_db);
  EXPECT_FALSE(pool.range_rate_interval_mps.has_value());
  EXPECT_TRUE(pool.snapshots);                       // some recording is single frames
  EXPECT_DOUBLE_EQ(pool.recorded_cycle_time_s, 0.05);  // the first's clock
  ASSERT_EQ(pool.cycles.size(), 10u);
  // Index = first of the recording + cycle x sensors + sensor.
  const PooledCycle& c = pool.cycles[5];  // drive, cycle 2, sensor 1
  EXPECT_EQ(c.recording, 0);
  EXPECT_EQ(c.cycle, 2);
  EXPECT_EQ(c.sensor, 1);
  EXPECT_DOUBLE_EQ(c.t_s, 0.1);
  EXPECT_DOUBLE_EQ(c.X_WV.x_m, 2.0);
  EXPECT_DOUBLE_EQ(c.X_VS.y_m, 0.5);
  EXPECT_DOUBLE_EQ(c.X_VS.yaw_rad, 0.1);
  ASSERT_EQ(c.detections.size(), 20u);
  EXPECT_DOUBLE_EQ(c.detections[3].range_m, 13.0);
  EXPECT_DOUBLE_EQ(c.detections[3].azimuth_rad, 0.03);
  EXPECT_DOUBLE_EQ(c.detections[3].amplitude_db, 23.0);
  EXPECT_TRUE(std::isnan(c.detections[3].rcs_dbsm));
  EXPECT_EQ(pool.cycles[6].recording, 1);
  EXPECT_EQ(pool.cycles[6].cycle, 0);
  // All targets at radial speed 0 over 0.06 rad: a standing sensor; each is stationary, none off it.
  EXPECT_TRUE(c.valid_fit);
  EXPECT_NEAR(c.v_S_S.norm(), 0.0, 1e-9);
  for (const PooledDetection& d : c.detections) EXPECT_NEAR(d.stationary_residual_mps, 0.0, 1e-9);
}

// One sensor driving at 8 m/s along its axis: 50 stationary targets over +-0.5 rad (radial speed
// -8 cos az), and 10 moving ones at -3 m/s; two cycles. `wrap`: as a radar of [-5, 5) m/s reports them.
Recording driving_past(bool wrap) {
  Recording r;
  r.dir = "driving";
  r.cycle_time_s = 0.05;
  r.sensors.push_back({"front", "aimotive_lrr", 0.0, 0.0, 0.0, ListLevel::detections});
  if (wrap) r.sensors[0].range_rate_interval_mps = RangeRateInterval{-5.0, 5.0};
  for (int k = 0; k < 2; ++k) {
    r.ego.push_back({0.05 * k, 0.4 * k, 0.0, 0.0, 8.0, 0.0});
    for (int i = 0; i < 60; ++i) {
      RecordedTarget t;
      t.cycle = k, t.range_m = 10.0 + i, t.azimuth_rad = -0.5 + (i % 50) * (1.0 / 49.0), t.amplitude_db = 20.0;
      t.range_rate_mps = i < 50 ? -8.0 * std::cos(t.azimuth_rad) : -3.0;
      if (wrap) t.range_rate_mps = wrap_range_rate_mps(t.range_rate_mps, -5.0, 5.0);
      r.targets.push_back(t);
    }
  }
  return r;
}

TEST(ProfileDetectionPool, TheStationaryWorldOfASensorDrivingAtAKnownSpeed) {
  for (const bool wrap : {false, true}) {
    const Recording r = driving_past(wrap);
    const DetectionPool pool = pool_detections({&r});
    ASSERT_EQ(pool.cycles.size(), 2u);
    EXPECT_EQ(pool.range_rate_interval_mps.has_value(), wrap);
    for (const PooledCycle& c : pool.cycles) {
      ASSERT_TRUE(c.valid_fit) << wrap;
      // The sensor's velocity over the ground: (8, 0) m/s in its frame.
      EXPECT_NEAR(c.v_S_S.x(), 8.0, 1e-6) << wrap;
      EXPECT_NEAR(c.v_S_S.y(), 0.0, 1e-6) << wrap;
      for (std::size_t i = 0; i < c.detections.size(); ++i) {
        EXPECT_EQ(c.detections[i].stationary(), i < 50) << wrap << " " << i;
        if (i < 50) {
          EXPECT_LT(c.detections[i].stationary_residual_mps, 1e-6) << wrap << " " << i;
        }
      }
    }
  }
}

// Moved from tests/replay/profile/profile_derivation_test.cpp (ProfileDerive): four of its five
// refusals are the pool's; now asked of pool_detections directly.
TEST(ProfileDetectionPool, RefusesWhatAProfileCannotComeFromNamingWhatIsMissing) {
  const auto one_range = [](int) { return 42.0; };
  const auto expect_refused = [](const Recording& r, const std::string& words) {
    const std::string message = refusal_of({&r});
    EXPECT_NE(message.find(words), std::string::npos) << message;
  };
  expect_refused(made_up(10, 50, ListLevel::tracks, spread), "reports tracks; a profile is derived from raw detections");
  expect_refused(made_up(1, 500, ListLevel::detections, spread), "1 sensor cycle(s): a profile needs at least 2");
  expect_refused(made_up(10, 5, ListLevel::detections, spread), "50 detection(s): a profile needs at least 100");
  expect_refused(made_up(10, 50, ListLevel::detections, one_range), "every detection lies at one range");
}

TEST(ProfileDetectionPool, RefusesTwoKindsOfRadarNamingTheRecordingAndSensor) {
  const Recording lrr = made_up(3, 50, ListLevel::detections, spread);
  const Recording srr = made_up(3, 50, ListLevel::detections, spread, 1, "srr24");
  EXPECT_EQ(refusal_of({&lrr, &srr}),
            "made_up: sensor s0: is of type \"srr24\", the first sensor of \"aimotive_lrr\": one profile is derived from "
            "one kind of radar (give its recordings only)");
  Recording relative = lrr;
  relative.sensors[0].amplitude_unit = AmplitudeUnit::relative_db;
  EXPECT_NE(refusal_of({&lrr, &relative}).find("made_up: sensor s0: is of type \"aimotive_lrr\""), std::string::npos);
  // The counts are over all recordings: two of 1 cycle and 50 detections each pass.
  const Recording half = made_up(1, 50, ListLevel::detections, spread);
  EXPECT_EQ(pool_detections({&half, &half}).detections, 100);
  EXPECT_EQ(refusal_of({&half}), "made_up: 1 sensor cycle(s): a profile needs at least 2");
}

}  // namespace rcsim::replay::profile::detection_pool_test
