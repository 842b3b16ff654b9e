// rcsim calibrate --real-drive: recordings split by sensor and by cycles, the goal figures of a
// replay, and on the aiMotive sample in ../shared/realdata (skipped, saying so, where it is absent)
// the fitted background and the held-out figures of the goals the fit meets (docs/sensor-profiles.md).
#include "replay/calibrate/real_drive_fit.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "common/input_error.hpp"
#include "replay/calibrate/calibration_fit.hpp"
#include "replay/calibrate/snapshot_frames.hpp"
#include "replay/import/aimotive_importer.hpp"
#include "scratch_dir.hpp"
#include "test_support.hpp"

namespace rcsim::replay {
namespace {

namespace fs = std::filesystem;

const fs::path kSynthetic = fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / "two_in_one_cell";
using rcsim::testing::kAimotiveRaw;

TEST(RealDriveFit, RecordingsSplitBySensorAndByCycles) {
  const Recording rec = read_recording(kSynthetic);
  ASSERT_EQ(rec.sensors.size(), 2u);
  const Recording a = restrict_to_sensor(rec, 0), b = restrict_to_sensor(rec, 1);
  EXPECT_EQ(a.sensors.size(), 1u);
  EXPECT_EQ(b.sensors[0].id, rec.sensors[1].id);
  EXPECT_EQ(a.targets.size() + b.targets.size(), rec.targets.size());
  for (const auto& t : b.targets) EXPECT_EQ(t.sensor, 0);
  const int half = rec.cycle_count() / 2;
  const Recording first = restrict_to_cycles(rec, 0, half), second = restrict_to_cycles(rec, half, rec.cycle_count());
  EXPECT_EQ(first.cycle_count() + second.cycle_count(), rec.cycle_count());
  EXPECT_EQ(first.targets.size() + second.targets.size(), rec.targets.size());
  EXPECT_EQ(second.ego.front().t_s, rec.ego[static_cast<std::size_t>(half)].t_s);
  for (const auto& t : second.targets) {
    EXPECT_GE(t.cycle, 0);
    EXPECT_LT(t.cycle, second.cycle_count());
  }
  EXPECT_THROW(restrict_to_cycles(rec, 5, 5), std::out_of_range);
  // Each part replays on its own.
  ReplayOptions options;
  DiscardingSink sink;
  EXPECT_EQ(replay_recording(second, options, sink).cycles, second.cycle_count());
  EXPECT_EQ(replay_recording(b, options, sink).targets_recorded, static_cast<long long>(b.targets.size()));
}

// Snapshot data boxes each object in its one frame: a cut of the frames leaves some objects
// without a box, which the importer cannot start a trajectory from (issue 48: calibrate
// --real-drive --hold-out crashed, SIGSEGV, on every such recording). The cuts drop them.
TEST(RealDriveFit, CutsOfSingleFramesDropTheObjectsLeftWithoutABox) {
  const Recording rec = rcsim::testing::snapshot_frames({.frames = 3, .objects_per_frame = 2});
  ASSERT_EQ(rec.objects.size(), 6u);
  const Recording tail = restrict_to_cycles(rec, 1, 3);
  ASSERT_EQ(tail.objects.size(), 4u);
  EXPECT_EQ(tail.objects.front().id, "car_1_0");
  ASSERT_EQ(tail.boxes.size(), 4u);
  for (const auto& boxes : tail.boxes) EXPECT_EQ(boxes.size(), 1u);

  const Recording without = without_cycle(rec, 1);
  EXPECT_EQ(without.cycle_count(), 2);
  ASSERT_EQ(without.objects.size(), 4u);
  EXPECT_EQ(without.objects[1].id, "car_0_1");
  EXPECT_EQ(without.objects[2].id, "car_2_0");
  EXPECT_DOUBLE_EQ(without.boxes[2].front().t_s, 2.0);
  EXPECT_DOUBLE_EQ(without.ego[1].t_s, 2.0);
  const auto per_frame = static_cast<std::size_t>(2 * 4 + 3);
  ASSERT_EQ(without.targets.size(), 2 * per_frame);
  EXPECT_EQ(without.targets.back().cycle, 1);  // frame 2, renumbered
  EXPECT_DOUBLE_EQ(without.targets.back().t_s, 2.0);
  EXPECT_THROW(without_cycle(rec, 3), std::out_of_range);

  // Each cut replays, every recorded target accounted for.
  ReplayOptions options;
  options.fidelity = Fidelity::no_tracking;
  DiscardingSink sink;
  for (const Recording* cut : {&tail, &without}) {
    SCOPED_TRACE(cut->name);
    const ReplaySummary s = replay_recording(*cut, options, sink);
    EXPECT_EQ(s.cycles, cut->cycle_count());
    EXPECT_EQ(s.targets_recorded, static_cast<long long>(cut->targets.size()));
  }
}

// Leave one frame out (issue 48): three frames give three hold-outs, each fitted on the two others
// and measured on its own frame; no 4-cycle minimum where detections are compared.
TEST(RealDriveFit, SingleFramesAreHeldOutOneByOne) {
  const Recording rec = rcsim::testing::snapshot_frames({.frames = 3});
  ReplayOptions options;
  options.fidelity = Fidelity::no_tracking;
  RealDriveSearch search;
  search.max_evaluations = 3;
  const std::vector<HoldOut> splits = hold_outs(rec, options, search);
  ASSERT_EQ(splits.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    const HoldOut& h = splits[static_cast<std::size_t>(k)];
    SCOPED_TRACE(h.name);
    EXPECT_EQ(h.name, fmt::format("frame {} of 3 held out", k));
    EXPECT_EQ(h.fit.evaluations, 3);
    // Measured on its frame: that frame's 4 object targets; fitted on the others' 8.
    EXPECT_EQ(h.held_out.object_targets_recorded, 4);
    EXPECT_EQ(h.in_sample.object_targets_recorded, 8);
  }
  // More frames than are left out one by one: the halves.
  const std::vector<HoldOut> halves =
      hold_outs(rcsim::testing::snapshot_frames({.frames = kMaxFramesLeftOut + 1}), options, search);
  ASSERT_EQ(halves.size(), 1u);
  EXPECT_EQ(halves[0].name, "first half of the frames -> second half");
}

TEST(RealDriveFit, AHoldOutNeedsACycleToFitOnAndOneToMeasureOn) {
  EXPECT_THROW(check_hold_out(rcsim::testing::snapshot_frames({.frames = 1})), InputError);
  EXPECT_NO_THROW(check_hold_out(rcsim::testing::snapshot_frames({.frames = 2})));
  Recording tracks = rcsim::testing::snapshot_frames({.frames = 3});
  tracks.sensors[0].reports = ListLevel::tracks;  // a track confirms after 4 hits: halves of 4 at least
  try {
    check_hold_out(tracks);
    ADD_FAILURE() << "accepted 3 cycles of tracks";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("3 cycle(s): a hold-out needs at least 4"), std::string::npos) << e.what();
  }
}

TEST(RealDriveFit, FiguresByHandFromASummary) {
  Recording rec;
  rec.sensors = {{"front", "srr24"}};
  rec.objects = {{"car", "passenger_car", 4.6, 1.8}, {"van", "passenger_car", 5.0, 2.0}};
  ReplaySummary s;
  s.cycles = 10;
  s.sensor_cycles = 10;  // one sensor
  // car: 40 recorded, 50 simulated (1.25); van: 30 against 15 (0.5, outside [0.67, 1.5]).
  s.objects = {{0, 0, 10, 8, 9, 40, 50}, {0, 1, 10, 10, 5, 30, 15}};
  s.object_ranges = {{0, 0, 0.0, 20.0, 10, 8, 9}, {0, 1, 0.0, 20.0, 10, 10, 5}};
  s.classes.background[0] = 300, s.classes.background[1] = 240;
  s.distances = {{"background_range", "m", {1.0, 0.125, 300, 240}}};
  const RealDriveFigures f = real_drive_figures(rec, s);
  EXPECT_EQ(f.object_targets_recorded, 70);
  EXPECT_EQ(f.object_targets_simulated, 65);
  EXPECT_NEAR(f.object_count_ratio, 65.0 / 70.0, 1e-12);
  EXPECT_EQ(f.objects_counted, 2);
  EXPECT_EQ(f.objects_within_ratio_goal, 1);
  EXPECT_EQ(f.worst_object, "van");
  EXPECT_NEAR(f.worst_object_ratio, 0.5, 1e-12);
  EXPECT_NEAR(f.max_detection_rate_difference, -0.5, 1e-12);  // van: 5 of 10 against 10 of 10
  EXPECT_EQ(f.max_detection_rate_object, "van@front");
  EXPECT_NEAR(f.max_pd_bin_difference, 4.0 / 20.0, 1e-12);  // 14 of 20 against 18 of 20
  EXPECT_NEAR(f.background_per_cycle_recorded, 30.0, 1e-12);
  EXPECT_NEAR(f.background_per_cycle_simulated, 24.0, 1e-12);
  EXPECT_EQ(f.background_range_ks, 0.125);
}

class RealDriveHoldOut : public rcsim::testing::ScratchDirTest {
 protected:
  RealDriveHoldOut() : ScratchDirTest("real_drive_fit") {}
  void SetUp() override {
    if (!fs::is_directory(kAimotiveRaw)) GTEST_SKIP() << "real data absent (" << kAimotiveRaw.string() << "): real-drive fit tests skipped";
    ScratchDirTest::SetUp();
  }
};

TEST_F(RealDriveHoldOut, BackgroundAndTheMetGoalsHoldOnDataNotFittedOn) {
  const DatasetRecording imported = import_aimotive(kAimotiveRaw);
  write_recording(dir_ / "rec", imported.recording, imported.extra_files);
  const Recording rec = read_recording(dir_ / "rec");
  ReplayOptions options;
  options.seed = 1;
  options.fidelity = Fidelity::no_tracking;
  // The background: 3190 stationary targets over 50 cycles of two radars.
  const StationaryBackground background =
      fit_stationary_background({&rec}, options, builtin_sensor_config("aimotive_lrr"));
  EXPECT_NEAR(background.targets_per_cycle, 31.9, 0.05);
  EXPECT_EQ(background.range_bins(), 18u);

  const std::vector<HoldOut> splits = hold_outs(rec, options);
  ASSERT_EQ(splits.size(), 3u);
  for (const HoldOut& h : splits) {
    SCOPED_TRACE(h.name);
    // Met held out on every split: background per cycle within 25 %, KS of its range <= 0.2.
    EXPECT_NEAR(h.held_out.background_per_cycle_simulated / h.held_out.background_per_cycle_recorded, 1.0, 0.25);
    EXPECT_LE(h.held_out.background_range_ks, 0.2);
    // In sample the object targets are counted within [0.8, 1.25].
    EXPECT_GE(h.in_sample.object_count_ratio, 0.8);
    EXPECT_LE(h.in_sample.object_count_ratio, 1.25);
  }
  // Met held out on the halves: the count within [0.8, 1.25], every object with 30 targets
  // within [0.67, 1.5].
  const HoldOut& halves = splits[2];
  EXPECT_GE(halves.held_out.object_count_ratio, 0.8);
  EXPECT_LE(halves.held_out.object_count_ratio, 1.25);
  EXPECT_EQ(halves.held_out.objects_within_ratio_goal, halves.held_out.objects_counted);
}

}  // namespace
}  // namespace rcsim::replay
