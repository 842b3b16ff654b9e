// The figure queries (replay/store/figure_reader.hpp) on a hand-written database: the cycles
// found, a window of cycles, thinned series and residuals, each checked against the rows put in.
#include "replay/store/figure_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angles.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay::report {
namespace {

class FigureReader : public rcsim::testing::ScratchDirTest {
 protected:
  FigureReader() : ScratchDirTest("figure_reader") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    db_ = open_report_database((dir_ / "f.sqlite").string(), true);
    db_->exec("INSERT INTO runs VALUES (1, 'r', '/r', '0', '{}', 0.1, 4, 0, 'tracks', '{}', 'v', 't')");
    // cycle, sensor, t, pose, n_rec, n_sim, n_assigned, gospa, parts, ospa, merges
    const char* cycles[] = {"(1, 0, 0, 0.0, 1, 0, 0, 1, 1, 1, 0.5, 0, 0, 0, 0.5, 0, 0, 0, NULL, NULL, NULL, NULL, NULL, NULL)",
                            "(1, 1, 0, 0.1, 1, 0, 0, 0, 2, 0, 1.5, 0, 0, 0, 1.5, 0, 0, 0, NULL, NULL, NULL, NULL, NULL, NULL)",
                            "(1, 2, 0, 0.2, 1, 0, 0, 3, 1, 1, 2.5, 0, 0, 0, 2.5, 2, 1, 1, NULL, NULL, NULL, NULL, NULL, NULL)",
                            "(1, 3, 0, 0.3, 2, 0, 1.5707963267948966, 1, 1, 1, 0.0, 0, 0, 0, 0.0, 0, 0, 0, NULL, NULL, NULL, NULL, NULL, NULL)"};
    for (const char* row : cycles) db_->exec(std::string("INSERT INTO cycles VALUES ") + row);
    // Cycle 3: a recorded target at (1, 0) in the sensor frame matched to a simulated one 0.2 m farther
    // and 2*pi - 0.1 rad round in azimuth (a wrap), and a merge pair with its object states.
    db_->exec("INSERT INTO targets VALUES (1, 3, 0, 'recorded', 0, NULL, 1.0, 0.05, -1.0, 3.0, 1.0, 0.0, 0, 0, 0, NULL, NULL, NULL, NULL, NULL, NULL)");
    db_->exec("INSERT INTO targets VALUES (1, 3, 0, 'simulated', 0, 7, 1.2, 6.233185307179586, -1.5, 1.0, 1.1, 0.2, 0, 0, 1, NULL, NULL, NULL, NULL, NULL, NULL)");
    db_->exec("INSERT INTO targets VALUES (1, 1, 0, 'recorded', 0, NULL, 4.0, 0.0, 0.0, 0.0, 4.0, 0.0, NULL, NULL, 0, NULL, NULL, NULL, NULL, NULL, NULL)");
    db_->exec("INSERT INTO merge_pairs VALUES (1, 3, 0, 0, 1)");
    db_->exec("INSERT INTO object_states VALUES (1, 3, 0, 5.0, 1.0, 0.5)");
  }
  std::unique_ptr<SQLite::Database> db_;
};

TEST_F(FigureReader, HighlightsNameTheCyclesByHand) {
  const CycleHighlights h = read_cycle_highlights(*db_, 1);
  ASSERT_TRUE(h.largest_gospa && h.most_merge_artefacts && h.first_recorded && h.first_simulated &&
              h.largest_count_difference);
  EXPECT_EQ(h.largest_gospa->cycle, 2);
  EXPECT_DOUBLE_EQ(h.largest_gospa->value, 2.5);
  EXPECT_EQ(h.largest_gospa->sensor, 0);
  EXPECT_EQ(h.most_merge_artefacts->cycle, 2);
  EXPECT_DOUBLE_EQ(h.most_merge_artefacts->value, 3.0);
  EXPECT_EQ(h.first_recorded->cycle, 0);
  EXPECT_EQ(h.first_simulated->cycle, 0);
  EXPECT_EQ(h.largest_count_difference->cycle, 1);  // |2 - 0|
  EXPECT_DOUBLE_EQ(h.largest_count_difference->value, 2.0);
}

TEST_F(FigureReader, WindowHoldsItsCyclesTargetsPairsAndBoxes) {
  const CycleWindow w = read_cycle_window(*db_, 1, 1, 3);
  EXPECT_EQ(w.first_cycle, 1);
  ASSERT_EQ(w.cycles.size(), 3u);
  EXPECT_DOUBLE_EQ(w.cycles[2].X_WS.yaw_rad, kPi / 2);
  EXPECT_EQ(w.targets.size(), 3u);
  EXPECT_EQ(w.merge_pairs, (std::vector<std::pair<int, int>>{{0, 1}}));
  ASSERT_EQ(w.objects.size(), 1u);
  EXPECT_DOUBLE_EQ(w.objects[0].X_WO.x_m, 5.0);
  int matched = 0;
  for (const auto& t : w.targets) matched += t.match_idx.has_value();
  EXPECT_EQ(matched, 2);  // the pair of cycle 3, each pointing at the other
}

TEST_F(FigureReader, SeriesAreThinnedToEveryStrideThCycle) {
  const auto nearest = read_nearest_targets(*db_, 1, 1);
  ASSERT_EQ(nearest.size(), 3u);  // cycle 1 recorded; cycle 3 recorded and simulated
  EXPECT_DOUBLE_EQ(nearest[0].range_m, 4.0);
  EXPECT_DOUBLE_EQ(nearest[0].t_s, 0.1);
  EXPECT_EQ(read_nearest_targets(*db_, 1, 2).size(), 0u);  // cycles 0 and 2 have no targets
  const auto buckets = read_cycle_buckets(*db_, 1, 2);
  ASSERT_EQ(buckets.size(), 2u);
  EXPECT_DOUBLE_EQ(buckets[0].gospa_mean_m, 1.0);  // (0.5 + 1.5) / 2
  EXPECT_DOUBLE_EQ(buckets[1].gospa_max_m, 2.5);
  EXPECT_DOUBLE_EQ(buckets[1].recorded_mean, 2.0);  // (3 + 1) / 2
}

TEST_F(FigureReader, ResidualsOfAssignedPairsWithTheAzimuthWrapped) {
  std::vector<Residuals> seen;
  EXPECT_EQ(for_each_residual(*db_, 1, [&](const Residuals& r) { seen.push_back(r); }), 1);
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_NEAR(seen[0][0], 0.2, 1e-12);
  EXPECT_NEAR(seen[0][1], 6.233185307179586 - 0.05 - 2 * kPi, 1e-12);  // -0.1, not 6.18
  EXPECT_NEAR(seen[0][2], -0.5, 1e-12);
  EXPECT_NEAR(seen[0][3], -2.0, 1e-12);
  const ResidualSampleStats stats = read_residual_sample_stats(*db_, 1, 1);
  EXPECT_EQ(stats.count, 1);
  EXPECT_NEAR(stats.mean[0], 0.2, 1e-12);
  EXPECT_NEAR(stats.mean_square[3], 4.0, 1e-12);
}

}  // namespace
}  // namespace rcsim::replay::report
