// The report's pictures from plain structs (replay/report/html_report_figures.hpp), by hand:
// which cycles are pictured and why, a bird's-eye picture in the pictured cycle's vehicle frame,
// and the residual histograms' bins, clamping and moments.
#include "replay/report/html_report_figures.hpp"

#include <gtest/gtest.h>

#include "common/angles.hpp"

namespace rcsim::replay::report {
namespace {

RunData two_sensor_run(int cycles) {
  RunData run;
  run.info.run_id = 1;
  run.info.cycles = cycles;
  run.sensors = {{0, "left", "srr24", Pose2{3.0, 1.0, 0.0}, 1.0, 50.0, ""},
                 {1, "right", "srr24", Pose2{3.0, -1.0, 0.0}, 1.0, 50.0, ""}};
  run.objects = {{0, "car", "passenger_car", 4.5, 1.8, 12}};
  return run;
}

// Issue 53: the thinned series' note read "every 2th cycle".
TEST(HtmlReportFigures, TheThinnedSeriesNoteSaysItsOrdinalInEnglish) {
  EXPECT_EQ(every_nth_cycle(1), "every cycle");
  EXPECT_EQ(every_nth_cycle(2), "every 2nd cycle");
  EXPECT_EQ(every_nth_cycle(3), "every 3rd cycle");
  EXPECT_EQ(every_nth_cycle(4), "every 4th cycle");
  EXPECT_EQ(every_nth_cycle(11), "every 11th cycle");
  EXPECT_EQ(every_nth_cycle(12), "every 12th cycle");
  EXPECT_EQ(every_nth_cycle(13), "every 13th cycle");
  EXPECT_EQ(every_nth_cycle(15), "every 15th cycle");
  EXPECT_EQ(every_nth_cycle(21), "every 21st cycle");
  EXPECT_EQ(every_nth_cycle(22), "every 22nd cycle");
  EXPECT_EQ(every_nth_cycle(103), "every 103rd cycle");
  EXPECT_EQ(every_nth_cycle(112), "every 112th cycle");
}

TEST(HtmlReportFigures, ChosenCyclesAreDistinctInTimeOrderWithTheirReasons) {
  CycleHighlights found;
  found.largest_gospa = CycleFound{40, 1.25, 1};
  found.most_merge_artefacts = CycleFound{40, 3.0, -1};
  found.first_recorded = CycleFound{2, 0.0, -1};
  const auto chosen = choose_cycles(found, two_sensor_run(100), 4);
  ASSERT_EQ(chosen.size(), 4u);  // 40, 2, 50 (middle), then 99 (last cycle) fills up
  EXPECT_EQ(chosen[0].cycle, 2);
  EXPECT_EQ(chosen[1].cycle, 40);
  EXPECT_EQ(chosen[1].reason, "largest GOSPA (1.25 m, sensor right); most merge artefacts (3, recorded + simulated)");
  EXPECT_EQ(chosen[2].cycle, 50);
  EXPECT_EQ(chosen[3].cycle, 99);
  // A run without cycles pictures nothing of its own.
  EXPECT_TRUE(choose_cycles(CycleHighlights{}, two_sensor_run(0), 4).empty());
}

TEST(HtmlReportFigures, BirdsEyeIsInThePicturedCyclesVehicleFrame) {
  const RunData run = two_sensor_run(10);
  CycleWindow w;
  w.first_cycle = 4;
  w.cycle = 5;
  // The vehicle stands at (100, 50) heading +y (yaw pi/2): the left sensor (3, 1) in V is at
  // (99, 53) in W, the right one at (101, 53).
  const double yaw = kPi / 2;
  w.cycles = {{4, 0, 0.4, Pose2{99.0, 53.0, yaw}, 0, 0, 0.0},
              {5, 0, 0.5, Pose2{99.0, 53.0, yaw}, 1, 1, 0.3},
              {5, 1, 0.5, Pose2{101.0, 53.0, yaw}, 0, 0, 0.0}};
  w.objects = {{0, Pose2{100.0, 70.0, yaw}}};  // 20 m ahead of the vehicle
  w.merge_pairs = {{0, 3}};
  TargetRow recorded{5, 0, 0, false, Vec2{10.0, 0.0}, 0, false, "object"};  // 10 m along the left boresight
  TargetRow simulated{5, 0, 0, true, Vec2{10.0, 0.5}, 0, true, "other"};
  TargetRow trace{4, 0, 1, false, Vec2{11.0, 0.0}, std::nullopt, false, "background"};
  w.targets = {recorded, simulated, trace};
  const svg::BirdsEyeSpec spec = birdseye_of_cycle(run, ChosenCycle{5, "because"}, w);
  EXPECT_EQ(spec.title, "Cycle 5 at t = 0.50 s");
  EXPECT_EQ(spec.trace_cycles, 1);
  EXPECT_EQ(spec.notes[0], "because");
  EXPECT_EQ(spec.notes[1], "1 recorded / 1 simulated targets; GOSPA 0.30 m (left), 0.00 m (right)");
  ASSERT_EQ(spec.boxes.size(), 1u);
  EXPECT_NEAR(spec.boxes[0].X_VO.x_m, 20.0, 1e-9);
  EXPECT_NEAR(spec.boxes[0].X_VO.y_m, 0.0, 1e-9);
  EXPECT_NEAR(spec.boxes[0].X_VO.yaw_rad, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(spec.boxes[0].length_m, 4.5);
  EXPECT_TRUE(spec.boxes[0].in_merge_pair);
  ASSERT_EQ(spec.targets.size(), 3u);
  EXPECT_NEAR(spec.targets[0].p_V.x(), 13.0, 1e-9);
  EXPECT_NEAR(spec.targets[0].p_V.y(), 1.0, 1e-9);
  EXPECT_EQ(spec.targets[2].age, 1);
  EXPECT_TRUE(spec.targets[1].merge_artefact);
  ASSERT_EQ(spec.links.size(), 1u);  // the assigned pair of the pictured cycle only
  EXPECT_NEAR(spec.links[0].p_simulated_V.y(), 1.5, 1e-9);
}

TEST(HtmlReportFigures, ResidualHistogramsBinClampAndAverage) {
  ResidualSampleStats sample;
  sample.count = 4;
  sample.mean = {0.0, 0.0, 0.0, 0.0};
  sample.mean_square = {1.0, 1.0, 1.0, 1.0};
  sample.min = {-1.0, -0.01, -1.0, -1.0};
  sample.max = {1.0, 0.01, 1.0, 100.0};
  sample.q1 = {-0.5, -0.005, -0.5, -0.5};  // interquartile range 1: the view is at most 3 beyond the quartiles
  sample.q3 = {0.5, 0.005, 0.5, 0.5};
  ResidualHistograms histograms(sample, 10);
  for (const double v : {-1.0, -0.5, 0.5, 1.0}) histograms.add({v, v / 100.0, v, v});
  histograms.add({0.0, 0.0, 0.0, 50.0});  // beyond the amplitude view
  const auto specs = histograms.specs();
  ASSERT_EQ(specs.size(), 4u);
  EXPECT_EQ(specs[1].x_label, "azimuth, simulated - recorded / deg");
  long long total = 0;
  for (const long long c : specs[0].counts) total += c;
  EXPECT_EQ(total, 5);
  EXPECT_EQ(specs[0].note, "5 pairs, mean 0, RMS 0.707");  // sqrt(2.5 / 5)
  EXPECT_EQ(specs[3].above, 1);                               // 50 dB lies beyond q3 + 3 IQR
  // The view [min, q3 + 3 IQR] = [-1, 3.5], padded by 2 % of its span (0.09) on either side.
  EXPECT_NEAR(specs[3].lo, -1.09, 1e-9);
  EXPECT_NEAR(specs[3].lo + 10 * specs[3].bin_width, 3.59, 1e-9);
  // The azimuth is shown in degrees: 0.01 rad is 0.573 deg.
  EXPECT_NEAR(specs[1].lo, -0.01 * 180.0 / kPi, 0.05);
}

}  // namespace
}  // namespace rcsim::replay::report
