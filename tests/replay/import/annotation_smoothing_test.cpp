#include "replay/import/annotation_smoothing.hpp"

#include <cmath>
#include <gtest/gtest.h>

#include "common/rng.hpp"

namespace rcsim::replay {
namespace {

TEST(AnnotationSmoothing, ReproducesAQuadraticExactly) {
  std::vector<double> t, y;
  for (int k = 0; k < 50; ++k) {
    t.push_back(0.04 * k);
    y.push_back(1.0 + 2.0 * t.back() - 0.5 * t.back() * t.back());
  }
  const auto fits = smooth_local_quadratic(t, y, 0.5);
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR(fits[i].value, y[i], 1e-9);
    EXPECT_NEAR(fits[i].slope_per_s, 2.0 - t[i], 1e-8);
  }
}

TEST(AnnotationSmoothing, OneDegreeOfYawNoiseDoesNotBecomeAWildYawRate) {
  // 25 Hz annotation of a steady turn at 0.2 rad/s with 1° of noise: central differences would
  // give about 0.3 rad/s of noise; the ±0.5 s local fit keeps it near 0.02 rad/s.
  Rng rng(3, 0);
  std::vector<double> t, yaw;
  for (int k = 0; k < 250; ++k) {
    t.push_back(0.04 * k);
    yaw.push_back(0.2 * t.back() + 0.01745 * rng.normal());
  }
  const auto fits = smooth_local_quadratic(t, yaw, 0.5);
  double raw_sq = 0.0, fit_sq = 0.0, bias = 0.0;
  for (std::size_t i = 1; i + 1 < t.size(); ++i) {
    const double central = (yaw[i + 1] - yaw[i - 1]) / (t[i + 1] - t[i - 1]);
    raw_sq += std::pow(central - 0.2, 2);
    fit_sq += std::pow(fits[i].slope_per_s - 0.2, 2);
    bias += fits[i].slope_per_s - 0.2;
  }
  const double n = static_cast<double>(t.size() - 2);
  EXPECT_GT(std::sqrt(raw_sq / n), 0.25);
  EXPECT_LT(std::sqrt(fit_sq / n), 0.06);
  EXPECT_LT(std::abs(bias / n), 0.01);
}

TEST(AnnotationSmoothing, ShortAndZeroWindowsKeepTheData) {
  const std::vector<double> t{0.0, 1.0}, y{3.0, 5.0};
  const auto none = smooth_local_quadratic(t, y, 0.0);
  EXPECT_EQ(none[1].value, 5.0);
  const auto line = smooth_local_quadratic(t, y, 2.0);  // two points: a straight line
  EXPECT_NEAR(line[0].value, 3.0, 1e-12);
  EXPECT_NEAR(line[0].slope_per_s, 2.0, 1e-12);
  const auto single = smooth_local_quadratic(std::vector<double>{1.0}, std::vector<double>{7.0}, 1.0);
  EXPECT_EQ(single[0].value, 7.0);
  EXPECT_EQ(single[0].slope_per_s, 0.0);
}

}  // namespace
}  // namespace rcsim::replay
