#include "metrics/distribution_distance.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace rcsim::metrics {
namespace {

TEST(DistributionDistance, IdenticalSamplesAreZeroApart) {
  const auto d = distribution_distance({3, 1, 2}, {2, 3, 1});
  EXPECT_EQ(d.wasserstein1, 0.0);
  EXPECT_EQ(d.kolmogorov_smirnov, 0.0);
}

TEST(DistributionDistance, ShiftedPointMassesAreTheShiftApart) {
  const auto d = distribution_distance({0.0}, {1.5});
  EXPECT_DOUBLE_EQ(d.wasserstein1, 1.5);
  EXPECT_DOUBLE_EQ(d.kolmogorov_smirnov, 1.0);
}

TEST(DistributionDistance, HandCaseWithUnequalSizes) {
  // F_a = 1/2 on [0, 2), F_b = 0 on [0, 1) and 1 on [1, 2): area 0.5 + 0.5, largest gap 0.5.
  const auto d = distribution_distance({0.0, 2.0}, {1.0});
  EXPECT_DOUBLE_EQ(d.wasserstein1, 1.0);
  EXPECT_DOUBLE_EQ(d.kolmogorov_smirnov, 0.5);
  EXPECT_EQ(d.n_recorded, 2);
  EXPECT_EQ(d.n_simulated, 1);
}

TEST(DistributionDistance, EmptySampleGivesNaN) {
  EXPECT_TRUE(std::isnan(distribution_distance({}, {1.0}).wasserstein1));
  EXPECT_TRUE(std::isnan(distribution_distance({1.0}, {}).kolmogorov_smirnov));
}

}  // namespace
}  // namespace rcsim::metrics
