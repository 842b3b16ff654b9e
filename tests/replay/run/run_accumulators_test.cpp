// The run's figures from two hand-made cycles: means over sensor cycles, residuals over the
// assigned pairs only, merge counts, and one distribution distance; the object targets' offsets
// as distributions.
#include "replay/run/run_accumulators.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rcsim::replay {
namespace {

TEST(RunAccumulators, MeansOverCyclesAndResidualsOverAssignedPairs) {
  RunAccumulators acc;
  CycleComparison a;
  a.recorded = {ComparedTarget{.range_m = 10.0, .azimuth_rad = 0.1, .range_rate_mps = -1.0, .amplitude_db = 3.0, .match = 0},
                ComparedTarget{.range_m = 30.0}};
  a.simulated = {ComparedTarget{.range_m = 10.3, .azimuth_rad = 0.05, .range_rate_mps = -1.4, .amplitude_db = 2.0, .match = 0}};
  a.gospa.gospa_m = 1.0;
  a.gospa.ospa_m = 0.5;
  a.merge_matched = 1;
  acc.add_cycle(a, 2, 1);
  CycleComparison b;  // nothing reported, GOSPA 3
  b.gospa.gospa_m = 3.0;
  acc.add_cycle(b, 0, 0);
  ReplaySummary s;
  acc.finish(s);
  EXPECT_EQ(s.targets_recorded, 2);
  EXPECT_EQ(s.targets_simulated, 1);
  EXPECT_EQ(s.targets_matched, 1);
  EXPECT_DOUBLE_EQ(s.gospa_mean_m, 2.0);
  EXPECT_DOUBLE_EQ(s.ospa_mean_m, 0.25);
  EXPECT_NEAR(s.residual_range_rms_m, 0.3, 1e-12);
  EXPECT_NEAR(s.residual_azimuth_rms_rad, 0.05, 1e-12);
  EXPECT_NEAR(s.residual_range_rate_rms_mps, 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(s.residual_amplitude_mean_db, -1.0);
  EXPECT_EQ(s.merge_artefacts_recorded, 2);
  EXPECT_EQ(s.merge_artefacts_simulated, 1);
  EXPECT_EQ(s.merge_artefacts_matched, 1);
  ASSERT_EQ(s.distances.size(), 10u);  // five of all targets, three of the background, two object offsets
  EXPECT_EQ(s.distances[4].quantity, "targets_per_cycle");
  // Counts per cycle: recorded {2, 0}, simulated {1, 0}: W1 = 0.5 (half the mass moved by 1).
  EXPECT_NEAR(s.distances[4].distance.wasserstein1, 0.5, 1e-6);
  // No object target on either side: the offsets' distances are not known (NaN, stored as NULL).
  EXPECT_EQ(s.distances[8].quantity, "object_offset_x");
  EXPECT_TRUE(std::isnan(s.distances[8].distance.wasserstein1));
}

// The offsets of the object targets in their object's frame, x and y apart, every object pooled;
// the targets of the other classes do not count.
TEST(RunAccumulators, ObjectOffsetsAreComparedAsDistributions) {
  using C = metrics::TargetClass;
  RunAccumulators acc;
  CycleComparison a;
  a.recorded = {ComparedTarget{.object = 0, .target_class = C::object, .p_OT_O = Vec2(2.0, 0.5)},
                ComparedTarget{.object = 1, .target_class = C::object, .p_OT_O = Vec2(-2.0, -0.5)},
                ComparedTarget{.target_class = C::stationary_background, .p_OT_O = Vec2(50.0, 50.0)}};
  a.simulated = {ComparedTarget{.object = 0, .target_class = C::object, .p_OT_O = Vec2(1.0, 0.5)},
                 ComparedTarget{.object = 1, .target_class = C::object, .p_OT_O = Vec2(-2.0, 0.5)}};
  acc.add_cycle(a, 0, 0);
  ReplaySummary s;
  acc.finish(s);
  ASSERT_EQ(s.distances.size(), 10u);
  const QuantityDistance& x = s.distances[8];
  const QuantityDistance& y = s.distances[9];
  EXPECT_EQ(x.quantity, "object_offset_x");
  EXPECT_EQ(x.unit, "m");
  EXPECT_EQ(y.quantity, "object_offset_y");
  EXPECT_EQ(x.distance.n_recorded, 2);
  EXPECT_EQ(x.distance.n_simulated, 2);
  // x: {-2, 2} against {-2, 1}: half the mass moved by 1 m; KS 0.5 on [1, 2).
  EXPECT_NEAR(x.distance.wasserstein1, 0.5, 1e-6);
  EXPECT_NEAR(x.distance.kolmogorov_smirnov, 0.5, 1e-6);
  // y: {-0.5, 0.5} against {0.5, 0.5}: half the mass moved by 1 m.
  EXPECT_NEAR(y.distance.wasserstein1, 0.5, 1e-6);
  EXPECT_NEAR(y.distance.kolmogorov_smirnov, 0.5, 1e-6);
}

}  // namespace
}  // namespace rcsim::replay
