// What campaigns read and write in a report (replay/store/campaign_store.hpp): the criteria rows
// replaced all or nothing, a report claimed once for a campaign, and the figure sources and
// distribution distances of a stored run.
#include "replay/store/campaign_store.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay {
namespace {

class CampaignStore : public rcsim::testing::ScratchDirTest {
 protected:
  CampaignStore() : ScratchDirTest("campaign_store") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    db_ = open_report_database((dir_ / "report.sqlite").string(), true);
  }
  std::unique_ptr<replay::ReportDatabase> db_;
};

const std::vector<CriterionRow> kRows = {{"gospa_mean_m", "recording", "value", "max", 1.5, "fail"},
                                         {"matched_fraction", "campaign", "p95", "min", 0.25, "pass"}};

void expect_rows(const std::vector<CriterionRow>& got, const std::vector<CriterionRow>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].figure, want[i].figure) << i;
    EXPECT_EQ(got[i].scope, want[i].scope) << i;
    EXPECT_EQ(got[i].statistic, want[i].statistic) << i;
    EXPECT_EQ(got[i].bound, want[i].bound) << i;
    EXPECT_EQ(got[i].threshold, want[i].threshold) << i;
    EXPECT_EQ(got[i].if_missing, want[i].if_missing) << i;
  }
}

TEST_F(CampaignStore, CriterionRowsAreReplacedInOrderAllOrNothing) {
  EXPECT_TRUE(read_criterion_rows(*db_).empty());
  EXPECT_EQ(count_criterion_rows(*db_), 0);
  replace_criterion_rows(*db_, kRows);
  expect_rows(read_criterion_rows(*db_), kRows);
  EXPECT_EQ(count_criterion_rows(*db_), 2);
  replace_criterion_rows(*db_, {kRows[1]});
  expect_rows(read_criterion_rows(*db_), {kRows[1]});

  // A row the schema refuses (scope CHECK) leaves the stored criteria as they were.
  std::vector<CriterionRow> bad = kRows;
  bad[1].scope = "everywhere";
  EXPECT_THROW(replace_criterion_rows(*db_, bad), SQLite::Exception);
  expect_rows(read_criterion_rows(*db_), {kRows[1]});
}

TEST_F(CampaignStore, AReportIsClaimedOnceAndThenTellsWhoseItIs) {
  EXPECT_EQ(read_campaign_name(*db_), std::nullopt);
  EXPECT_EQ(claim_campaign(*db_, "night drives", R"({"format": "rcsim-campaign"})", kRows), std::nullopt);
  EXPECT_EQ(read_campaign_name(*db_), "night drives");
  expect_rows(read_criterion_rows(*db_), kRows);

  // Claimed again, by the same or another campaign: nothing written, the stored campaign returned.
  const auto stored = claim_campaign(*db_, "day drives", "{}", {});
  ASSERT_TRUE(stored.has_value());
  EXPECT_EQ(stored->name, "night drives");
  expect_rows(stored->criteria, kRows);
  EXPECT_EQ(read_campaign_name(*db_), "night drives");
  EXPECT_EQ(db_->execAndGet("SELECT count(*) FROM campaign").getInt64(), 1);
  EXPECT_EQ(db_->execAndGet("SELECT manifest FROM campaign").getString(), R"({"format": "rcsim-campaign"})");
  EXPECT_EQ(count_criterion_rows(*db_), 2);
}

TEST_F(CampaignStore, FigureSourcesAndDistancesOfAStoredRun) {
  EXPECT_TRUE(read_run_figure_sources(*db_).empty());
  EXPECT_TRUE(read_run_distances(*db_).empty());
  EXPECT_TRUE(read_distance_quantities(*db_).empty());

  const auto recording = std::filesystem::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / "front_approach";
  ReplaySummary summary;
  {
    ReportWriter writer(*db_, StoreLevel::summary);
    summary = replay_recording_dir(recording, ReplayOptions{}, writer);
  }
  const auto runs = read_run_figure_sources(*db_);
  ASSERT_EQ(runs.size(), 1u);
  const RunFigureSources& run = runs[0];
  EXPECT_EQ(run.run_id, 1);
  EXPECT_EQ(run.recording_name, "front_approach");
  EXPECT_EQ(run.recording_dir, recording.string());
  EXPECT_GT(run.duration_s, 0.0);
  EXPECT_DOUBLE_EQ(run.gospa_mean, summary.gospa_mean_m);
  EXPECT_DOUBLE_EQ(run.wall_s, summary.total_wall_s);
  EXPECT_GE(run.targets_recorded, run.targets_matched);

  const auto quantities = read_distance_quantities(*db_);
  const auto distances = read_run_distances(*db_);
  ASSERT_FALSE(quantities.empty());
  ASSERT_EQ(distances.size(), quantities.size());  // one run: one row per quantity
  for (std::size_t i = 0; i < distances.size(); ++i) {
    EXPECT_EQ(distances[i].run_id, 1);
    EXPECT_EQ(distances[i].quantity, quantities[i].quantity);
    EXPECT_FALSE(quantities[i].unit.empty()) << quantities[i].quantity;
  }
}

}  // namespace
}  // namespace rcsim::replay
