// Quantiles once (common/quantile.hpp): linear interpolation between order statistics
// (Hyndman & Fan type 7, numpy's default), by hand.
#include "common/quantile.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rcsim {
namespace {

TEST(Quantile, InterpolatesBetweenOrderStatisticsByHand) {
  // {1, 2, 4, 8}: h = q (n - 1); q = 0.5 -> h = 1.5, 2 + 0.5 (4 - 2) = 3; q = 0.9 -> h = 2.7,
  // 4 + 0.7 (8 - 4) = 6.8; the ends are the extremes, q outside [0, 1] clamped.
  const std::vector<double> v{8.0, 1.0, 4.0, 2.0};
  EXPECT_DOUBLE_EQ(quantile(v, 0.5), 3.0);
  EXPECT_DOUBLE_EQ(quantile(v, 0.9), 6.8);
  EXPECT_DOUBLE_EQ(quantile(v, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(quantile(v, 1.5), 8.0);
  EXPECT_DOUBLE_EQ(quantile_of_sorted({1.0, 2.0, 4.0, 8.0}, 0.25), 1.75);  // h = 0.75
  EXPECT_DOUBLE_EQ(median({1.0, 2.0}), 1.5);
  EXPECT_DOUBLE_EQ(median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_TRUE(std::isnan(median({})));
}

}  // namespace
}  // namespace rcsim
