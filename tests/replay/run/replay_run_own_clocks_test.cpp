// Sensors on their own clocks (recording v4): each sensor is simulated at its own cycle times, the
// ego and boxes interpolated to them, and its cycles compared on their own.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <tuple>
#include <vector>

#include "io/recording.hpp"
#include "replay/import/importer.hpp"
#include "replay/replay_fixtures.hpp"
#include "replay/run/replay_run.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay_run_own_clocks_test {
namespace {

namespace fs = std::filesystem;
using replay::CycleComparison;
using replay::ReplayOptions;
using replay::ReplaySummary;

// Every compared cycle as (sensor, time, sensor x, targets recorded, simulated, GOSPA).
using CycleRow = std::tuple<int, double, double, std::size_t, std::size_t, double>;

class CollectingSink final : public replay::ReplaySink {
 public:
  void begin_run(const Recording&, const replay::ImportedScene&, const Scene&, const ReplayOptions&) override {}
  void end_run(const ReplaySummary&) override {}
  void add_cycle(const CycleComparison& c) override {
    rows.emplace_back(c.sensor, c.t_s, c.X_WS.x_m, c.recorded.size(), c.simulated.size(), c.gospa.gospa_m);
    cycles.push_back(c.cycle);
  }
  std::vector<CycleRow> rows;
  std::vector<int> cycles;
};

class ReplayOwnClocks : public testing::ScratchDirTest {
 protected:
  ReplayOwnClocks() : ScratchDirTest("own_clocks") {}
};

// Listing every sensor at every shared cycle is the shared clock said another way: the same
// comparisons, bit for bit, in the same order, read whole and streamed.
TEST_F(ReplayOwnClocks, EverySensorAtEverySharedCycleGivesTheSharedClocksFigures) {
  const Recording shared = read_recording(testing::kBundledRecordings / "two_in_one_cell");
  write_recording(dir_ / "own", testing::on_own_clocks(shared, {1, 1}, {0, 0}, 1));
  const ReplayOptions options;
  CollectingSink on_shared, on_own, on_own_streamed;
  const ReplaySummary a = replay::replay_recording(shared, options, on_shared);
  const ReplaySummary b = replay::replay_recording(read_recording(dir_ / "own"), options, on_own);
  const ReplaySummary c = replay::replay_recording_dir(dir_ / "own", options, on_own_streamed);
  ASSERT_GT(on_shared.rows.size(), 100u);
  EXPECT_EQ(on_own.rows, on_shared.rows);
  EXPECT_EQ(on_own_streamed.rows, on_shared.rows);
  EXPECT_EQ(b.cycles, 2 * a.cycles);  // a cycle is one sensor's now
  EXPECT_EQ(a.sensor_cycles, 2 * a.cycles);
  EXPECT_EQ(b.sensor_cycles, a.sensor_cycles);
  for (const ReplaySummary* s : {&b, &c}) {
    EXPECT_EQ(s->targets_recorded, a.targets_recorded);
    EXPECT_EQ(s->targets_simulated, a.targets_simulated);
    EXPECT_EQ(s->targets_matched, a.targets_matched);
    EXPECT_EQ(s->gospa_mean_m, a.gospa_mean_m);
    EXPECT_EQ(s->latency_simulated_s, a.latency_simulated_s);
    EXPECT_EQ(s->classes.object[1], a.classes.object[1]);
  }
}

// The ego drives along x at 10 m/s towards a parked car. The left radar keeps every 40 ms cycle,
// the right one every third (120 ms) from the second on; the ego log keeps every fifth row (5 Hz).
class ReplayOwnRates : public ReplayOwnClocks {
 protected:
  void SetUp() override {
    ReplayOwnClocks::SetUp();
    Scene scene = testing::two_cars_scene(3.0);  // its two radars, not its cars
    scene.objects.clear();
    scene.ego = Trajectory({testing::sample(0.0, 0.0, 0.0, 0.0, 10.0), testing::sample(3.0, 30.0, 0.0, 0.0, 10.0)});
    testing::add_object(scene, "parked", "passenger_car", {testing::sample(0.0, 45.0, 0.0, kPi, 0.0)});
    shared_ = testing::model_recording(scene, 5);
    write_recording(dir_ / "own", testing::on_own_clocks(shared_, {1, 3}, {0, 1}, 5));
    own_ = read_recording(dir_ / "own");
  }
  Recording shared_, own_;
};

TEST_F(ReplayOwnRates, EachSensorIsSimulatedAndComparedAtItsOwnTimes) {
  const int n = shared_.cycle_count();
  ASSERT_EQ(n, 76);  // 0 to 3 s every 40 ms
  ASSERT_EQ(own_.ego.size(), 16u);  // rows 0, 5, ..., 75
  CollectingSink sink;
  const ReplaySummary summary = replay::replay_recording(own_, ReplayOptions{}, sink);
  ASSERT_EQ(static_cast<int>(sink.rows.size()), own_.cycle_count());
  int per_sensor[2] = {0, 0};
  for (std::size_t i = 0; i < sink.rows.size(); ++i) {
    const auto& [sensor, t_s, x_m, recorded, simulated, gospa_m] = sink.rows[i];
    const int k = sink.cycles[i];
    EXPECT_EQ(k, static_cast<int>(i));
    EXPECT_EQ(sensor, own_.cycle_sensor(k));
    EXPECT_DOUBLE_EQ(t_s, own_.cycle_t_s(k));
    // The ego interpolated between its 5 Hz rows to the sensor's time: x = 10 t, the mount 3.7 m ahead.
    EXPECT_NEAR(x_m, 10.0 * t_s + 3.7 * std::cos(0.0), 1e-9) << "cycle " << k;
    ++per_sensor[sensor];
  }
  EXPECT_EQ(per_sensor[0], n);
  EXPECT_EQ(per_sensor[1], 25);  // cycles 1, 4, ..., 73
  EXPECT_EQ(summary.cycles, 101);
  // The right radar, on a third of the cycles with a tracker stepping 120 ms, still sees the car
  // where it was recorded.
  EXPECT_GT(summary.targets_matched, summary.targets_recorded / 2);
  EXPECT_LT(summary.residual_range_rms_m, 0.5);
}

TEST_F(ReplayOwnRates, EachSensorsTrackerStepsItsOwnCycleTime) {
  const replay::ImportedScene imported = replay::import_recording(own_, testing::library(), replay::ImportOptions{});
  const Scene scene = replay::build_scene(imported, testing::library(), own_.dir.string());
  EXPECT_NEAR(scene.sensor_cycle_time_s(0), 0.04, 1e-12);
  EXPECT_NEAR(scene.sensor_cycle_time_s(1), 0.12, 1e-12);
}

TEST_F(ReplayOwnRates, StreamedAndReadWholeAgree) {
  CollectingSink whole, streamed;
  const ReplaySummary a = replay::replay_recording(own_, ReplayOptions{}, whole);
  const ReplaySummary b = replay::replay_recording_dir(dir_ / "own", ReplayOptions{}, streamed);
  EXPECT_EQ(streamed.rows, whole.rows);
  EXPECT_EQ(b.targets_simulated, a.targets_simulated);
  EXPECT_EQ(b.gospa_mean_m, a.gospa_mean_m);
}

}  // namespace
}  // namespace rcsim::replay_run_own_clocks_test
