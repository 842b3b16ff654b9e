// The fitted stationary background (paper VI): drawn as its density says, each target a stationary
// reflector.
#include "sim/background.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rcsim {
namespace {


SensorKinematics moving_sensor() {
  SensorKinematics k;
  k.X_WS = Pose2{0.0, 0.0, 0.0};
  k.v_WS_W = Vec2(30.0, 0.0);
  return k;
}

TEST(StationaryBackground, DrawsFollowTheDensityAndAreStationary) {
  const StationaryBackground b = testing::hand_background();
  Rng rng(5, 0);
  constexpr int kCycles = 2000;
  long long count = 0, right_bin = 0;
  double amplitude_sum_db = 0.0;
  for (int c = 0; c < kCycles; ++c) {
    Detections d;
    add_stationary_background(b, moving_sensor(), rng, d);
    for (const Detection& t : d) {
      ++count;
      EXPECT_GE(t.range_m, 10.0);
      EXPECT_LT(t.range_m, 20.0);
      EXPECT_GE(t.azimuth_rad, -0.1);
      EXPECT_LT(t.azimuth_rad, 0.1);
      right_bin += t.azimuth_rad >= 0.0;
      // A stationary point seen from a sensor moving at 30 m/s along x: -30 cos(az).
      EXPECT_NEAR(t.range_rate_mps, -30.0 * std::cos(t.azimuth_rad), 1e-9);
      EXPECT_GE(t.amplitude_db, 10.0);
      EXPECT_LE(t.amplitude_db, 20.0);
      EXPECT_EQ(t.object_index, -1);
      amplitude_sum_db += t.amplitude_db;
    }
  }
  // Poisson(20) over 2000 cycles: the mean within 5 sigma (0.5); 3/4 in the right bin; amplitudes
  // uniform over 10..20 dB, mean 15.
  EXPECT_NEAR(static_cast<double>(count) / kCycles, 20.0, 0.5);
  EXPECT_NEAR(static_cast<double>(right_bin) / static_cast<double>(count), 0.75, 0.02);
  EXPECT_NEAR(amplitude_sum_db / static_cast<double>(count), 15.0, 0.1);
}

TEST(StationaryBackground, EmptyDrawsNothing) {
  Rng rng(5, 0), untouched(5, 0);
  Detections d;
  add_stationary_background(StationaryBackground{}, moving_sensor(), rng, d);
  EXPECT_TRUE(d.empty());
  EXPECT_EQ(rng.next_u64(), untouched.next_u64());
}

}  // namespace
}  // namespace rcsim
