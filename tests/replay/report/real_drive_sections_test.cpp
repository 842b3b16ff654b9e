// The objects' section of the report (replay/report/real_drive_sections.hpp) from a hand-made
// run of 60 objects of two classes: the table by class and range, computed by hand; the offsets'
// distances in a line under it; the per-object table capped at the 50 objects with the most
// recorded targets, saying so, and the objects' table alike; targets per range bin of a run
// stored before schema v6 shown as not known, never as 0.
#include "replay/report/real_drive_sections.hpp"

#include <SQLiteCpp/SQLiteCpp.h>
#include <gtest/gtest.h>

#include <string>

#include "replay/report/html_report_tables.hpp"

namespace rcsim::replay::report {
namespace {

// Objects 0..39 passenger cars, 40..59 trucks, one sensor; object o: 10 cycles in view in
// [0, 10) m, detected in 5 recorded and 6 simulated, o recorded and 2o simulated targets.
RunData sixty_object_run() {
  RunData run;
  run.info.run_id = 1;
  run.info.store = "summary";  // no pictures: the section reads nothing from the database
  RunSummary s;
  s.classes = RunSummary::Classes{};
  s.classes->object[0] = 1800;  // 30 recorded and 60 simulated beyond the view
  s.classes->object[1] = 3600;
  run.summary = s;
  run.sensors = {{0, "radar", "astyx_hires", Pose2{}, 1.0, 100.0, ""}};
  for (int o = 0; o < 60; ++o) {
    run.objects.push_back({o, "car" + std::to_string(o), o < 40 ? "passenger_car" : "truck", 4.0, 1.8, 10});
    run.object_figures.push_back({0, o, 10, 5, 6, o, 2 * o});
    run.object_ranges.push_back({0, o, 0.0, 10.0, 10, 5, 6, o, 2 * o});
  }
  run.distances = {{"object_offset_x", "m", 0.25, 0.125, 100, 90}, {"object_offset_y", "m", 0.5, 0.375, 100, 90}};
  return run;
}

std::string section_of(const RunData& run) {
  replay::ReportDatabase db(":memory:");
  return object_section(db, run, 4);
}

TEST(RealDriveSections, ObjectsByClassAndRangeAreComputedOverTheObjectsOfEachClass) {
  const std::string html = section_of(sixty_object_run());
  EXPECT_NE(html.find("Objects by class and range"), std::string::npos) << html;
  // Cars: 400 object-cycles, 780 recorded and 1560 simulated targets, 200 and 240 detected.
  const std::string cars = R"(<td>passenger_car</td><td class="num">0)" "\u2013" R"(10</td><td class="num">400</td>)"
                           R"(<td class="num">1.95</td><td class="num">3.90</td><td class="num">2.00</td>)"
                           R"(<td class="num">50.0 %</td><td class="num">60.0 %</td>)";
  EXPECT_NE(html.find(cars), std::string::npos) << html;
  // Trucks: objects 40..59, 990 recorded targets over 200 object-cycles; the class over all ranges.
  const std::string trucks = R"(<td>truck</td><td class="num">all</td><td class="num">200</td>)"
                             R"(<td class="num">4.95</td><td class="num">9.90</td><td class="num">2.00</td>)";
  EXPECT_NE(html.find(trucks), std::string::npos) << html;
  // The offsets in a line under the table.
  EXPECT_NE(html.find("sensors: x: W1 0.250 m, KS 0.125; y: W1 0.500 m, KS 0.375"), std::string::npos) << html;
  EXPECT_NE(html.find("(100 recorded, 90 simulated targets"), std::string::npos);
  EXPECT_NE(html.find("1770 of the run's 1800 recorded and 3540 of its 3600 simulated object targets"), std::string::npos);
  EXPECT_EQ(html.find("not known"), std::string::npos);
}

TEST(RealDriveSections, ThePerObjectTableShowsTheFiftyObjectsWithTheMostRecordedTargets) {
  const std::string html = section_of(sixty_object_run());
  // Objects 10..59: 1725 of the 1770 recorded object targets.
  EXPECT_NE(html.find("The 50 of 60 objects in view with the most recorded targets (1725 of their 1770 recorded targets)"),
            std::string::npos)
      << html;
  const std::string table = html.substr(html.find(R"(<table class="objects-detection">)"));
  EXPECT_EQ(table.find("<td>car9</td>"), std::string::npos);
  EXPECT_EQ(table.find("<td>car0</td>"), std::string::npos);
  EXPECT_NE(table.find("<td>car10</td>"), std::string::npos);
  EXPECT_NE(table.find("<td>car59</td>"), std::string::npos);
  // Fifty objects or fewer: all, and no note.
  RunData few = sixty_object_run();
  few.object_figures.resize(50);
  few.objects.resize(50);
  EXPECT_EQ(section_of(few).find("objects-capped"), std::string::npos);
  EXPECT_NE(section_of(few).find("<td>car0</td>"), std::string::npos);
  EXPECT_EQ(object_table(few).find("objects-capped"), std::string::npos);
}

// The table of the annotated objects (html_report_tables.hpp) shows the same fifty, with the
// count of every class.
TEST(RealDriveSections, TheObjectTableShowsTheSameFiftyAndCountsTheClasses) {
  const std::string html = object_table(sixty_object_run());
  EXPECT_NE(html.find("The 50 of 60 annotated objects with the most recorded targets, in the order of the recording; "
                      "by class: 40 passenger_car, 20 truck."),
            std::string::npos)
      << html;
  EXPECT_EQ(html.find("<td>car9</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>car10</td>"), std::string::npos);
  EXPECT_EQ(objects_with_most_targets(sixty_object_run()).size(), kMaxObjectRows);
  EXPECT_EQ(*objects_with_most_targets(sixty_object_run()).begin(), 10);
}

TEST(RealDriveSections, TargetsPerRangeBinOfARunStoredBeforeV6AreNotKnown) {
  RunData run = sixty_object_run();
  for (ObjectRangeBin& b : run.object_ranges) b.targets_recorded.reset(), b.targets_simulated.reset();
  run.distances.clear();  // stored before the offsets were compared
  const std::string html = section_of(run);
  EXPECT_NE(html.find(R"(<td class="num">400</td><td class="num">not known</td><td class="num">not known</td>)"
                      R"(<td class="num">not known</td><td class="num">50.0 %</td>)"),
            std::string::npos)
      << html;
  EXPECT_NE(html.find("stored before report schema v6"), std::string::npos);
  EXPECT_NE(html.find("were not computed for this run"), std::string::npos);
  EXPECT_EQ(html.find(R"(<td class="num">0.00</td>)"), std::string::npos) << "never 0 for not known";
}

}  // namespace
}  // namespace rcsim::replay::report
