// The report's tables (replay/report/html_report_tables.hpp) from a hand-made RunData: values
// with their units, sensor totals joined by sensor, NULLs shown as such, every text escaped.
#include "replay/report/html_report_tables.hpp"

#include <gtest/gtest.h>

#include "common/angles.hpp"

namespace rcsim::replay::report {
namespace {

RunData hand_run() {
  RunData run;
  run.info.run_id = 3;
  run.info.recording_name = "drive <1>";
  run.info.cycles = 250;
  run.info.cycle_time_s = 0.04;
  run.info.parameters = R"({"gospa": {"cutoff_m": 2.0}})";
  RunSummary s;
  s.targets_recorded = 200;
  s.targets_simulated = 150;
  s.targets_matched = 120;
  s.gospa_mean_m = 1.23456;
  s.residual_azimuth_rms_rad = kPi / 180.0;  // 1 deg
  s.latency_recorded_s = 0.16;
  run.summary = s;
  run.sensors = {{0, "front&left", "srr24", Pose2{3.7, 0.7, kPi / 6}, kPi / 4, 50.0, ""}};
  run.sensor_totals = {{0, 250, 200, 150, 120, 1.5, 2.0, 1.0, 4, 3, 2}};
  run.objects = {{0, "car\"1", "passenger_car", 4.5, 1.8, 12}};
  run.latencies = {{0, 0, 1.0, 1.16, std::nullopt, 0.16, std::nullopt}};
  return run;
}

TEST(HtmlReportTables, SummaryShowsValuesWithTheirUnits) {
  const std::string html = summary_table(hand_run());
  EXPECT_NE(html.find(R"(data-key="gospa_mean">1.235</td><td>m</td>)"), std::string::npos) << html;
  EXPECT_NE(html.find("0.750 x recorded"), std::string::npos);  // 150 / 200
  EXPECT_NE(html.find("60.0 % of recorded"), std::string::npos);
  EXPECT_NE(html.find(R"(data-key="residual_azimuth_rms">1.000</td><td>deg)"), std::string::npos);
  EXPECT_NE(html.find(R"(data-key="latency_simulated">-</td>)"), std::string::npos);  // NULL
  RunData damaged = hand_run();
  damaged.summary.reset();
  EXPECT_NE(summary_table(damaged).find("damaged database"), std::string::npos);
}

// Sensors on their own clocks (recording v4): 250 cycles, 150 the front's and 100 the rear's; the
// duration from their own first and last times, not cycles × the annotation's step.
TEST(HtmlReportTables, ARunOnOwnClocksCountsEachSensorsCyclesAndItsOwnDuration) {
  RunData run = hand_run();
  run.sensors.push_back({1, "rear", "srr24", Pose2{-1.0, 0.0, kPi}, kPi / 4, 50.0, ""});
  run.sensor_totals = {{0, 150, 0, 0, 0, 0.0, 0.0, 0.0, 0, 0, 0, 0.013, 8.213}, {1, 100, 0, 0, 0, 0.0, 0.0, 0.0, 0, 0, 0, 0.0, 9.9}};
  EXPECT_TRUE(run.on_own_clocks());
  EXPECT_EQ(run.sensor_cycles(), 250);
  const std::string html = run_information_table(run);
  EXPECT_NE(html.find("of 2 sensors, each on its own clock"), std::string::npos) << html;
  EXPECT_NE(html.find(R"(data-key="duration">9.9</td>)"), std::string::npos) << html;
  EXPECT_NE(html.find("annotation step"), std::string::npos) << html;
  EXPECT_FALSE(hand_run().on_own_clocks());  // 250 cycles x 1 sensor
  EXPECT_NE(run_information_table(hand_run()).find("x 1 sensor"), std::string::npos);
}

TEST(HtmlReportTables, SensorRowsCarryTheirTotalsAndAnglesInDegrees) {
  const std::string html = sensor_table(hand_run());
  EXPECT_NE(html.find("<td>front&amp;left</td>"), std::string::npos) << html;
  EXPECT_NE(html.find(R"(<td class="num">30.0</td>)"), std::string::npos);       // yaw
  EXPECT_NE(html.find(R"(<td class="num">)" "\u00b1" "45.0</td>"), std::string::npos);  // half FOV
  EXPECT_NE(html.find(R"(<td class="num">1.500</td>)"), std::string::npos);      // GOSPA mean
}

TEST(HtmlReportTables, EveryTextFromTheDatabaseIsEscaped) {
  const RunData run = hand_run();
  for (const std::string& html : {run_information_table(run), object_table(run), latency_table(run)}) {
    EXPECT_EQ(html.find("<1>"), std::string::npos) << html;
    EXPECT_EQ(html.find("car\"1"), std::string::npos) << html;
  }
  EXPECT_NE(run_information_table(run).find("drive &lt;1&gt;"), std::string::npos);
  EXPECT_NE(object_table(run).find("car&quot;1"), std::string::npos);
}

TEST(HtmlReportTables, LatencyRowsSayCensoredWhereASideNeverConfirmed) {
  const std::string html = latency_table(hand_run());
  EXPECT_NE(html.find(R"(<td class="num">1.160</td><td class="num">never (censored)</td>)"), std::string::npos) << html;
  EXPECT_NE(html.find(R"(<td class="num">0.160</td><td class="num">-</td><td class="num">-</td>)"), std::string::npos);
  RunData none = hand_run();
  none.latencies.clear();
  EXPECT_NE(latency_table(none).find("No object became detectable"), std::string::npos);
}

}  // namespace
}  // namespace rcsim::replay::report
