// The campaign overview of rcsim report (replay/report/campaign_section.hpp, docs/report.md
// "Campaign report"): verdicts with the criteria's values computed here by hand from the stored
// figures, the failed runs, the worst runs by each figure, the distributions, the links into the
// runs' detail and their pages, escaping, and the page of a database that is no campaign unchanged.
#include "replay/report/campaign_section.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sys/wait.h>

#include "replay/verdict/criteria.hpp"
#include "replay/replay_fixtures.hpp"
#include "replay/report/html_report.hpp"
#include "replay/store/report_store.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay {
namespace {

namespace fs = std::filesystem;
using verdict::Bound;
using verdict::Criterion;
using verdict::Scope;
using verdict::Statistic;
using rcsim::testing::count_occurrences;
using rcsim::testing::read_file;

constexpr const char* kEvilCampaignName = "<script>alert(1)</script> & \"x\" 'y'";

// The text between `begin` and the next `end` after it (empty if `begin` is absent).
std::string between(const std::string& text, const std::string& begin, const std::string& end) {
  const auto a = text.find(begin);
  if (a == std::string::npos) return {};
  const auto b = text.find(end, a + begin.size());
  return text.substr(a, b == std::string::npos ? std::string::npos : b - a);
}

// Copies run `source` (every table with a run_id) as new runs, `copies` times; returns their ids.
std::vector<std::int64_t> copy_run(SQLite::Database& db, std::int64_t source, int copies) {
  std::vector<std::string> statements;
  SQLite::Statement tables(db, "SELECT m.name FROM sqlite_master m WHERE m.type = 'table' AND "
                               "EXISTS (SELECT 1 FROM pragma_table_info(m.name) WHERE name = 'run_id') "
                               "ORDER BY m.name <> 'runs', m.name");
  while (tables.executeStep()) {
    const std::string table = tables.getColumn(0).getString();
    std::string names, values;
    SQLite::Statement info(db, "SELECT name FROM pragma_table_info(?)");
    info.bind(1, table);
    while (info.executeStep()) {
      const std::string c = info.getColumn(0).getString();
      names += (names.empty() ? "" : ", ") + c;
      values += (values.empty() ? "" : ", ") + (c == "run_id" ? std::string("?1") : c);
    }
    statements.push_back(fmt::format("INSERT INTO {0} ({1}) SELECT {2} FROM {0} WHERE run_id = ?2", table, names, values));
  }
  std::vector<std::int64_t> ids;
  SQLite::Transaction transaction(db);
  for (int k = 0; k < copies; ++k) {
    const std::int64_t id = db.execAndGet("SELECT max(run_id) + 1 FROM runs").getInt64();
    for (const std::string& sql : statements) {
      SQLite::Statement s(db, sql);
      s.bind(1, id);
      s.bind(2, source);
      s.exec();
    }
    ids.push_back(id);
  }
  transaction.commit();
  return ids;
}

class CampaignReport : public rcsim::testing::ScratchDirTest {
 protected:
  CampaignReport() : ScratchDirTest("campaign_report") {}

  // Three bundled recordings replayed (summary store) into a fresh database.
  void replay_bundled() {
    db_path_ = (dir_ / "campaign.sqlite").string();
    db_ = open_report_database(db_path_, true);
    for (const char* name : {"front_approach", "two_in_one_cell", "corner_approach"}) {
      ReportWriter writer(*db_, StoreLevel::summary);
      replay_recording_dir(fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / name, ReplayOptions{}, writer);
    }
    for (const auto& row : verdict::read_run_figures(*db_, {"gospa_mean_m"})) {
      ids_.push_back(row.run_id);
      gospa_.push_back(*row.values[0]);
    }
    ASSERT_EQ(gospa_.size(), 3u);
  }

  // A per-recording criterion that every run passes, one that the worse runs fail, one on a
  // figure no run has (the synthetic drives have no stationary background to compare), and two campaign criteria: a passing mean and a failing max.
  void store_five_criteria() {
    std::vector<double> sorted = gospa_;
    std::sort(sorted.begin(), sorted.end());
    threshold_ = sorted[0] + 0.5 * (sorted[1] - sorted[0]);  // the lowest passes, the other two fail
    criteria_ = {
        {"gospa_mean_m", Scope::recording, Statistic::value, Bound::max, sorted[2] * 1.2, false},
        {"gospa_mean_m", Scope::recording, Statistic::value, Bound::max, threshold_, false},
        {"wasserstein1.background_range", Scope::recording, Statistic::value, Bound::max, 1.0, false},
        {"gospa_mean_m", Scope::campaign, Statistic::mean, Bound::max, sorted[2] * 1.2, false},
        {"gospa_mean_m", Scope::campaign, Statistic::max, Bound::max, sorted[1], false},
    };
    verdict::store_criteria(*db_, criteria_);
  }

  std::string write(HtmlReportOptions options = {}, const std::string& name = "campaign.html") {
    db_.reset();  // the report opens the file itself
    write_html_report_file(db_path_, (dir_ / name).string(), options);
    db_ = open_report_database(db_path_, false);
    return read_file(dir_ / name);
  }

  std::string db_path_;
  std::unique_ptr<replay::ReportDatabase> db_;
  std::vector<std::int64_t> ids_;
  std::vector<double> gospa_;  // by run
  std::vector<Criterion> criteria_;
  double threshold_ = 0.0;
};

TEST_F(CampaignReport, ListsTheFailedRunsAndTheCriteriaWithTheirValues) {
  replay_bundled();
  store_five_criteria();
  const std::string html = write();
  const std::string overview = between(html, "<section class=\"campaign\" id=\"campaign\">", "</section>");
  ASSERT_FALSE(overview.empty());
  // Before the runs' sections.
  EXPECT_LT(html.find("id=\"campaign\""), html.find("<section class=\"run\""));

  // Every run fails the missing figure; so all three fail.
  EXPECT_NE(overview.find(R"(data-key="runs_failed">3<)"), std::string::npos);
  EXPECT_NE(overview.find(R"(data-key="runs_passed">0<)"), std::string::npos);
  EXPECT_NE(overview.find(R"(data-key="campaign_passed">1<)"), std::string::npos);
  EXPECT_NE(overview.find(R"(data-key="verdict">FAIL<)"), std::string::npos);

  // The criteria table: the passing one, the failing one (two runs), the missing figure (three runs).
  const auto row = [&](int k) { return between(overview, fmt::format("data-criterion=\"{}\"", k), "</tr>"); };
  EXPECT_NE(row(0).find(R"(data-key="runs_failed">0 of 3<)"), std::string::npos) << row(0);
  EXPECT_NE(row(1).find(R"(data-key="runs_failed">2 of 3<)"), std::string::npos) << row(1);
  EXPECT_NE(row(2).find(R"(data-key="runs_failed">3 of 3<)"), std::string::npos) << row(2);
  EXPECT_NE(row(2).find("wasserstein1.background_range"), std::string::npos);
  // The campaign criteria's values, computed here: the mean and the max of the runs' GOSPA.
  const double mean = (gospa_[0] + gospa_[1] + gospa_[2]) / 3.0;
  const double max = *std::max_element(gospa_.begin(), gospa_.end());
  EXPECT_NE(row(3).find(fmt::format(R"(data-key="value">{}<)", report::figure_value(mean))), std::string::npos) << row(3);
  EXPECT_NE(row(3).find(R"(<td class="pass">pass<)"), std::string::npos) << row(3);
  EXPECT_NE(row(4).find(fmt::format(R"(data-key="value">{}<)", report::figure_value(max))), std::string::npos) << row(4);
  EXPECT_NE(row(4).find(R"(<td class="fail">FAIL<)"), std::string::npos) << row(4);

  // The failed runs, each with its failed criteria and values: the two worse runs fail criterion 1
  // with their GOSPA, all three the missing figure.
  const std::string failed = between(overview, "<table class=\"failed-runs\">", "</table>");
  EXPECT_EQ(count_occurrences(failed, "<tr class=\"fail\">"), 3u);
  for (std::size_t i = 0; i < ids_.size(); ++i) {
    const std::string run_row = between(failed, fmt::format(">run {}<", ids_[i]), "</tr>");
    ASSERT_FALSE(run_row.empty()) << "run " << ids_[i];
    EXPECT_NE(run_row.find("wasserstein1.background_range missing"), std::string::npos) << run_row;
    const std::string gospa_failure = fmt::format("gospa_mean_m = {:.6g} &gt; {:g}", gospa_[i], threshold_);
    EXPECT_EQ(run_row.find(gospa_failure) != std::string::npos, gospa_[i] > threshold_) << run_row;
  }

  // The worst runs by GOSPA, worst first; runs shown on the page link to their sections.
  const std::string worst = between(overview, "<tr data-figure=\"gospa_mean_m\">", "</tr>");
  std::vector<std::size_t> order = {0, 1, 2};
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return gospa_[a] > gospa_[b]; });
  std::size_t at = 0;
  for (const std::size_t i : order) {
    const auto pos = worst.find(fmt::format(R"(<a href="#run-{0}">run {0}</a>)", ids_[i]), at);
    ASSERT_NE(pos, std::string::npos) << worst;
    EXPECT_GE(pos, at);
    at = pos;
  }
  // Distributions: a quantile row per figure, a histogram with the four thresholds on GOSPA drawn.
  const std::string quantiles = between(overview, "<table class=\"quantiles\">", "</table>");
  const std::string gospa_row = between(quantiles, "<tr data-figure=\"gospa_mean_m\">", "</tr>");
  EXPECT_NE(gospa_row.find(fmt::format(R"(data-key="max">{}<)", report::figure_value(max))), std::string::npos);
  EXPECT_NE(gospa_row.find(fmt::format(R"(data-key="mean">{}<)", report::figure_value(mean))), std::string::npos);
  const std::string histogram = between(overview, "aria-label=\"gospa_mean_m\"", "</svg>");
  EXPECT_EQ(count_occurrences(histogram, "class=\"marker\""), 4u);
  EXPECT_NE(overview.find("data-figure=\"wasserstein1.range\""), std::string::npos);
  EXPECT_NE(overview.find("data-figure=\"wasserstein1.background_range\""), std::string::npos);
}

TEST_F(CampaignReport, EscapesTheRecordingAndCampaignNames) {
  db_path_ = (dir_ / "evil.sqlite").string();
  db_ = open_report_database(db_path_, true);
  {
    Recording rec = testing::model_recording(testing::two_cars_scene(2.0), 5);
    rec.dir = dir_ / "evil";
    rec.name = kEvilCampaignName;
    ReplayOptions options;
    options.import.effects = {};
    ReportWriter writer(*db_, StoreLevel::summary);
    replay_recording(rec, options, writer);
  }
  verdict::store_criteria(*db_, {{"gospa_mean_m", Scope::recording, Statistic::value, Bound::max, -1.0, false}});
  db_->exec("INSERT INTO campaign VALUES ('<b>bold</b> campaign', '{}')");
  const std::string html = write();
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("<b>"), std::string::npos);
  EXPECT_NE(html.find("&lt;b&gt;bold&lt;/b&gt; campaign"), std::string::npos);
  const std::string failed = between(html, "<table class=\"failed-runs\">", "</table>");
  EXPECT_NE(failed.find("&lt;script&gt;alert(1)&lt;/script&gt; &amp; &quot;x&quot; &#39;y&#39;"), std::string::npos)
      << failed;
  // The whole name as the tooltip of its shortened form.
  EXPECT_NE(html.find("title=\"&lt;script&gt;alert(1)&lt;/script&gt; &amp; &quot;x&quot; &#39;y&#39;\""), std::string::npos);
}

TEST_F(CampaignReport, OneRunJudgedByItsCriteriaHasNoOverview) {
  // rcsim replay --criteria FILE into a fresh report: the run's section opens with the verdict.
  db_path_ = (dir_ / "one.sqlite").string();
  db_ = open_report_database(db_path_, true);
  {
    Recording rec = testing::model_recording(testing::two_cars_scene(2.0), 5);
    rec.dir = dir_ / "one";
    rec.name = "one";
    ReplayOptions options;
    options.import.effects = {};
    ReportWriter writer(*db_, StoreLevel::summary);
    replay_recording(rec, options, writer);
  }
  verdict::store_criteria(*db_, {{"gospa_mean_m", Scope::recording, Statistic::value, Bound::max, 1.0, false}});
  std::string html = write();
  EXPECT_EQ(html.find("id=\"campaign\""), std::string::npos);
  EXPECT_NE(html.find("id=\"run-1\""), std::string::npos);
  // Named a campaign, the same database opens with the overview.
  db_->exec("INSERT INTO campaign VALUES ('q3', '{}')");
  html = write();
  EXPECT_NE(html.find("id=\"campaign\""), std::string::npos);
}

TEST_F(CampaignReport, ADatabaseWithoutCriteriaAndWithFewRunsRendersAsBefore) {
  replay_bundled();
  const std::string automatic = write();
  EXPECT_EQ(automatic.find("id=\"campaign\""), std::string::npos);
  HtmlReportOptions never;
  never.campaign = CampaignOverview::never;
  EXPECT_EQ(write(never, "never.html"), automatic);
  // Asked for, it shows the runs' figures without verdicts.
  HtmlReportOptions always;
  always.campaign = CampaignOverview::always;
  const std::string with = write(always, "always.html");
  EXPECT_NE(with.find("id=\"campaign\""), std::string::npos);
  EXPECT_NE(with.find("holds no criteria"), std::string::npos);
  EXPECT_EQ(with.find("<table class=\"failed-runs\">"), std::string::npos);
  EXPECT_EQ(count_occurrences(with, "<section class=\"run\""), 3u);
}

TEST_F(CampaignReport, ManyRunsGetTheOverviewAndOnlyTheLastRunsInDetail) {
  replay_bundled();
  copy_run(*db_, ids_[0], 22);  // 25 runs, no criteria
  const std::string html = write();
  EXPECT_NE(html.find("id=\"campaign\""), std::string::npos);
  EXPECT_EQ(count_occurrences(html, "<section class=\"run\""), 20u);
  EXPECT_NE(html.find("20 of its 25 runs shown in detail"), std::string::npos);
  // Run 1 is not on the page: its tooltip gives the command that renders it.
  EXPECT_NE(html.find(fmt::format("title=\"rcsim report {} --run 1 -o run-1.html\"", db_path_)), std::string::npos);
  EXPECT_EQ(html.find("href=\"#run-1\""), std::string::npos);
  // With --run, no overview: the page of one run, as the tooltip's command writes it.
  HtmlReportOptions one;
  one.run_ids = {1};
  const std::string page = write(one, "run-1.html");
  EXPECT_EQ(page.find("id=\"campaign\""), std::string::npos);
  EXPECT_EQ(count_occurrences(page, "<section class=\"run\""), 1u);
  // The overview alone.
  HtmlReportOptions only;
  only.campaign = CampaignOverview::only;
  const std::string overview = write(only, "only.html");
  EXPECT_NE(overview.find("id=\"campaign\""), std::string::npos);
  EXPECT_EQ(overview.find("<section class=\"run\""), std::string::npos);
  EXPECT_EQ(overview.find("Runs side by side"), std::string::npos);
}

TEST_F(CampaignReport, CapsTheFailedRunsAndFoldsTheRest) {
  replay_bundled();
  copy_run(*db_, ids_[0], 7);  // 10 runs
  verdict::store_criteria(*db_, {{"gospa_mean_m", Scope::recording, Statistic::value, Bound::max, -1.0, false},
                                  {"replay_wall_s", Scope::recording, Statistic::value, Bound::max, 3600.0, false}});
  HtmlReportOptions options;
  options.campaign_failed_rows = 4;
  const std::string html = write(options);
  EXPECT_NE(html.find("6 more failed runs"), std::string::npos);
  const std::string first = between(html, "<table class=\"failed-runs\">", "</table>");
  EXPECT_EQ(count_occurrences(first, "<tr class=\"fail\">"), 4u);
  const std::string rest = between(html, "<details class=\"failed-rest\">", "</details>");
  EXPECT_EQ(count_occurrences(rest, "<tr class=\"fail\">"), 6u);
  for (int id = 1; id <= 10; ++id) {
    EXPECT_EQ(count_occurrences(first + rest, fmt::format("run {}<", id)), 1u) << id;
  }
  // A threshold far beyond the values is named, not drawn: the runs keep the axis.
  const std::string wall = between(html, "aria-label=\"replay_wall_s\"", "</svg>");
  EXPECT_NE(wall.find("\u2264 3600 right of the axis"), std::string::npos) << wall;
  EXPECT_EQ(count_occurrences(wall, "class=\"marker\""), 0u);
}

TEST_F(CampaignReport, RunsDirHoldsThePagesOfTheListedRunsLinkedBothWays) {
  replay_bundled();
  store_five_criteria();
  HtmlReportOptions options;
  options.last_runs = 1;
  options.runs_dir = (dir_ / "out" / "campaign runs").string();  // a space: percent-encoded in the links
  fs::create_directories(dir_ / "out");
  db_.reset();
  const int pages = write_html_report_file(db_path_, (dir_ / "out" / "campaign.html").string(), options);
  db_ = open_report_database(db_path_, false);
  const std::string html = read_file(dir_ / "out" / "campaign.html");
  // Run 3 is detailed on the page, runs 1 and 2 (failed, and among the worst) get pages.
  EXPECT_EQ(pages, 2);
  EXPECT_NE(html.find(R"(<a href="#run-3">run 3</a>)"), std::string::npos);
  for (int id : {1, 2}) {
    EXPECT_NE(html.find(fmt::format(R"(<a href="campaign%20runs/run-{0}.html">run {0}</a>)", id)), std::string::npos);
    const std::string page = read_file(dir_ / "out" / "campaign runs" / fmt::format("run-{}.html", id));
    EXPECT_NE(page.find(R"(<a href="../campaign.html#campaign">)"), std::string::npos);
    EXPECT_EQ(count_occurrences(page, "<section class=\"run\""), 1u);
    EXPECT_NE(page.find(fmt::format("id=\"run-{}\"", id)), std::string::npos);
    EXPECT_EQ(page.find("id=\"campaign\""), std::string::npos);
  }
  EXPECT_FALSE(fs::exists(dir_ / "out" / "campaign runs" / "run-3.html"));
}

TEST(CampaignWorstRuns, ByEachDirection) {
  report::CampaignData data;
  data.figures = {{"higher", "1", "", verdict::Worse::higher},
                  {"lower", "1", "", verdict::Worse::lower},
                  {"zero", "1", "", verdict::Worse::away_from_zero},
                  {"one", "1", "", verdict::Worse::away_from_one}};
  const std::vector<double> values = {0.5, 2.0, -3.0, 1.0, 0.9};
  for (std::size_t i = 0; i < values.size(); ++i) {
    verdict::RunFigureRow row;
    row.run_id = static_cast<std::int64_t>(i + 1);
    row.values.assign(4, values[i]);
    if (i == 3) row.values[0].reset();  // missing: never ranked
    data.runs.push_back(row);
  }
  const auto ids = [&](std::size_t figure, int n) {
    std::vector<std::int64_t> out;
    for (const std::size_t r : report::worst_runs(data, figure, n)) out.push_back(data.runs[r].run_id);
    return out;
  };
  EXPECT_EQ(ids(0, 3), (std::vector<std::int64_t>{2, 5, 1}));
  EXPECT_EQ(ids(0, 10), (std::vector<std::int64_t>{2, 5, 1, 3}));
  EXPECT_EQ(ids(1, 2), (std::vector<std::int64_t>{3, 1}));
  EXPECT_EQ(ids(2, 2), (std::vector<std::int64_t>{3, 2}));
  EXPECT_EQ(ids(3, 3), (std::vector<std::int64_t>{3, 2, 1}));  // |v - 1|: 4, 1, 0.5
  EXPECT_EQ(quantile_of_sorted({1.0, 2.0, 3.0, 4.0}, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(quantile_of_sorted({1.0, 2.0, 3.0, 4.0}, 0.95), 3.85);
}

TEST(CampaignReportCli, CampaignOnlyAndABadValue) {
  const fs::path dir = rcsim::testing::fresh_scratch_dir("campaign_report_cli");
  const std::string db = (dir / "r.sqlite").string();
  {
    const auto handle = open_report_database(db, true);
    ReportWriter writer(*handle, StoreLevel::summary);
    replay_recording_dir(fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / "front_approach", ReplayOptions{}, writer);
  }
  const std::string base = std::string(RCSIM_BINARY) + " report " + db + " -o " + (dir / "o.html").string();
  int status = std::system((base + " --campaign only 2> /dev/null").c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  const std::string html = read_file(dir / "o.html");
  EXPECT_NE(html.find("id=\"campaign\""), std::string::npos);
  EXPECT_EQ(html.find("<section class=\"run\""), std::string::npos);
  status = std::system((base + " --campaign sometimes 2> /dev/null").c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_NE(WEXITSTATUS(status), 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rcsim::replay
