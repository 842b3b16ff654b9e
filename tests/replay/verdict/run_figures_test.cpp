// The figures campaigns judge and rank runs by (replay/verdict/run_figures.hpp): the catalogue and
// the distance figures by name, and every run's figures computed from its stored sources by hand,
// for a replayed run and two copies of it with known variations (run_copies.hpp); an unknown
// figure refused.
#include "replay/verdict/run_figures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "replay/store/campaign_store.hpp"
#include "replay/store/report_store.hpp"
#include "replay/store/run_copies.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::run_figures_test {

using namespace replay::verdict;

TEST(RunFigures, TheCatalogueAndTheDistanceFiguresByName) {
  const auto& catalogue = figure_catalogue();
  ASSERT_EQ(catalogue.size(), 24u);
  EXPECT_EQ(catalogue.front().name, "gospa_mean_m");
  std::set<std::string> names;
  for (const FigureInfo& f : catalogue) {
    EXPECT_TRUE(names.insert(f.name).second) << f.name << " twice";
    ASSERT_TRUE(find_figure(f.name).has_value()) << f.name;
    EXPECT_EQ(find_figure(f.name)->unit, f.unit);
  }
  EXPECT_EQ(find_figure("target_count_ratio")->worse, Worse::away_from_one);
  EXPECT_EQ(find_figure("matched_fraction")->worse, Worse::lower);
  // A distance of a compared quantity: W1 in the quantity's unit, KS a fraction.
  const auto w1 = find_figure("wasserstein1.range");
  ASSERT_TRUE(w1.has_value());
  EXPECT_EQ(w1->unit, "of the quantity");
  EXPECT_EQ(w1->meaning, "Wasserstein-1 (area metric) between recorded and simulated range");
  EXPECT_EQ(w1->worse, Worse::higher);
  EXPECT_EQ(find_figure("kolmogorov_smirnov.object_offset_y")->unit, "1");
  // No quantity, another one, or the prefix alone: no figure.
  for (const char* unknown : {"wasserstein1.rang", "wasserstein1.", "wasserstein1", "kolmogorov_smirnov.speed", "range",
                              "gospa_mean", ""}) {
    EXPECT_FALSE(find_figure(unknown).has_value()) << unknown;
  }
  const std::string all = figure_names();
  EXPECT_EQ(all.rfind("gospa_mean_m, ospa_mean_m, ", 0), 0u) << all;
  EXPECT_NE(all.find(", simulate_cpu_s, wasserstein1.QUANTITY, kolmogorov_smirnov.QUANTITY (QUANTITY: range, azimuth, "
                     "range_rate, amplitude, "),
            std::string::npos)
      << all;
}

class RunFiguresStored : public testing::ScratchDirTest {
 protected:
  RunFiguresStored() : ScratchDirTest("run_figures") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    db_ = replay::open_report_database((dir_ / "report.db").string(), true);
    replay::ReportWriter writer(*db_, replay::StoreLevel::summary);
    replay::replay_recording_dir(testing::kBundledRecordings / "front_approach", replay::ReplayOptions{}, writer);
  }
  std::unique_ptr<replay::ReportDatabase> db_;
};

TEST_F(RunFiguresStored, EachFigureFromTheStoredSourcesByHand) {
  const std::vector<replay::RunFigureSources> sources = replay::read_run_figure_sources(*db_);
  ASSERT_EQ(sources.size(), 1u);
  const replay::RunFigureSources s = sources[0];
  ASSERT_GT(s.targets_recorded, 0.0);
  ASSERT_GT(s.in_view, 0.0) << "front_approach has its object in view";
  std::optional<double> w1_range;
  for (const replay::RunDistance& d : replay::read_run_distances(*db_)) {
    if (d.run_id == s.run_id && d.quantity == "range") w1_range = d.wasserstein1;
  }
  ASSERT_TRUE(w1_range.has_value());
  // Run 2: no latency pair, no simulated detection; run 3: a latency difference of 0.3 s, GOSPA x4.
  {
    replay::RunCopier copier(*db_, s.run_id);
    copier.copy(2);
    replay::RunVariation none;
    none.no_latency_pair = true;
    none.detection_factor = 0.0;
    copier.vary(2, none);
    copier.copy(3);
    replay::RunVariation worse;
    worse.quality = 4.0;
    worse.latency_difference_s = 0.3;
    copier.vary(3, worse);
    copier.commit();
  }
  const std::vector<RunFigureRow> rows =
      read_run_figures(*db_, {"target_count_ratio", "matched_fraction", "object_detection_rate_difference",
                              "latency_difference_mean_s", "gospa_mean_m", "wasserstein1.range", "gospa_mean_m"});
  ASSERT_EQ(rows.size(), 3u);
  const RunFigureRow& run = rows[0];
  EXPECT_EQ(run.run_id, s.run_id);
  EXPECT_EQ(run.recording_name, "front_approach");
  EXPECT_EQ(run.recording_dir, s.recording_dir);
  EXPECT_DOUBLE_EQ(run.duration_s, s.duration_s);
  EXPECT_EQ(run.kind, s.kind);
  ASSERT_EQ(run.values.size(), 7u);
  EXPECT_DOUBLE_EQ(*run.values[0], s.targets_simulated / s.targets_recorded);
  EXPECT_DOUBLE_EQ(*run.values[1], s.targets_matched / s.targets_recorded);
  EXPECT_DOUBLE_EQ(*run.values[2], (s.detected_simulated - s.detected_recorded) / s.in_view);
  EXPECT_EQ(run.values[3].has_value(), s.latency_pairs > 0);
  EXPECT_DOUBLE_EQ(*run.values[4], s.gospa_mean);
  EXPECT_DOUBLE_EQ(*run.values[5], *w1_range);
  EXPECT_EQ(run.values[6], run.values[4]) << "a figure asked for twice, twice";

  EXPECT_EQ(rows[1].run_id, 2);
  EXPECT_FALSE(rows[1].values[3].has_value()) << "no latency pair: missing";
  EXPECT_DOUBLE_EQ(*rows[1].values[2], (0.0 - s.detected_recorded) / s.in_view);
  EXPECT_EQ(rows[2].run_id, 3);
  EXPECT_DOUBLE_EQ(*rows[2].values[3], 0.3);
  EXPECT_DOUBLE_EQ(*rows[2].values[4], 4.0 * s.gospa_mean);
  EXPECT_DOUBLE_EQ(*rows[2].values[5], *w1_range) << "distance_factor 1";
}

TEST_F(RunFiguresStored, AnUnknownFigureIsRefusedAndNoFigureGivesTheRunsAlone) {
  try {
    read_run_figures(*db_, {"gospa_mean_m", "gospa"});
    ADD_FAILURE() << "an unknown figure was read";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unknown figure 'gospa'");
  }
  EXPECT_THROW(read_run_figures(*db_, {"wasserstein1.speed"}), std::invalid_argument);
  const auto rows = read_run_figures(*db_, {});
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].run_id, 1);
  EXPECT_TRUE(rows[0].values.empty());
  // A distance no run has is missing, never 0.
  const auto background = read_run_figures(*db_, {"wasserstein1.background_range"});
  ASSERT_EQ(background.size(), 1u);
  EXPECT_FALSE(background[0].values[0].has_value());
}

}  // namespace rcsim::run_figures_test
