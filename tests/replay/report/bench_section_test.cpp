// The "Speed against error" section of the HTML report: bench rows written straight into the
// report database with hand-chosen numbers, then the page checked against the hand-computed
// aggregates, the Pareto front, the axes and the escaping.
#include "replay/report/bench_section.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <regex>

#include "common/input_error.hpp"
#include "replay/report/html_report.hpp"
#include "replay/store/report_store.hpp"
#include "replay/report/svg_pareto.hpp"
#include "replay/replay_fixtures.hpp"

namespace rcsim::replay {
namespace {

namespace fs = std::filesystem;

using testing::count_occurrences;
using testing::read_file;

constexpr const char* kEvilLevelName = "<script>alert(1)</script>";

struct Row {
  int recording = 0;
  std::string name;
  std::string level;
  std::int64_t sensor_cycles = 0;
  std::optional<double> cpu_s;
  double gospa_mean_m = 0.0;
  std::int64_t targets_recorded = 100, targets_simulated = 100;
  std::optional<double> targets_per_cycle_ratio = 1.0;
  std::int64_t merge_recorded = 0, merge_found = 0, merge_missed = 0, merge_spurious = 0;
  std::optional<double> latency_difference_s;
  std::int64_t latency_pairs = 0;
};

std::int64_t insert_bench(SQLite::Database& db, std::int64_t seed, const std::string& machine) {
  SQLite::Statement q(db,
                      "INSERT INTO bench_runs (seed, machine, parameters, rcsim_version, created_utc) "
                      "VALUES (?, ?, ?, ?, ?)");
  q.bind(1, seed);
  q.bind(2, machine);
  q.bind(3, R"({"timing": "CPU time of the simulation passes", "note": "</pre><b>x</b>"})");
  q.bind(4, "0.1.0");
  q.bind(5, "2025-01-02T03:04:05Z");
  q.exec();
  return db.getLastInsertRowid();
}

void bind_optional(SQLite::Statement& q, int index, const std::optional<double>& value) {
  if (value) {
    q.bind(index, *value);
  } else {
    q.bind(index);
  }
}

void insert_row(SQLite::Database& db, std::int64_t bench_id, const Row& r) {
  SQLite::Statement q(
      db,
      "INSERT INTO bench_rows (bench_id, recording, recording_name, recording_checksum, level, "
      "sensor_cycles, cpu_s, sensor_cycles_per_cpu_s, gospa_mean_m, targets_recorded, targets_simulated, "
      "targets_per_cycle_ratio, merge_artefacts_recorded, merge_artefacts_found, merge_artefacts_missed, "
      "merge_artefacts_spurious, latency_difference_s, latency_pairs) "
      "VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  int i = 1;
  q.bind(i++, bench_id);
  q.bind(i++, r.recording);
  q.bind(i++, r.name);
  q.bind(i++, r.recording == 0 ? "00000000000000aa" : "00000000000000bb");
  q.bind(i++, r.level);
  q.bind(i++, r.sensor_cycles);
  bind_optional(q, i++, r.cpu_s);
  bind_optional(q, i++,
                r.cpu_s ? std::optional<double>(static_cast<double>(r.sensor_cycles) / *r.cpu_s) : std::nullopt);
  q.bind(i++, r.gospa_mean_m);
  q.bind(i++, r.targets_recorded);
  q.bind(i++, r.targets_simulated);
  bind_optional(q, i++, r.targets_per_cycle_ratio);
  q.bind(i++, r.merge_recorded);
  q.bind(i++, r.merge_found);
  q.bind(i++, r.merge_missed);
  q.bind(i++, r.merge_spurious);
  bind_optional(q, i++, r.latency_difference_s);
  q.bind(i++, r.latency_pairs);
  q.exec();
}

// Two recordings (1000 and 3000 sensor cycles) x six levels. Aggregates, by hand:
//   level         sum cycles / sum CPU s        mean GOSPA       / noise floor 0.40
//   reference     4000 / (4 + 16)     = 200     (0.5 + 0.7) / 2 = 0.6   1.50
//   noise_floor   -                             (0.3 + 0.5) / 2 = 0.4   1.00
//   full          4000 / 0.010 = 400000         (0.8 + 1.0) / 2 = 0.9   2.25
//   no_monopulse  4000 / 0.005 = 800000         1.2                     3.00
//   points_only   4000 / 0.008 = 500000         1.5 (dominated by no_monopulse)
//   no_tracking   4000 / 0.002 = 2000000        2.0                     5.00
// The mean of the per-recording speeds of the reference would be (250 + 187.5) / 2 = 218.75.
std::vector<Row> two_recordings(const std::string& second_name, bool with_reference) {
  struct Level {
    const char* level;
    std::optional<double> cpu0, cpu1;
    double gospa0, gospa1;
  };
  const std::vector<Level> levels{{"reference", 4.0, 16.0, 0.5, 0.7},      {"noise_floor", {}, {}, 0.3, 0.5},
                                  {"full", 0.004, 0.006, 0.8, 1.0},        {"no_monopulse", 0.002, 0.003, 1.1, 1.3},
                                  {"points_only", 0.003, 0.005, 1.4, 1.6}, {"no_tracking", 0.001, 0.001, 1.9, 2.1}};
  std::vector<Row> rows;
  for (const Level& l : levels) {
    if (!with_reference && (std::string(l.level) == "reference" || std::string(l.level) == "noise_floor")) continue;
    for (int recording = 0; recording < 2; ++recording) {
      Row r;
      r.recording = recording;
      r.name = recording == 0 ? "urban" : second_name;
      r.level = l.level;
      r.sensor_cycles = recording == 0 ? 1000 : 3000;
      r.cpu_s = recording == 0 ? l.cpu0 : l.cpu1;
      r.gospa_mean_m = recording == 0 ? l.gospa0 : l.gospa1;
      rows.push_back(r);
    }
  }
  // The default level's other columns: sums and means of non-NULL values to check.
  for (Row& r : rows) {
    if (r.level != "full") continue;
    if (r.recording == 0) {
      r.targets_per_cycle_ratio = 0.9;
      r.merge_recorded = 4, r.merge_found = 3, r.merge_missed = 1, r.merge_spurious = 2;
      r.latency_difference_s = 0.1;
      r.latency_pairs = 3;
    } else {
      r.targets_per_cycle_ratio = 1.2;
      r.merge_recorded = 6, r.merge_found = 5, r.merge_missed = 1, r.merge_spurious = 0;
      r.latency_difference_s = std::nullopt;  // no paired episode: left out of the mean
    }
  }
  return rows;
}

// A run with one sensor and one cycle, enough for the run sections.
void insert_minimal_run(SQLite::Database& db, int run_id) {
  SQLite::Statement run(db,
                        "INSERT INTO runs VALUES (?, 'minimal', '/x', '0000000000000000', '{}', 0.04, 1, 1, "
                        "'tracks', '{}', '0', '2024-01-01T00:00:00Z', 'full')");
  run.bind(1, run_id);
  run.exec();
  SQLite::Statement sensor(db, "INSERT INTO run_sensors VALUES (?, 0, 's', 'srr24', 3.7, 0, 0, 1.0, 50, '{}')");
  sensor.bind(1, run_id);
  sensor.exec();
  RunRowWriter rows(db, run_id, StoreLevel::full, 2.0, 2.0);
  StoredCycle cycle;
  cycle.X_WS = Pose2{3.7, 0, 0};
  rows.add_cycle(cycle, {}, {});
  rows.finish();
  SQLite::Statement summary(db,
                            "INSERT INTO summaries VALUES (?, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, NULL, NULL, 0, "
                            "0, 0, 0, 0, 1, 2, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL)");
  summary.bind(1, run_id);
  summary.exec();
}

// The first pareto plot of the page (the one over all recordings).
std::string main_plot(const std::string& html) {
  const std::size_t begin = html.find("<svg class=\"pareto\"");
  if (begin == std::string::npos) return {};
  return html.substr(begin, html.find("</svg>", begin) + 6 - begin);
}

// The centre of a level's marker in a plot.
std::pair<double, double> marker(const std::string& svg, const std::string& level) {
  const std::regex re("data-level=\"" + level + "\"><title>[^<]*</title><circle cx=\"([-0-9.]+)\" cy=\"([-0-9.]+)\"");
  std::smatch m;
  if (!std::regex_search(svg, m, re)) return {std::nan(""), std::nan("")};
  return {std::stod(m[1]), std::stod(m[2])};
}

// The cells of a level's row in the table of the given class.
std::vector<std::string> table_row(const std::string& html, const std::string& table_class, const std::string& level) {
  const std::size_t table = html.find("<table class=\"" + table_class + "\"");
  const std::size_t row = html.find("<tr data-level=\"" + level + "\"", table);
  const std::size_t end = html.find("</tr>", row);
  std::vector<std::string> cells;
  if (table == std::string::npos || row == std::string::npos) return cells;
  const std::string text = html.substr(row, end - row);
  const std::regex cell_re("<td[^>]*>([^<]*)</td>");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), cell_re); it != std::sregex_iterator(); ++it) {
    cells.push_back((*it)[1]);
  }
  return cells;
}

class HtmlReportBench : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rcsim_html_bench_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    db_ = open_report_database(db_path(), true);
  }
  void TearDown() override {
    db_.reset();
    fs::remove_all(dir_);
  }
  std::string db_path() const { return (dir_ / "r.sqlite").string(); }
  std::int64_t add_bench(const std::vector<Row>& rows, std::int64_t seed = 7) {
    const std::int64_t id = insert_bench(*db_, seed, "2-core AMD EPYC <test>");
    for (const Row& r : rows) insert_row(*db_, id, r);
    return id;
  }
  std::string write(const HtmlReportOptions& options = {}) {
    write_html_report_file(db_path(), (dir_ / "r.html").string(), options);
    return read_file(dir_ / "r.html");
  }

  fs::path dir_;
  std::unique_ptr<replay::ReportDatabase> db_;
};

TEST_F(HtmlReportBench, LevelTableShowsTheHandComputedAggregates) {
  add_bench(two_recordings("highway", true));
  const std::string html = write();
  // level, recordings, sensor cycles, CPU s, cycles per CPU s, GOSPA, / noise floor, targets ratio,
  // merge recorded, found, missed, spurious, latency difference, latency pairs, Pareto front.
  const auto reference = table_row(html, "bench-levels", "reference");
  ASSERT_EQ(reference.size(), 15u);
  EXPECT_EQ(reference[2], "4000");
  EXPECT_EQ(reference[3], "20.000");
  EXPECT_EQ(reference[4], "200");  // summed cycles over summed CPU time, not the mean of the speeds (218.75)
  EXPECT_EQ(reference[5], "0.600");
  EXPECT_EQ(reference[6], "1.50");
  EXPECT_EQ(reference[14], "yes");
  const auto floor = table_row(html, "bench-levels", "noise_floor");
  ASSERT_EQ(floor.size(), 15u);
  EXPECT_EQ(floor[3], "\u2014");
  EXPECT_EQ(floor[4], "\u2014");
  EXPECT_EQ(floor[5], "0.400");
  EXPECT_EQ(floor[14], "\u2014");
  const auto full = table_row(html, "bench-levels", "full");
  ASSERT_EQ(full.size(), 15u);
  EXPECT_EQ(full[1], "2");
  EXPECT_EQ(full[4], "400000");
  EXPECT_EQ(full[5], "0.900");
  EXPECT_EQ(full[6], "2.25");
  EXPECT_EQ(full[7], "1.050");
  EXPECT_EQ(full[8], "10");
  EXPECT_EQ(full[9], "8");
  EXPECT_EQ(full[10], "2");
  EXPECT_EQ(full[11], "2");
  EXPECT_EQ(full[12], "0.100");  // the mean of the non-NULL value only
  EXPECT_EQ(full[13], "3");
  EXPECT_EQ(table_row(html, "bench-levels", "no_monopulse")[4], "800000");
  EXPECT_EQ(table_row(html, "bench-levels", "points_only")[4], "500000");
  EXPECT_EQ(table_row(html, "bench-levels", "points_only")[5], "1.500");
  EXPECT_EQ(table_row(html, "bench-levels", "points_only")[14], "no");
  EXPECT_EQ(table_row(html, "bench-levels", "no_tracking")[4], "2000000");
  EXPECT_EQ(table_row(html, "bench-levels", "no_tracking")[6], "5.00");
  // The row table: per recording, with its own noise floor (0.8 / 0.3) and "—" for NULL.
  const auto full_row = table_row(html, "bench-rows", "full");
  ASSERT_EQ(full_row.size(), 15u);
  EXPECT_EQ(full_row[1], "urban");
  EXPECT_EQ(full_row[5], "250000");
  EXPECT_EQ(full_row[7], "2.67");
  const std::string rows = html.substr(html.find("<table class=\"bench-rows\""));
  EXPECT_EQ(count_occurrences(rows, "<tr data-level="), 12u);
  EXPECT_NE(rows.find("<td class=\"num\">\u2014</td>"), std::string::npos);
}

TEST_F(HtmlReportBench, ParetoFrontLeavesOutTheDominatedLevel) {
  add_bench(two_recordings("highway", true));
  const std::string svg = main_plot(write());
  ASSERT_FALSE(svg.empty());
  EXPECT_EQ(count_occurrences(svg, "<g class=\"point front"), 4u);
  EXPECT_EQ(count_occurrences(svg, "<g class=\"point dominated"), 1u);
  EXPECT_NE(svg.find("<g class=\"point dominated\" data-level=\"points_only\">"), std::string::npos);
  EXPECT_EQ(svg.find("data-level=\"noise_floor\""), std::string::npos);  // a line, not a point
  for (const char* level : {"reference", "full", "no_monopulse", "no_tracking"}) {
    EXPECT_NE(svg.find(std::string("front") + (std::string(level) == "full" ? " default" : "") + "\" data-level=\"" +
                       level + "\""),
              std::string::npos)
        << level;
  }
  // The front is one line through its four levels, slowest first.
  const std::regex front_re("<path class=\"front\" d=\"([^\"]*)\"");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, front_re));
  const std::string d = m[1];
  EXPECT_EQ(count_occurrences(d, "M"), 1u);
  EXPECT_EQ(count_occurrences(d, "L"), 3u);
  const auto [x_ref, y_ref] = marker(svg, "reference");
  EXPECT_EQ(d.rfind("M", 0), 0u);
  EXPECT_EQ(std::stod(d.substr(1)), x_ref);
  // Every level is labelled with its name.
  for (const char* level : {"reference", "full", "no_monopulse", "points_only", "no_tracking"}) {
    EXPECT_NE(svg.find(std::string(">") + level + "</text>"), std::string::npos) << level;
  }
}

TEST_F(HtmlReportBench, PointsSitOnALogSpeedAxisAndALinearErrorAxis) {
  add_bench(two_recordings("highway", true));
  const std::string svg = main_plot(write());
  const auto [x_ref, y_ref] = marker(svg, "reference");
  const auto [x_full, y_full] = marker(svg, "full");
  const auto [x_po, y_po] = marker(svg, "points_only");
  const auto [x_nt, y_nt] = marker(svg, "no_tracking");
  ASSERT_TRUE(std::isfinite(x_ref) && std::isfinite(x_full) && std::isfinite(x_po) && std::isfinite(x_nt));
  // x: log10 of the aggregate speed (200, 400000, 500000, 2000000), up to the 0.1 px rounding.
  const double span = std::log10(2e6) - std::log10(200.0);
  EXPECT_NEAR((x_full - x_ref) / (x_nt - x_ref), (std::log10(4e5) - std::log10(200.0)) / span, 1e-3);
  EXPECT_NEAR((x_po - x_ref) / (x_nt - x_ref), (std::log10(5e5) - std::log10(200.0)) / span, 1e-3);
  // y: mean GOSPA (0.6, 0.9, 1.5, 2.0), larger error drawn higher (smaller y).
  EXPECT_NEAR((y_full - y_ref) / (y_nt - y_ref), (0.9 - 0.6) / (2.0 - 0.6), 1e-3);
  EXPECT_NEAR((y_po - y_ref) / (y_nt - y_ref), (1.5 - 0.6) / (2.0 - 0.6), 1e-3);
  EXPECT_LT(y_nt, y_ref);
  // Ticks at powers of ten, 10² to 10⁶ at least.
  for (const char* tick : {">10\u00b2<", ">10\u00b3<", ">10\u2074<", ">10\u2075<", ">10\u2076<"}) {
    EXPECT_NE(svg.find(tick), std::string::npos) << tick;
  }
  EXPECT_NE(svg.find("log scale"), std::string::npos);
  EXPECT_NE(svg.find("mean over the recordings"), std::string::npos);
}

TEST_F(HtmlReportBench, DrawsTheNoiseFloorAndHighlightsTheDefaultLevel) {
  add_bench(two_recordings("highway", true));
  const std::string html = write();
  const std::string svg = main_plot(html);
  const std::regex floor_re("<line class=\"noise-floor\" x1=\"[-0-9.]+\" y1=\"([-0-9.]+)\"");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, floor_re));
  const auto [x_ref, y_ref] = marker(svg, "reference");
  const auto [x_nt, y_nt] = marker(svg, "no_tracking");
  // Where the error axis puts 0.4 m, from the markers at 0.6 m and 2.0 m.
  const double y_floor = y_ref + (0.4 - 0.6) * (y_nt - y_ref) / (2.0 - 0.6);
  EXPECT_NEAR(std::stod(m[1]), y_floor, 0.2);
  EXPECT_NE(svg.find("noise floor 0.400 m</text>"), std::string::npos);
  // The default level: ringed, labelled in bold, its table rows marked.
  EXPECT_EQ(count_occurrences(svg, " default\" data-level="), 1u);
  EXPECT_NE(svg.find("<g class=\"point front default\" data-level=\"full\">"), std::string::npos);
  EXPECT_NE(svg.find("class=\"point-label default\""), std::string::npos);
  EXPECT_EQ(count_occurrences(html, "<tr data-level=\"full\" class=\"default\">"), 3u);  // levels + two rows
}

TEST_F(HtmlReportBench, OneSmallPlotPerRecordingWithItsOwnNoiseFloor) {
  add_bench(two_recordings("highway", true));
  const std::string html = write();
  EXPECT_EQ(count_occurrences(html, "<svg class=\"pareto\""), 3u);
  EXPECT_EQ(count_occurrences(html, "<line class=\"noise-floor\""), 3u);
  EXPECT_NE(html.find("noise floor 0.300 m"), std::string::npos);
  EXPECT_NE(html.find("noise floor 0.500 m"), std::string::npos);
  EXPECT_NE(html.find(">#1 highway</text>"), std::string::npos);
  EXPECT_NE(html.find("width=\"620\""), std::string::npos);
  // In each recording alone points_only is dominated too.
  EXPECT_EQ(count_occurrences(html, "<g class=\"point dominated\" data-level=\"points_only\">"), 3u);
}

TEST_F(HtmlReportBench, ARecordingBenchedAloneHasNoSmallPlots) {
  std::vector<Row> rows = two_recordings("highway", true);
  std::erase_if(rows, [](const Row& r) { return r.recording == 1; });
  add_bench(rows);
  const std::string html = write();
  EXPECT_EQ(count_occurrences(html, "<svg class=\"pareto\""), 1u);
  EXPECT_NE(html.find("1 recording."), std::string::npos);
  EXPECT_EQ(table_row(html, "bench-levels", "full")[4], "250000");
}

TEST_F(HtmlReportBench, EscapesRecordingNamesAndEveryOtherDatabaseText) {
  add_bench(two_recordings(kEvilLevelName, true));
  const std::string html = write();
  EXPECT_EQ(html.find("<script"), std::string::npos);
  EXPECT_EQ(html.find("<test>"), std::string::npos);
  EXPECT_EQ(html.find("<b>x</b>"), std::string::npos);
  EXPECT_GE(count_occurrences(html, "&lt;script&gt;alert(1)&lt;/script&gt;"), 7u);  // 6 rows and a plot title
  EXPECT_NE(html.find("2-core AMD EPYC &lt;test&gt;"), std::string::npos);
  EXPECT_NE(html.find("&lt;/pre&gt;&lt;b&gt;x&lt;/b&gt;"), std::string::npos);
}

TEST_F(HtmlReportBench, WithoutReferenceAndNoiseFloorStillRenders) {
  add_bench(two_recordings("highway", false));
  const std::string html = write();
  const std::string svg = main_plot(html);
  ASSERT_FALSE(svg.empty());
  EXPECT_EQ(html.find("class=\"noise-floor\""), std::string::npos);
  EXPECT_NE(svg.find("no noise floor in this bench"), std::string::npos);
  // Without the reference, full is the slowest and most accurate: still on the front.
  EXPECT_EQ(count_occurrences(svg, "<g class=\"point front"), 3u);
  EXPECT_EQ(count_occurrences(svg, "<g class=\"point dominated"), 1u);
  EXPECT_EQ(table_row(html, "bench-levels", "full")[6], "\u2014");
  EXPECT_TRUE(table_row(html, "bench-levels", "reference").empty());
  // A narrower speed range still has labelled ticks on the log axis.
  EXPECT_NE(svg.find(">10\u2076<"), std::string::npos);
}

TEST_F(HtmlReportBench, ADatabaseWithABenchAndNoRunsRenders) {
  add_bench(two_recordings("highway", true));
  const std::string html = write();
  EXPECT_NE(html.find("<h2>Speed against error (bench 1)</h2>"), std::string::npos);
  EXPECT_NE(html.find("0 of its 0 runs shown, and bench 1 of its 1 benches"), std::string::npos);
  EXPECT_EQ(html.find("<section class=\"run\""), std::string::npos);
  EXPECT_EQ(html.find("Runs side by side"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"#bench-1\">"), std::string::npos);
}

TEST_F(HtmlReportBench, ABenchWithoutRowsRendersAnEmptyPlot) {
  add_bench({});
  const std::string html = write();
  EXPECT_NE(html.find("Speed against error (bench 1)"), std::string::npos);
  EXPECT_NE(main_plot(html).find("no level with a CPU time"), std::string::npos);
  EXPECT_EQ(count_occurrences(html, "<tr data-level="), 0u);
}

TEST_F(HtmlReportBench, ADatabaseWithNeitherRunsNorBenchIsAnError) {
  try {
    write();
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(db_path()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("holds no runs"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_ / "r.html"));
}

TEST_F(HtmlReportBench, LatestBenchByDefaultAndTheBenchOptionChoosesAnother) {
  add_bench(two_recordings("first", true), 11);
  std::vector<Row> second = two_recordings("second", true);
  for (Row& r : second) r.gospa_mean_m += 1.0;
  add_bench(second, 12);
  const std::string latest = write();
  EXPECT_NE(latest.find("Speed against error (bench 2)"), std::string::npos);
  EXPECT_NE(latest.find("seed 12"), std::string::npos);
  EXPECT_EQ(table_row(latest, "bench-levels", "full")[5], "1.900");
  EXPECT_EQ(count_occurrences(latest, "<section class=\"bench\""), 1u);
  HtmlReportOptions options;
  options.bench_id = 1;
  const std::string first = write(options);
  EXPECT_NE(first.find("Speed against error (bench 1)"), std::string::npos);
  EXPECT_NE(first.find("seed 11"), std::string::npos);
  EXPECT_EQ(table_row(first, "bench-levels", "full")[5], "0.900");
}

TEST_F(HtmlReportBench, UnknownBenchIdIsAnInputErrorNamingTheDatabase) {
  add_bench(two_recordings("highway", true));
  HtmlReportOptions options;
  options.bench_id = 99;
  try {
    write(options);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(db_path()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no bench with id 99"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_ / "r.html"));
  // The command line: exit status 2, the file named, nothing written; a known id works.
  const std::string out = (dir_ / "cli.html").string();
  const auto failed = testing::run_rcsim("report " + db_path() + " -o " + out + " --bench 99");
  EXPECT_EQ(failed.exit_code, 2) << failed.output;
  EXPECT_NE(failed.output.find(db_path()), std::string::npos) << failed.output;
  EXPECT_NE(failed.output.find("no bench with id 99"), std::string::npos) << failed.output;
  EXPECT_FALSE(fs::exists(out));
  const auto ok = testing::run_rcsim("report " + db_path() + " -o " + out + " --bench 1");
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(read_file(out).find("Speed against error (bench 1)"), std::string::npos);
}

TEST_F(HtmlReportBench, RunsWithoutABenchHaveNoBenchSection) {
  insert_minimal_run(*db_, 1);
  const std::string html = write();
  EXPECT_EQ(count_occurrences(html, "<section class=\"run\""), 1u);
  EXPECT_EQ(html.find("Speed against error"), std::string::npos);
  EXPECT_EQ(html.find("class=\"pareto\""), std::string::npos);
  EXPECT_EQ(html.find("class=\"bench"), std::string::npos);
  EXPECT_EQ(html.find("benches"), std::string::npos);
  EXPECT_NE(html.find("1 of its 1 runs shown; written by rcsim"), std::string::npos);
}

// The bench measures rcsim, not the model: it comes after the runs, which open with their verdicts.
TEST_F(HtmlReportBench, SectionSitsAfterTheRuns) {
  insert_minimal_run(*db_, 1);
  insert_minimal_run(*db_, 2);
  add_bench(two_recordings("highway", true));
  const std::string html = write();
  const std::size_t nav = html.find("</nav>"), bench = html.find("<section class=\"bench\""),
                    side = html.find("<h2>Runs side by side</h2>"), run = html.find("<section class=\"run\"");
  ASSERT_NE(bench, std::string::npos);
  ASSERT_NE(side, std::string::npos);
  EXPECT_LT(nav, side);
  EXPECT_LT(side, run);
  EXPECT_LT(html.rfind("<section class=\"run\""), bench);
  EXPECT_EQ(count_occurrences(html, "<section class=\"run\""), 2u);
  EXPECT_GT(html.find("<a href=\"#bench-1\">"), html.find("<a href=\"#run-2\">"));
}

}  // namespace
}  // namespace rcsim::replay
