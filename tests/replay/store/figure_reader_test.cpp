// The figure queries (replay/store/figure_reader.hpp) on a hand-written database: the cycles
// found, a window of cycles, thinned series and residuals, each checked against the rows put in.
#include "replay/store/figure_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/angles.hpp"
#include "replay/store/report_store.hpp"
#include "replay/store/run_rows.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay::report {
namespace {

using replay::RunRowWriter;
using replay::StoredCycle;
using replay::StoredObjectState;
using replay::StoredTarget;
using replay::StoreLevel;


// A cycle row of sensor 0 without the real-drive figures.
StoredCycle cycle_row(int cycle, double t_s, Pose2 X_WS, int n_recorded, int n_simulated, int n_assigned,
                      double gospa_m, int merge_recorded, int merge_simulated, int merge_matched) {
  StoredCycle c;
  c.cycle = cycle;
  c.t_s = t_s;
  c.X_WS = X_WS;
  c.n_recorded = n_recorded;
  c.n_simulated = n_simulated;
  c.n_assigned = n_assigned;
  c.gospa_m = c.ospa_m = gospa_m;
  c.merge_recorded = merge_recorded;
  c.merge_simulated = merge_simulated;
  c.merge_matched = merge_matched;
  return c;
}

StoredTarget target(double range_m, double azimuth_rad, double range_rate_mps, double amplitude_db, int object,
                    int match_idx, bool merge_artefact) {
  StoredTarget t;
  t.range_m = range_m;
  t.azimuth_rad = azimuth_rad;
  t.range_rate_mps = range_rate_mps;
  t.amplitude_db = amplitude_db;
  t.object = object;
  t.match_idx = match_idx;
  t.merge_artefact = merge_artefact;
  return t;
}

class FigureReader : public rcsim::testing::ScratchDirTest {
 protected:
  FigureReader() : ScratchDirTest("figure_reader") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    db_ = open_report_database((dir_ / "f.sqlite").string(), true);
    db_->exec("INSERT INTO runs (run_id, recording_name, recording_dir, recording_checksum, recording_source, "
              "cycle_time_s, cycles, seed, level, parameters, rcsim_version, created_utc) "
              "VALUES (1, 'r', '/r', '0', '{}', 0.1, 4, 0, 'tracks', '{}', 'v', 't')");
    db_->exec("INSERT INTO run_objects VALUES (1, 3, 'car', 'passenger_car', 4.5, 1.8, 7)");
    RunRowWriter rows(*db_, 1, StoreLevel::full, 2.0, 2.0);
    const Pose2 ahead{1, 0, 0};
    // cycle, t, pose, n_rec, n_sim, n_assigned, gospa (= OSPA), merges
    rows.add_cycle(cycle_row(0, 0.0, ahead, 1, 1, 1, 0.5, 0, 0, 0), {}, {});
    // Cycle 1: a recorded target 4 m ahead, alone.
    rows.add_cycle(cycle_row(1, 0.1, ahead, 2, 0, 0, 1.5, 0, 0, 0), {target(4.0, 0.0, 0.0, 0.0, -1, -1, false)}, {});
    rows.add_cycle(cycle_row(2, 0.2, ahead, 3, 1, 1, 2.5, 2, 1, 1), {}, {});
    // Cycle 3: a recorded target at (1, 0) in the sensor frame matched to a simulated one 0.2 m
    // farther and 2*pi - 0.1 rad round in azimuth (a wrap), and a merge pair with its object state.
    rows.add_cycle(cycle_row(3, 0.3, Pose2{2, 0, 1.5707963267948966}, 1, 1, 1, 0.0, 0, 0, 0),
                   {target(1.0, 0.05, -1.0, 3.0, 0, 0, false)}, {target(1.2, 6.233185307179586, -1.5, 1.0, 0, 0, true)});
    for (int cycle = 0; cycle < 4; ++cycle) {
      rows.add_object_states(cycle, cycle == 3 ? std::vector<StoredObjectState>{{3, 0, Pose2{5.0, 1.0, 0.5}}}
                                               : std::vector<StoredObjectState>{});
    }
    rows.finish();
    db_->exec("INSERT INTO merge_pairs VALUES (1, 3, 0, 0, 1)");
  }
  std::unique_ptr<replay::ReportDatabase> db_;
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
  // The targets' reals are stored as float32: about 7 significant digits.
  EXPECT_NEAR(seen[0][0], 0.2, 1e-6);
  EXPECT_NEAR(seen[0][1], 6.233185307179586 - 0.05 - 2 * kPi, 1e-6);  // -0.1, not 6.18
  EXPECT_NEAR(seen[0][2], -0.5, 1e-6);
  EXPECT_NEAR(seen[0][3], -2.0, 1e-6);
  const ResidualSampleStats stats = read_residual_sample_stats(*db_, 1, 1);
  EXPECT_EQ(stats.count, 1);
  EXPECT_NEAR(stats.mean[0], 0.2, 1e-6);
  EXPECT_NEAR(stats.mean_square[3], 4.0, 1e-6);
}

}  // namespace
}  // namespace rcsim::replay::report
