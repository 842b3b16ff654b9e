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

// The report's one-pass readers (issue 52) against the one-figure ones: several objects' targets
// in their frames at once, the background's range and azimuth histograms at once; over 300
// cycles (two target blocks, decoded a cycle at a time) with a hand-counted total.
TEST_F(FigureReader, OnePassReadersEqualTheOneFigureOnes) {
  db_->exec("INSERT INTO runs (run_id, recording_name, recording_dir, recording_checksum, recording_source, "
            "cycle_time_s, cycles, seed, level, parameters, rcsim_version, created_utc) "
            "VALUES (2, 'r', '/r', '0', '{}', 0.1, 300, 0, 'detections', '{}', 'v', 't')");
  {
    RunRowWriter rows(*db_, 2, StoreLevel::full, 2.0, 2.0);
    for (int k = 0; k < 300; ++k) {
      std::vector<StoredTarget> recorded, simulated;
      for (int i = 0; i < 3; ++i) {
        StoredTarget t = target(5.0 + i + 0.01 * k, 0.1 * i - 0.1, 0.0, 0.0, (k + i) % 2, -1, false);
        t.target_class = metrics::TargetClass::object;
        t.p_OT_O = Vec2{0.1 * i, 0.001 * k};
        recorded.push_back(t);
        StoredTarget b = target(20.0 + 0.1 * (k % 50), -0.3 + 0.002 * k, 0.0, 0.0, -1, -1, false);
        b.target_class = metrics::TargetClass::stationary_background;
        (i == 0 ? simulated : recorded).push_back(b);
      }
      rows.add_cycle(cycle_row(k, 0.1 * k, Pose2{0, 0, 0}, static_cast<int>(recorded.size()), static_cast<int>(simulated.size()), 0,
                               0.0, 0, 0, 0),
                     recorded, simulated);
      rows.add_object_states(k, {});
    }
    rows.finish();
  }
  const auto both = read_objects_frame_targets(*db_, 2, {0, 1}, 100000);
  ASSERT_EQ(both.size(), 2u);
  for (const int object : {0, 1}) {
    const auto one = read_object_frame_targets(*db_, 2, object, 100000);
    ASSERT_EQ(both.at(object).size(), one.size());
    for (std::size_t i = 0; i < one.size(); ++i) {
      EXPECT_EQ(both.at(object)[i].p_OT_O, one[i].p_OT_O);
      EXPECT_EQ(both.at(object)[i].simulated, one[i].simulated);
    }
  }
  EXPECT_EQ(both.at(0).size() + both.at(1).size(), 900u);  // 3 object targets a cycle
  const auto [range, azimuth] = read_background_histograms(*db_, 2, {15.0, 1.0, 12}, {-0.4, 0.05, 20});
  const auto range_alone = read_background_histogram(*db_, 2, BackgroundQuantity::range, 15.0, 1.0, 12);
  const auto azimuth_alone = read_background_histogram(*db_, 2, BackgroundQuantity::azimuth, -0.4, 0.05, 20);
  EXPECT_EQ(range.counts, range_alone.counts);
  EXPECT_EQ(azimuth.counts, azimuth_alone.counts);
  std::int64_t recorded = 0, simulated = 0;
  for (const std::int64_t c : range.counts[0]) recorded += c;
  for (const std::int64_t c : range.counts[1]) simulated += c;
  EXPECT_EQ(recorded, 600);  // 2 background targets a cycle recorded, 1 simulated
  EXPECT_EQ(simulated, 300);
}

}  // namespace
}  // namespace rcsim::replay::report
