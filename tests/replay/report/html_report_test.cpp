#include "replay/report/html_report.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <sys/wait.h>

#include "common/input_error.hpp"
#include "replay/replay_fixtures.hpp"
#include "replay/store/report_store.hpp"

namespace rcsim::replay {
namespace {

namespace fs = std::filesystem;

constexpr const char* kEvilName = "<script>alert(1)</script> & \"x\"";
constexpr const char* kEvilObject = "<img src=x onerror=\"document.body.setAttribute('data-pwned','1')\">";

// Two runs: the two-car scene against another seed (recording text made hostile), and two cars
// abreast in one cell for merge artefacts.
void fill_database(const fs::path& dir, const std::string& path) {
  const auto db = open_report_database(path, true);
  {
    const Scene scene = testing::two_cars_scene(3.0);
    Recording rec = testing::model_recording(scene, 5);
    rec.dir = dir / "evil";
    rec.name = kEvilName;
    rec.objects[0].id = kEvilObject;
    rec.sensors[1].id = "<i>front_right</i>";
    rec.source = {{"generator", "</pre><script>alert(2)</script>"}};
    ReplayOptions options;
    options.seed = 6;
    options.import.effects = {};
    ReportWriter writer(*db);
    replay_recording(rec, options, writer);
  }
  {
    Scene scene = testing::two_cars_scene(4.0);
    scene.sensors.resize(1);
    scene.sensors.front().X_VS = {3.7, 0.0, 0.0};
    Recording rec = testing::model_recording(scene, 3);
    rec.dir = dir / "merge";
    rec.name = "merge";
    ReplayOptions options;
    options.seed = 4;
    options.import.effects = {};
    ReportWriter writer(*db);
    replay_recording(rec, options, writer);
  }
}

using testing::count_occurrences;
using testing::read_file;


class HtmlReport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("rcsim_html_report_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    fill_database(dir_, db_path());
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static std::string db_path() { return (dir_ / "r.sqlite").string(); }
  static std::string write(const HtmlReportOptions& options, const std::string& name = "r.html") {
    write_html_report_file(db_path(), (dir_ / name).string(), options);
    return read_file(dir_ / name);
  }
  static inline fs::path dir_;
};

TEST_F(HtmlReport, EscapesEveryTextFromTheRecording) {
  const std::string html = write({});
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("<img"), std::string::npos);
  EXPECT_EQ(html.find("<i>"), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;alert(1)&lt;/script&gt; &amp; &quot;x&quot;"), std::string::npos);
  EXPECT_NE(html.find("&lt;img src=x onerror=&quot;document.body.setAttribute(&#39;data-pwned&#39;"), std::string::npos);
  EXPECT_NE(html.find("&lt;i&gt;front_right&lt;/i&gt;"), std::string::npos);
  EXPECT_NE(html.find("&lt;/pre&gt;&lt;script&gt;alert(2)"), std::string::npos);
}

TEST_F(HtmlReport, SummaryTablesShowTheStoredValues) {
  const std::string html = write({});
  const auto db = open_report_database(db_path(), false);
  SQLite::Statement q(*db, "SELECT run_id, targets_recorded, targets_simulated, merge_artefacts_recorded FROM summaries");
  int runs = 0;
  while (q.executeStep()) {
    ++runs;
    const auto id = q.getColumn(0).getInt64();
    const auto section = html.substr(html.find("id=\"run-" + std::to_string(id) + "\""));
    EXPECT_NE(section.find("data-key=\"targets_recorded\">" + std::to_string(q.getColumn(1).getInt64()) + "<"),
              std::string::npos);
    EXPECT_NE(section.find("data-key=\"targets_simulated\">" + std::to_string(q.getColumn(2).getInt64()) + "<"),
              std::string::npos);
    EXPECT_NE(section.find("data-key=\"merge_recorded\">" + std::to_string(q.getColumn(3).getInt64()) + "<"),
              std::string::npos);
  }
  EXPECT_EQ(runs, 2);
  EXPECT_GT(std::stoll(html.substr(html.rfind("data-key=\"merge_recorded\">") + 26)), 0);
}

TEST_F(HtmlReport, HasPicturesPerRunAndTheSideBySideOfSeveralRuns) {
  const std::string html = write({});
  EXPECT_NE(html.find("Runs side by side"), std::string::npos);
  EXPECT_EQ(testing::count_occurrences(html, "<section class=\"run\""), 2u);
  const std::size_t birdseye = testing::count_occurrences(html, "<svg class=\"birdseye\"");
  EXPECT_GE(birdseye, 6u);  // at least three cycles per run
  EXPECT_LE(birdseye, 10u);
  // Per sensor four time series (run 1 has two sensors, run 2 one), and per run the detection
  // rate against range and the background's range and azimuth.
  EXPECT_EQ(testing::count_occurrences(html, "<svg class=\"plot\""), 18u);
  EXPECT_EQ(testing::count_occurrences(html, "<svg class=\"histogram\""), 8u);
  EXPECT_GT(testing::count_occurrences(html, "<circle class=\"t rec current\""), 10u);
  EXPECT_GT(testing::count_occurrences(html, "<polygon class=\"t sim current\""), 10u);
  EXPECT_GT(testing::count_occurrences(html, "<polygon class=\"t sim trace\""), 10u);
  EXPECT_GE(testing::count_occurrences(html, "<polygon class=\"fov\""), 6u);
  EXPECT_GE(testing::count_occurrences(html, "<polygon class=\"box\""), 6u);
  EXPECT_GE(testing::count_occurrences(html, "<circle class=\"merge\""), 1u);
  // Each run says how to get every row the page thins (issue 52).
  EXPECT_EQ(testing::count_occurrences(html, "<p class=\"hint rows-query\">"), 2u);
  EXPECT_NE(html.find("--run 1 --table targets</code>"), std::string::npos);
  EXPECT_NE(html.find("most merge artefacts"), std::string::npos);
  EXPECT_NE(html.find("largest GOSPA"), std::string::npos);
  EXPECT_NE(html.find("Generalized optimal sub-pattern assignment"), std::string::npos);  // cited source
  // Nothing the page would fetch.
  EXPECT_EQ(html.find("src="), html.find("src=x"));
  EXPECT_EQ(html.find("href=\"http"), std::string::npos);
}

TEST_F(HtmlReport, OneSelectedRunHasNoSideBySide) {
  HtmlReportOptions options;
  options.run_ids = {2};
  const std::string html = write(options);
  EXPECT_EQ(html.find("Runs side by side"), std::string::npos);
  EXPECT_EQ(testing::count_occurrences(html, "<section class=\"run\""), 1u);
  EXPECT_NE(html.find("id=\"run-2\""), std::string::npos);
  options.run_ids = {};
  options.last_runs = 1;
  EXPECT_EQ(write(options), html);  // the last run by default, and deterministic
}

TEST_F(HtmlReport, UnknownRunIsAnInputErrorNamingDatabaseAndId) {
  HtmlReportOptions options;
  options.run_ids = {1, 77};
  const fs::path out = dir_ / "unknown.html";
  try {
    write_html_report_file(db_path(), out.string(), options);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(db_path()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("77"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(HtmlReport, CommandLineExitsWith2OnAnUnknownRunAndWritesTheFileOtherwise) {
  const fs::path out = dir_ / "cli.html";
  const std::string base = std::string(RCSIM_BINARY) + " report " + db_path() + " -o " + out.string();
  int status = std::system((base + " --run 9 2> " + (dir_ / "err.txt").string()).c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_NE(read_file(dir_ / "err.txt").find("no run with id 9"), std::string::npos);
  EXPECT_FALSE(fs::exists(out));
  status = std::system((base + " --run 1 --run 2 2> /dev/null").c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_NE(read_file(out).find("Runs side by side"), std::string::npos);
  status = std::system((std::string(RCSIM_BINARY) + " report " + out.string() + " -o " + (dir_ / "x.html").string() +
                        " 2> /dev/null").c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2);  // not a report database
}

// An hour-like run written straight into the tables: the page thins its series and stays small.
TEST(HtmlReportLarge, LongRunsAreThinnedAndTheFileStaysSmall) {
  const fs::path dir = fs::temp_directory_path() / ("rcsim_html_large_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "big.sqlite").string();
  constexpr int kCycles = 30000;
  {
    const auto db = open_report_database(path, true);
    SQLite::Transaction transaction(*db);
    db->exec("INSERT INTO runs VALUES (1, 'big', '/x', '0000000000000000', '{}', 0.04, 30000, 1, 'tracks', '{}', "
             "'0', '2024-01-01T00:00:00Z', 'full')");
    db->exec("INSERT INTO run_sensors VALUES (1, 0, 's', 'srr24', 3.7, 0, 0, 1.0, 50, '{}')");
    db->exec("INSERT INTO run_objects VALUES (1, 0, 'car', 'passenger_car', 4.5, 1.8, 10)");
    RunRowWriter rows(*db, 1, StoreLevel::full, 2.0, 2.0);
    for (int k = 0; k < kCycles; ++k) {
      const double range_m = 10.0 + 5.0 * std::sin(k * 1e-3);
      StoredCycle c;
      c.cycle = k;
      c.t_s = 0.04 * k;
      c.X_WS = Pose2{3.7, 0, 0};
      c.n_recorded = c.n_simulated = c.n_assigned = 2;
      c.gospa_m = 0.1 + 0.05 * std::sin(k * 0.01);
      c.gospa_localisation_mp = 0.1;
      c.ospa_m = 0.1;
      std::vector<StoredTarget> lists[2];
      for (int origin = 0; origin < 2; ++origin) {
        for (int i = 0; i < 2; ++i) {
          StoredTarget t;
          t.range_m = range_m + i + 0.05 * origin;
          t.azimuth_rad = 0.1;
          t.range_rate_mps = -1;
          t.amplitude_db = 20;
          t.object = 0;
          t.match_idx = i;
          lists[origin].push_back(t);
        }
      }
      rows.add_cycle(c, lists[0], lists[1]);
      rows.add_object_states(k, {{k, 0, Pose2{range_m + 6.0, 0, 3.14}}});
    }
    rows.finish();
    db->exec("INSERT INTO summaries VALUES (1, 30000, 60000, 60000, 60000, 0.1, 0.1, 0.01, 0, 0, 0, 0, 0, NULL, NULL, 0, "
             "0.05, 0, 0, 0, 1, 2, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL)");
    transaction.commit();
  }
  HtmlReportOptions options;
  options.max_points = 2000;
  write_html_report_file(path, (dir / "big.html").string(), options);
  const std::string html = read_file(dir / "big.html");
  EXPECT_LT(html.size(), 1'500'000u);
  EXPECT_NE(html.find("every 15th cycle shown"), std::string::npos);
  EXPECT_NE(html.find("mean over 15 cycles per point"), std::string::npos);
  int series = 0;
  for (const char* kind : {"class=\"series dots\" d=\"", "class=\"series line\" d=\""}) {
    for (auto pos = html.find(kind); pos != std::string::npos; pos = html.find(kind, pos + 1)) {
      const std::size_t begin = pos + std::string(kind).size();
      const std::string d = html.substr(begin, html.find('"', begin) - begin);
      const std::size_t points = testing::count_occurrences(d, "M") + testing::count_occurrences(d, "L");
      EXPECT_LE(points, 2000u);
      EXPECT_GE(points, 1900u);
      ++series;
    }
  }
  EXPECT_EQ(series, 8);  // range, lateral, counts (recorded and simulated each), GOSPA mean and max
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rcsim::replay
