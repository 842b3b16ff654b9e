// Criteria and verdicts (replay/verdict/criteria.hpp, schemas/campaign.md): a pass, a fail, a
// missing figure, the campaign statistics computed by hand, and the errors of a bad document.
#include "replay/verdict/criteria.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay::verdict {
namespace {

class CriteriaTest : public rcsim::testing::ScratchDirTest {
 protected:
  CriteriaTest() : ScratchDirTest("criteria") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    db_ = open_report_database((dir_ / "report.sqlite").string(), true);
    for (const char* name : {"front_approach", "two_in_one_cell"}) {
      ReportWriter writer(*db_, StoreLevel::summary);
      replay_recording_dir(std::filesystem::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / name, ReplayOptions{},
                           writer);
    }
    for (const auto& row : read_run_figures(*db_, {"gospa_mean_m"})) gospa_.push_back(*row.values[0]);
    ASSERT_EQ(gospa_.size(), 2u);
  }
  std::vector<Criterion> parse(const std::string& text) {
    const nlohmann::json doc = nlohmann::json::parse(text);
    return parse_criteria(JsonField(doc, "criteria.json", ""));
  }
  std::unique_ptr<replay::ReportDatabase> db_;
  std::vector<double> gospa_;  // per run, by run id
};

TEST_F(CriteriaTest, APassAFailAndAMissingFigure) {
  // wasserstein1.background_range is missing: the synthetic drives have no background to compare.
  const double higher = std::max(gospa_[0], gospa_[1]), lower = std::min(gospa_[0], gospa_[1]);
  const auto criteria = parse(R"({"criteria": [
      {"figure": "gospa_mean_m", "max": )" + std::to_string(higher + 1.0) + R"(},
      {"figure": "wasserstein1.background_range", "max": 1},
      {"figure": "wasserstein1.background_range", "max": 1, "if_missing": "pass"}]})");
  ASSERT_EQ(criteria.size(), 3u);
  Verdicts v = judge(*db_, criteria);
  ASSERT_EQ(v.runs.size(), 2u);
  for (const RunVerdict& r : v.runs) {
    ASSERT_EQ(r.results.size(), 3u);
    EXPECT_TRUE(r.results[0].passed);
    ASSERT_TRUE(r.results[0].value.has_value());
    EXPECT_FALSE(r.results[1].passed);  // missing, and if_missing defaults to fail
    EXPECT_FALSE(r.results[1].value.has_value());
    EXPECT_TRUE(r.results[2].passed);
    EXPECT_FALSE(r.passed);
  }
  EXPECT_EQ(v.runs_failed, 2);
  EXPECT_FALSE(v.passed());
  EXPECT_NE(describe_failure(criteria[1], v.runs[0].results[1]).find("missing"), std::string::npos);
  // A quantity no run compares is no figure: refused with the known ones named.
  try {
    parse(R"({"criteria": [{"figure": "wasserstein1.rang", "max": 1}]})");
    ADD_FAILURE() << "wasserstein1.rang was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("QUANTITY: range, azimuth, range_rate"), std::string::npos) << e.what();
  }

  // A threshold between the two runs: exactly the worse run fails, with its value.
  v = judge(*db_, parse(R"({"criteria": [{"figure": "gospa_mean_m", "max": )" +
                        fmt::format("{:.17g}", (higher + lower) / 2) + "}]}"));
  EXPECT_EQ(v.runs_failed, 1);
  for (const RunVerdict& r : v.runs) {
    EXPECT_EQ(r.passed, *r.results[0].value <= (higher + lower) / 2);
    EXPECT_DOUBLE_EQ(*r.results[0].value, gospa_[r.run_id == v.runs[0].run_id ? 0 : 1]);
  }
  const std::string failure = describe_failure(v.criteria[0], v.runs[gospa_[0] > gospa_[1] ? 0 : 1].results[0]);
  EXPECT_NE(failure.find("gospa_mean_m = "), std::string::npos) << failure;
  EXPECT_NE(failure.find(" > "), std::string::npos) << failure;
}

TEST_F(CriteriaTest, CampaignStatisticsByHand) {
  const double a = std::min(gospa_[0], gospa_[1]), b = std::max(gospa_[0], gospa_[1]);
  ASSERT_LT(a, b);
  // Two values: mean = median = (a + b) / 2; p95 = a + 0.95 (b - a) (type 7); min a; max b.
  const std::vector<std::pair<std::string, double>> expected = {
      {"mean", (a + b) / 2}, {"median", (a + b) / 2}, {"p95", a + 0.95 * (b - a)}, {"min", a}, {"max", b}};
  for (const auto& [statistic, value] : expected) {
    const auto criteria = parse(R"({"criteria": [{"figure": "gospa_mean_m", "scope": "campaign", "statistic": ")" +
                                statistic + R"(", "max": )" + fmt::format("{:.17g}", value - 1e-9) +
                                R"(, "min": )" + fmt::format("{:.17g}", value - 1e-6) + "}]}");
    const Verdicts v = judge(*db_, criteria);
    ASSERT_EQ(v.campaign.size(), 2u) << statistic;
    EXPECT_NEAR(*v.campaign[0].value, value, 1e-12) << statistic;
    EXPECT_TRUE(v.campaign[0].passed) << statistic;    // "min" comes first: >= value - 1e-6 passes
    EXPECT_FALSE(v.campaign[1].passed) << statistic;   // <= value - 1e-9 fails
    EXPECT_EQ(v.runs_failed, 0);
    EXPECT_FALSE(v.passed());
  }
  // Judging one run (rcsim replay) leaves the campaign criteria out.
  const Verdicts one = judge(*db_, parse(R"({"criteria": [{"figure": "gospa_mean_m", "scope": "campaign", "max": 0}]})"),
                             judge(*db_, {}).runs[0].run_id);
  EXPECT_EQ(one.runs.size(), 1u);
  EXPECT_TRUE(one.campaign.empty());
  EXPECT_TRUE(one.passed());
}

TEST_F(CriteriaTest, StoredCriteriaRoundTripAndReplace) {
  const auto criteria = parse(R"({"criteria": [
      {"figure": "latency_difference_mean_s", "min": -0.2, "max": 0.2, "if_missing": "pass"},
      {"figure": "matched_fraction", "scope": "campaign", "statistic": "p95", "min": 0.5}]})");
  ASSERT_EQ(criteria.size(), 3u);
  store_criteria(*db_, criteria);
  EXPECT_EQ(stored_criteria(*db_), criteria);
  store_criteria(*db_, {criteria[2]});
  EXPECT_EQ(stored_criteria(*db_), std::vector<Criterion>{criteria[2]});
  EXPECT_EQ(criteria[2].text(), "p95 matched_fraction over the campaign >= 0.5");
}

TEST_F(CriteriaTest, BadCriteriaNameTheField) {
  const auto error_of = [&](const std::string& text) {
    try {
      parse(text);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of(R"({"criteria": [{"figure": "gospa_mean_m", "max": 1}, {"figure": "gospa", "max": 1}]})")
                .find("criteria.json: criteria[1].figure: unknown figure 'gospa'"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"criteria": [{"figure": "gospa_mean_m"}]})").find("criteria[0]"), std::string::npos);
  EXPECT_NE(error_of(R"({"criteria": [{"figure": "gospa_mean_m", "max": 1, "statistic": "p95"}]})")
                .find("needs \"scope\": \"campaign\""),
            std::string::npos);
  EXPECT_NE(error_of(R"({"criteria": [{"figure": "gospa_mean_m", "max": 1, "maximum": 2}]})").find("maximum"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"criteria": [{"figure": "gospa_mean_m", "max": 1, "if_missing": "skip"}]})")
                .find("if_missing"),
            std::string::npos);
  // A floor above a ceiling can never pass: in one entry, or across two.
  EXPECT_NE(error_of(R"({"criteria": [{"figure": "gospa_mean_m", "min": 2, "max": 1}]})")
                .find("criteria[0].max: \"gospa_mean_m <= 1\": min 2 above max 1"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"criteria": [{"figure": "gospa_mean_m", "max": 1}, {"figure": "gospa_mean_m", "min": 2}]})")
                .find("criteria[1].min"),
            std::string::npos);
  // The same figure over the campaign is another quantity: no contradiction.
  EXPECT_EQ(error_of(R"({"criteria": [{"figure": "gospa_mean_m", "max": 1},
                                      {"figure": "gospa_mean_m", "scope": "campaign", "min": 2}]})"),
            "no error");
  EXPECT_EQ(error_of(R"({"criteria": [{"figure": "gospa_mean_m", "min": 1, "max": 1}]})"), "no error");
}

}  // namespace
}  // namespace rcsim::replay::verdict
