// Per-object figures (replay/run/object_figures.hpp) counted by hand: cycles in view, cycles
// detected (at least one object target), targets, and the same in 10 m bins of range; on a replay,
// each (sensor, object)'s bins add up to its totals.
#include "replay/run/object_figures.hpp"

#include <gtest/gtest.h>

#include <map>
#include <tuple>

#include "replay/replay_fixtures.hpp"

namespace rcsim::replay {
namespace {

metrics::BoxInSensor box(int object, double range_m) {
  metrics::BoxInSensor b;
  b.object = object;
  b.range_m = range_m;
  return b;
}

ComparedTarget target(int object, metrics::TargetClass c) {
  ComparedTarget t;
  t.object = object;
  t.target_class = c;
  return t;
}

TEST(ObjectFigures, CountsCyclesDetectionsAndTargetsPerObjectSensorAndRangeBin) {
  using C = metrics::TargetClass;
  ObjectFigures figures(2, 3, 10.0);
  CycleComparison cycle;
  // Cycle 0, sensor 0: object 0 at 5 m with two recorded targets and one simulated; object 1 at
  // 25 m with nothing but a background target near it; object 2 not in view (a target of it
  // still counts nowhere).
  cycle.sensor = 0;
  cycle.recorded = {target(0, C::object), target(0, C::object), target(-1, C::stationary_background),
                    target(2, C::object)};
  cycle.simulated = {target(0, C::object)};
  figures.add_cycle(cycle, {box(0, 5.0), box(1, 25.0)});
  // Cycle 1, sensor 0: object 0 at 12 m, only simulated.
  cycle.recorded = {};
  cycle.simulated = {target(0, C::object), target(0, C::object)};
  figures.add_cycle(cycle, {box(0, 12.0)});
  // Cycle 1, sensor 1: object 1 at 25 m, recorded once.
  cycle.sensor = 1;
  cycle.recorded = {target(1, C::object)};
  cycle.simulated = {};
  figures.add_cycle(cycle, {box(1, 25.0)});

  ReplaySummary s;
  figures.finish(s);
  ASSERT_EQ(s.objects.size(), 3u);  // (sensor 0, object 0), (0, 1), (1, 1)
  const ObjectFigureRow& a = s.objects[0];
  EXPECT_EQ(a.sensor, 0);
  EXPECT_EQ(a.object, 0);
  EXPECT_EQ(a.cycles_in_view, 2);
  EXPECT_EQ(a.cycles_detected_recorded, 1);
  EXPECT_EQ(a.cycles_detected_simulated, 2);
  EXPECT_EQ(a.targets_recorded, 2);
  EXPECT_EQ(a.targets_simulated, 3);
  const ObjectFigureRow& b = s.objects[1];
  EXPECT_EQ(b.object, 1);
  EXPECT_EQ(b.cycles_in_view, 1);
  EXPECT_EQ(b.cycles_detected_recorded, 0);  // the background target is not the object's
  EXPECT_EQ(b.targets_recorded, 0);
  const ObjectFigureRow& c = s.objects[2];
  EXPECT_EQ(c.sensor, 1);
  EXPECT_EQ(c.object, 1);
  EXPECT_EQ(c.cycles_detected_recorded, 1);

  // Bins: object 0 of sensor 0 in [0, 10) and [10, 20); object 1 in [20, 30) for each sensor.
  ASSERT_EQ(s.object_ranges.size(), 4u);
  EXPECT_DOUBLE_EQ(s.object_ranges[0].range_from_m, 0.0);
  EXPECT_DOUBLE_EQ(s.object_ranges[0].range_to_m, 10.0);
  EXPECT_EQ(s.object_ranges[0].cycles_detected_recorded, 1);
  EXPECT_EQ(s.object_ranges[0].cycles_detected_simulated, 1);
  EXPECT_EQ(s.object_ranges[0].targets_recorded, 2);
  EXPECT_EQ(s.object_ranges[0].targets_simulated, 1);
  EXPECT_DOUBLE_EQ(s.object_ranges[1].range_from_m, 10.0);
  EXPECT_EQ(s.object_ranges[1].cycles_detected_recorded, 0);
  EXPECT_EQ(s.object_ranges[1].cycles_detected_simulated, 1);
  EXPECT_EQ(s.object_ranges[1].targets_recorded, 0);
  EXPECT_EQ(s.object_ranges[1].targets_simulated, 2);
  EXPECT_DOUBLE_EQ(s.object_ranges[2].range_from_m, 20.0);
  EXPECT_EQ(s.object_ranges[2].object, 1);
  EXPECT_EQ(s.object_ranges[2].targets_recorded, 0);
  EXPECT_EQ(s.object_ranges[3].sensor, 1);
  EXPECT_EQ(s.object_ranges[3].targets_recorded, 1);
  EXPECT_EQ(s.object_ranges[3].targets_simulated, 0);
}

// On a replay of two cars passing two sensors from 25 m, in 5 m bins: every (sensor, object)'s
// bins add up to its row, cycles and targets alike, and the cars are seen in several bins.
TEST(ObjectFigures, TheRangeBinsOfAnObjectAddUpToItsTotals) {
  const Scene scene = testing::two_cars_scene(6.0);
  const Recording rec = testing::model_recording(scene, 3);
  ReplayOptions options;
  options.import.effects = {};
  options.object_range_bin_m = 5.0;
  DiscardingSink sink;
  const ReplaySummary s = replay_recording(rec, options, sink);
  ASSERT_FALSE(s.objects.empty());
  std::map<std::pair<int, int>, std::tuple<long long, long long, long long, int>> sums;  // in view, rec, sim, bins
  for (const ObjectRangeRow& r : s.object_ranges) {
    auto& [in_view, recorded, simulated, bins] = sums[{r.sensor, r.object}];
    in_view += r.cycles_in_view;
    recorded += r.targets_recorded;
    simulated += r.targets_simulated;
    ++bins;
  }
  long long targets = 0;
  int binned = 0;
  for (const ObjectFigureRow& o : s.objects) {
    const auto& [in_view, recorded, simulated, bins] = sums.at({o.sensor, o.object});
    EXPECT_EQ(in_view, o.cycles_in_view) << o.sensor << " " << o.object;
    EXPECT_EQ(recorded, o.targets_recorded) << o.sensor << " " << o.object;
    EXPECT_EQ(simulated, o.targets_simulated) << o.sensor << " " << o.object;
    targets += o.targets_recorded + o.targets_simulated;
    binned += bins > 1;
  }
  EXPECT_EQ(sums.size(), s.objects.size());
  EXPECT_GT(targets, 0);
  EXPECT_GT(binned, 0) << "the cars cross bins";
}

TEST(ObjectFigures, AnObjectNeverInViewHasNoRow) {
  ObjectFigures figures(1, 2, 10.0);
  CycleComparison cycle;
  figures.add_cycle(cycle, {});
  ReplaySummary s;
  figures.finish(s);
  EXPECT_TRUE(s.objects.empty());
  EXPECT_TRUE(s.object_ranges.empty());
}

}  // namespace
}  // namespace rcsim::replay
