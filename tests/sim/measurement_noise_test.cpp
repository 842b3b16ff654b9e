// Paper III-A: range and range-rate noise whose variance falls as the amplitude rises.
#include "sim/measurement_noise.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rcsim {
namespace {

TEST(MeasurementNoise, SigmaHalvesPer6dBDownToItsFloor) {
  EXPECT_DOUBLE_EQ(noise_sigma(0.1, 0.02, 1.0), 0.1);  // at the threshold
  EXPECT_NEAR(noise_sigma(0.1, 0.02, std::pow(10.0, -6.0 / 20.0)), 0.0501, 1e-4);
  EXPECT_DOUBLE_EQ(noise_sigma(0.1, 0.02, 0.01), 0.02);  // 40 dB above: the floor
}

TEST(MeasurementNoise, EmpiricalSpreadMatchesSigma) {
  MeasurementNoise noise;  // 0.1 m and 0.15 m/s at threshold
  Rng rng(9);
  const int n = 50000;
  double sum2_range = 0, sum2_rate = 0;
  for (int i = 0; i < n; ++i) {
    Detections d(1);
    d[0].range_m = 10.0;
    d[0].amplitude_db = 12.0;  // 6 dB above the 6 dB threshold: sigma halves
    add_measurement_noise(noise, 6.0, rng, d);
    sum2_range += (d[0].range_m - 10.0) * (d[0].range_m - 10.0);
    sum2_rate += d[0].range_rate_mps * d[0].range_rate_mps;
  }
  EXPECT_NEAR(std::sqrt(sum2_range / n), 0.1 * std::pow(10.0, -6.0 / 20.0), 0.002);
  EXPECT_NEAR(std::sqrt(sum2_rate / n), 0.15 * std::pow(10.0, -6.0 / 20.0), 0.003);
}

}  // namespace
}  // namespace rcsim
