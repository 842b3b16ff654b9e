// Doppler aliasing (docs/imaging-radar.md): radial speeds wrapped into the unambiguous interval.
#include "sim/doppler_aliasing.hpp"

#include <gtest/gtest.h>

namespace rcsim {
namespace {

TEST(DopplerAliasing, RadialSpeedsWrapIntoTheUnambiguousInterval) {
  // The Astyx HiRes: [-5.1562, 5.2374), width 10.3936 m/s.
  constexpr double kMin = -5.1562, kMax = 5.2374, kWidth = kMax - kMin;
  EXPECT_DOUBLE_EQ(wrap_range_rate_mps(1.0, kMin, kMax), 1.0);               // inside: unchanged
  EXPECT_NEAR(wrap_range_rate_mps(6.0, kMin, kMax), 6.0 - kWidth, 1e-12);     // -4.3936
  EXPECT_NEAR(wrap_range_rate_mps(-6.0, kMin, kMax), -6.0 + kWidth, 1e-12);   // 4.3936
  EXPECT_NEAR(wrap_range_rate_mps(-30.0, kMin, kMax), -30.0 + 3 * kWidth, 1e-12);  // 1.1808 (30 m/s, 108 km/h)
  EXPECT_NEAR(wrap_range_rate_mps(kMax, kMin, kMax), kMin, 1e-12);            // the upper end is the lower
  EXPECT_DOUBLE_EQ(wrap_range_rate_mps(kMin, kMin, kMax), kMin);
}

TEST(DopplerAliasing, OnlyASensorThatAliasesWrapsItsDetections) {
  Detections d(1);
  d[0].range_rate_mps = 12.0;
  alias_range_rates(ResolutionCell{}, d);  // no interval: unchanged
  EXPECT_DOUBLE_EQ(d[0].range_rate_mps, 12.0);
  ResolutionCell cell;
  cell.unambiguous_min_mps = -5.0;
  cell.unambiguous_max_mps = 5.0;
  alias_range_rates(cell, d);
  EXPECT_NEAR(d[0].range_rate_mps, 2.0, 1e-12);
}

}  // namespace
}  // namespace rcsim
