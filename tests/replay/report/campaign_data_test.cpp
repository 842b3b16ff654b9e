// What the campaign overview reads (replay/report/campaign_data.hpp), from two replayed runs: a
// database is a campaign's once it is named or holds criteria; the figures listed are the
// criteria's first, in their order, then those some run has (a distance in its quantity's unit),
// never one no run has and no criterion names; each run's values follow that order; the sorted
// values and the index of a figure by name.
#include "replay/report/campaign_data.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "replay/store/campaign_store.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::campaign_data_test {

using replay::report::CampaignData;
using replay::report::is_campaign_database;
using replay::report::read_campaign_data;
using namespace replay::verdict;

class CampaignDataRead : public testing::ScratchDirTest {
 protected:
  CampaignDataRead() : ScratchDirTest("campaign_data") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    db_ = replay::open_report_database((dir_ / "report.db").string(), true);
    for (const char* name : {"front_approach", "two_in_one_cell"}) {
      replay::ReportWriter writer(*db_, replay::StoreLevel::summary);
      replay::replay_recording_dir(testing::kBundledRecordings / name, replay::ReplayOptions{}, writer);
    }
  }

  // The names of data.figures, in order.
  static std::vector<std::string> names(const CampaignData& data) {
    std::vector<std::string> out;
    for (const FigureInfo& f : data.figures) out.push_back(f.name);
    return out;
  }

  std::unique_ptr<replay::ReportDatabase> db_;
};

TEST_F(CampaignDataRead, ACampaignOnceNamedOrJudged) {
  EXPECT_FALSE(is_campaign_database(*db_));
  EXPECT_EQ(read_campaign_data(*db_).name, "");
  store_criteria(*db_, {{"gospa_mean_m", Scope::recording, Statistic::value, Bound::max, 100.0, false}});
  EXPECT_TRUE(is_campaign_database(*db_));
  store_criteria(*db_, {});
  EXPECT_FALSE(is_campaign_database(*db_));
  EXPECT_FALSE(replay::claim_campaign(*db_, "q3 <drives>", "{}", {}).has_value());
  EXPECT_TRUE(is_campaign_database(*db_));
  EXPECT_EQ(read_campaign_data(*db_).name, "q3 <drives>") << "as stored, unescaped";
}

TEST_F(CampaignDataRead, WithoutCriteriaTheFiguresSomeRunHasAndEveryRunPassed) {
  const CampaignData data = read_campaign_data(*db_);
  const std::vector<std::string> listed = names(data);
  ASSERT_EQ(data.runs.size(), 2u);
  EXPECT_EQ(data.runs[0].run_id, 1);
  EXPECT_EQ(data.runs[1].run_id, 2);
  // The catalogue's order first; the synthetic drives have no stationary background, so no
  // distance of its ranges.
  ASSERT_GE(listed.size(), 2u);
  EXPECT_EQ(listed[0], "gospa_mean_m");
  EXPECT_EQ(listed[1], "ospa_mean_m");
  EXPECT_EQ(std::count(listed.begin(), listed.end(), "wasserstein1.background_range"), 0);
  for (std::size_t f = 0; f < data.figures.size(); ++f) {
    EXPECT_TRUE(data.runs[0].values[f] || data.runs[1].values[f]) << listed[f] << ": no run has it";
  }
  // A distance in the unit of its quantity; KS a fraction.
  const auto w1 = data.figure_index("wasserstein1.range");
  const auto ks = data.figure_index("kolmogorov_smirnov.range");
  ASSERT_TRUE(w1 && ks);
  EXPECT_EQ(data.figures[*w1].unit, "m");
  EXPECT_EQ(data.figures[*ks].unit, "1");
  EXPECT_GT(*w1, *data.figure_index("simulate_cpu_s")) << "after the catalogue";
  EXPECT_FALSE(data.figure_index("gospa").has_value());
  // Each run's values are those read_run_figures gives, in the listed order.
  const auto direct = read_run_figures(*db_, listed);
  ASSERT_EQ(direct.size(), 2u);
  EXPECT_EQ(data.runs[0].values, direct[0].values);
  EXPECT_EQ(data.runs[1].values, direct[1].values);
  EXPECT_TRUE(data.verdicts.criteria.empty());
  EXPECT_EQ(data.verdicts.runs.size(), 2u);
  EXPECT_EQ(data.verdicts.runs_failed, 0);
}

TEST_F(CampaignDataRead, TheCriteriasFiguresComeFirstEvenWhereNoRunHasThem) {
  const std::vector<Criterion> criteria = {
      {"matched_fraction", Scope::recording, Statistic::value, Bound::min, 0.0, false},
      {"wasserstein1.background_range", Scope::recording, Statistic::value, Bound::max, 2.0, true},
      {"matched_fraction", Scope::campaign, Statistic::mean, Bound::min, 0.0, false},
      {"gospa_mean_m", Scope::recording, Statistic::value, Bound::max, 1000.0, false}};
  store_criteria(*db_, criteria);
  const CampaignData data = read_campaign_data(*db_);
  const std::vector<std::string> listed = names(data);
  ASSERT_GE(listed.size(), 4u);
  EXPECT_EQ(listed[0], "matched_fraction");
  EXPECT_EQ(listed[1], "wasserstein1.background_range");
  EXPECT_EQ(listed[2], "gospa_mean_m");
  EXPECT_EQ(listed[3], "ospa_mean_m") << "then the catalogue's order";
  EXPECT_EQ(std::count(listed.begin(), listed.end(), "gospa_mean_m"), 1);
  EXPECT_FALSE(data.runs[0].values[1].has_value());
  EXPECT_TRUE(data.sorted_values(1).empty());
  // The sorted values of GOSPA: both runs', ascending.
  const auto direct = read_run_figures(*db_, {"gospa_mean_m"});
  std::vector<double> expected{*direct[0].values[0], *direct[1].values[0]};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(data.sorted_values(2), expected);
  EXPECT_EQ(data.verdicts.criteria, criteria);
  EXPECT_EQ(data.verdicts.runs_failed, 0);
  ASSERT_EQ(data.verdicts.campaign.size(), 1u);
  EXPECT_TRUE(data.verdicts.campaign[0].passed);
}

TEST(CampaignDataValues, SortedValuesLeaveOutTheRunsWithoutTheFigure) {
  CampaignData data;
  data.figures = {{"a", "m", "", Worse::higher}, {"b", "1", "", Worse::lower}};
  for (const auto& [a, b] : std::vector<std::pair<std::optional<double>, std::optional<double>>>{
           {3.0, std::nullopt}, {std::nullopt, std::nullopt}, {-1.0, 0.5}, {2.0, std::nullopt}}) {
    RunFigureRow row;
    row.values = {a, b};
    data.runs.push_back(row);
  }
  EXPECT_EQ(data.sorted_values(0), (std::vector<double>{-1.0, 2.0, 3.0}));
  EXPECT_EQ(data.sorted_values(1), (std::vector<double>{0.5}));
  EXPECT_EQ(data.figure_index("b"), std::optional<std::size_t>(1));
  EXPECT_FALSE(data.figure_index("c").has_value());
}

}  // namespace rcsim::campaign_data_test
