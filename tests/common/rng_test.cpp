#include "common/rng.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rcsim {
namespace {

TEST(Rng, SameSeedSameStreamOtherSeedOrStreamDifferent) {
  Rng a(42, 0), b(42, 0), c(43, 0), d(42, 1);
  for (int i = 0; i < 100; ++i) {
    const auto x = a.next_u64();
    EXPECT_EQ(x, b.next_u64());
    EXPECT_NE(x, c.next_u64());
    EXPECT_NE(x, d.next_u64());
  }
}

TEST(Rng, NormalHasUnitMomentsAndPoissonItsMean) {
  Rng rng(5);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = rng.normal();
    sum += x;
    sum2 += x * x;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(sum2 / n, 1.0, 0.015);
  long long events = 0;
  for (int i = 0; i < n; ++i) events += rng.poisson(0.3);
  EXPECT_NEAR(static_cast<double>(events) / n, 0.3, 0.005);
  for (int i = 0; i < 1000; ++i) {
    const double u = rng.uniform01();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
  }
}

}  // namespace
}  // namespace rcsim
