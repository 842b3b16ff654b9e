// The figures' distributions over a campaign (replay/report/campaign_distributions.cpp, declared
// in campaign_section.hpp), from campaign data made by hand: the quantile row, the histogram's
// bins and its criteria's thresholds, a figure alike in every run drawn only when a criterion
// bounds it, a threshold far off named instead of drawn, and a far outlier left to the end bin.
#include "replay/report/campaign_section.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "replay/replay_fixtures.hpp"

namespace rcsim::campaign_distributions_test {

using replay::report::campaign_distributions;
using replay::report::CampaignData;
using namespace replay::verdict;
using testing::count_occurrences;

// One figure, its values per run (nullopt: the run lacks it).
CampaignData one_figure(const FigureInfo& info, const std::vector<std::optional<double>>& values) {
  CampaignData data;
  data.figures = {info};
  for (std::size_t i = 0; i < values.size(); ++i) {
    RunFigureRow row;
    row.run_id = static_cast<std::int64_t>(i + 1);
    row.values = {values[i]};
    data.runs.push_back(row);
  }
  return data;
}

const FigureInfo kGospa{"gospa_mean_m", "m", "GOSPA <mean>", Worse::higher};

// The text from `begin` up to the next `end`.
std::string part(const std::string& text, const std::string& begin, const std::string& end) {
  const auto a = text.find(begin);
  if (a == std::string::npos) return {};
  return text.substr(a, text.find(end, a) - a);
}

TEST(CampaignDistributions, QuantilesAndHistogramWithTheThresholdsByHand) {
  CampaignData data = one_figure(kGospa, {4.0, 1.0, std::nullopt, 3.0, 2.0});
  data.verdicts.criteria = {{"gospa_mean_m", Scope::recording, Statistic::value, Bound::max, 3.5, false},
                            {"gospa_mean_m", Scope::campaign, Statistic::p95, Bound::max, 3.0, false},
                            {"ospa_mean_m", Scope::recording, Statistic::value, Bound::max, 0.1, false}};
  const std::string html = campaign_distributions(data, 30);
  // {1, 2, 3, 4}: median 2.5, p95 at h = 0.95 x 3 = 2.85: 3 + 0.85 = 3.85, mean 2.5; one run without.
  EXPECT_NE(html.find(R"(<tr data-figure="gospa_mean_m"><th title="GOSPA &lt;mean&gt;">gospa_mean_m</th><td>m</td>)"
                      R"(<td class="num">4</td><td class="num">1</td><td class="num" data-key="min">1</td>)"
                      R"(<td class="num" data-key="median">2.5</td><td class="num" data-key="p95">3.85</td>)"
                      R"(<td class="num" data-key="max">4</td><td class="num" data-key="mean">2.5</td>)"
                      "<td>\u2264 3.5, p95 \u2264 3</td></tr>"),
            std::string::npos)
      << html;
  const std::string svg = part(html, R"(aria-label="gospa_mean_m")", "</svg>");
  ASSERT_FALSE(svg.empty()) << html;
  EXPECT_NE(svg.find("4 runs, 1 without the figure"), std::string::npos) << svg;
  EXPECT_NE(svg.find(">gospa_mean_m / m</text>"), std::string::npos);
  // At least 5 bins over [1, 4], 0.6 wide: 1 -> bin 0, 2 -> 1, 3 -> 3, 4 -> the last; four bars.
  EXPECT_EQ(count_occurrences(svg, "class=\"bar\""), 4u);
  // Both thresholds drawn: the recording's solid red, the campaign's dashed orange with its statistic.
  EXPECT_EQ(count_occurrences(svg, "class=\"marker\""), 2u);
  EXPECT_NE(svg.find("stroke=\"#c92a2a\" stroke-width=\"1.5\"/>"), std::string::npos) << svg;
  EXPECT_NE(svg.find("stroke=\"#e8590c\" stroke-width=\"1.5\" stroke-dasharray=\"5 3\"/>"), std::string::npos) << svg;
  EXPECT_NE(svg.find(">p95 \u2264 3</text>"), std::string::npos) << svg;
  EXPECT_EQ(html.find("<mean>"), std::string::npos);
}

TEST(CampaignDistributions, AFigureAlikeInEveryRunIsDrawnOnlyWhenACriterionBoundsIt) {
  const FigureInfo matched{"matched_fraction", "1", "matched", Worse::lower};
  CampaignData data = one_figure(matched, {0.5, 0.5, 0.5});
  std::string html = campaign_distributions(data, 30);
  EXPECT_NE(html.find(R"(<tr data-figure="matched_fraction">)"), std::string::npos) << "its row stays";
  EXPECT_EQ(html.find("<svg"), std::string::npos) << html;
  data.verdicts.criteria = {{"matched_fraction", Scope::recording, Statistic::value, Bound::min, 0.4, false}};
  html = campaign_distributions(data, 30);
  const std::string svg = part(html, R"(aria-label="matched_fraction")", "</svg>");
  ASSERT_FALSE(svg.empty()) << html;
  EXPECT_NE(svg.find(">matched_fraction</text>"), std::string::npos) << "a unit of 1 is not named";
  EXPECT_EQ(count_occurrences(svg, "class=\"marker\""), 1u);
  EXPECT_NE(svg.find(">\u2265 0.4</text>"), std::string::npos) << svg;
}

TEST(CampaignDistributions, AThresholdFarOffIsNamedNotDrawn) {
  CampaignData data = one_figure(kGospa, {1.0, 2.0, 3.0, 4.0});
  // The axis reaches max(4 - 1, 4 / 2) = 3 beyond the values: 100 and -50 lie farther.
  data.verdicts.criteria = {{"gospa_mean_m", Scope::recording, Statistic::value, Bound::max, 100.0, false},
                            {"gospa_mean_m", Scope::campaign, Statistic::mean, Bound::min, -50.0, false}};
  const std::string svg = part(campaign_distributions(data, 30), R"(aria-label="gospa_mean_m")", "</svg>");
  EXPECT_NE(svg.find("4 runs; \u2264 100 right of the axis, mean \u2265 -50 left of the axis"), std::string::npos) << svg;
  EXPECT_EQ(count_occurrences(svg, "class=\"marker\""), 0u);
}

TEST(CampaignDistributions, AFarOutlierIsCountedInTheEndBin) {
  // 0, 1, ..., 98 and 10000: p1 = 0.99, p99 = 98 + 0.01 x 9902 = 197.02; 10000 lies more than
  // their span beyond, so the axis ends at p99 + half the span, 295.035, and 10000 is counted
  // in the last bin.
  std::vector<std::optional<double>> values;
  for (int i = 0; i < 99; ++i) values.emplace_back(static_cast<double>(i));
  values.emplace_back(10000.0);
  const std::string html = campaign_distributions(one_figure(kGospa, values), 30);
  EXPECT_NE(html.find(R"(<td class="num" data-key="max">1e+04</td>)"), std::string::npos) << html;
  const std::string svg = part(html, R"(aria-label="gospa_mean_m")", "</svg>");
  EXPECT_NE(svg.find("100 runs; 0 below / 1 above the range, counted in the end bins"), std::string::npos) << svg;
}

}  // namespace rcsim::campaign_distributions_test
