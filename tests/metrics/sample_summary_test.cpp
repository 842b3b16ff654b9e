// Bounded sample summaries for the distribution distances: exact up to their capacity, binned
// beyond with stated error bounds that hold.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "metrics/sample_summary.hpp"

namespace rcsim::metrics {
namespace {

TEST(SampleSummary, WithinCapacityTheDistancesAreThoseOfTheSamples) {
  SampleSummary a(0.01), b(0.01);
  std::vector<double> xa, xb;
  std::mt19937_64 rng(3);
  std::normal_distribution<float> n(10.0f, 2.0f);
  for (int i = 0; i < 5000; ++i) {
    const float u = n(rng), v = n(rng) + 0.3f;
    a.add(u);
    b.add(v);
    xa.push_back(u);
    xb.push_back(v);
  }
  const DistributionDistance s = distribution_distance(a, b), e = distribution_distance(xa, xb);
  EXPECT_TRUE(a.exact());
  EXPECT_EQ(s.wasserstein1, e.wasserstein1);
  EXPECT_EQ(s.kolmogorov_smirnov, e.kolmogorov_smirnov);
  EXPECT_EQ(s.wasserstein1_bound, 0.0);
}

TEST(SampleSummary, BeyondCapacityTheBinnedDistancesAreWithinTheirBoundsInBoundedMemory) {
  const std::size_t n = SampleSummary::kExactCapacity + 100'000;
  for (const double width : {0.01, 0.1}) {
    SampleSummary a(width), b(width);
    std::vector<double> xa, xb;
    std::mt19937_64 rng(7);
    std::normal_distribution<float> near(30.0f, 8.0f);
    std::uniform_real_distribution<float> far(0.0f, 150.0f);
    for (std::size_t i = 0; i < n; ++i) {
      const float u = near(rng), v = i % 3 == 0 ? far(rng) : near(rng) + 0.5f;
      a.add(u);
      b.add(v);
      xa.push_back(u);
      xb.push_back(v);
    }
    EXPECT_FALSE(a.exact());
    EXPECT_EQ(a.size(), n);
    const DistributionDistance s = distribution_distance(a, b), e = distribution_distance(xa, xb);
    EXPECT_EQ(s.wasserstein1_bound, width);
    EXPECT_LE(std::abs(s.wasserstein1 - e.wasserstein1), s.wasserstein1_bound) << width;
    EXPECT_LE(std::abs(s.kolmogorov_smirnov - e.kolmogorov_smirnov), s.kolmogorov_smirnov_bound + 1e-12) << width;
    EXPECT_GT(e.wasserstein1, 10.0 * width);  // the test tells something
    // 150 m in bins of 1 cm: 15,000 bins of 8 bytes, whatever the number of samples.
    EXPECT_LE(a.memory_bytes() + b.memory_bytes(), 2 * 8 * (200.0 / width) + 1024);
  }
}

TEST(SampleSummary, HugeOrNonFiniteValuesLandInTheEndBinsInsteadOfGrowingWithoutBound) {
  SampleSummary a(0.01);
  for (std::size_t i = 0; i <= SampleSummary::kExactCapacity; ++i) a.add(static_cast<float>(i % 100));
  a.add(1e30f);
  a.add(-1e30f);
  EXPECT_LE(a.memory_bytes(), SampleSummary::kMaxBins * 8 + 1024);
  SampleSummary b(0.01);
  b.add(5.0f);
  const DistributionDistance d = distribution_distance(a, b);
  EXPECT_TRUE(std::isfinite(d.wasserstein1));
}

}  // namespace
}  // namespace rcsim::metrics
