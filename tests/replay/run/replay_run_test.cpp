#include "scratch_dir.hpp"
#include "replay/run/replay_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <filesystem>
#include <fstream>

#include "replay/replay_fixtures.hpp"
#include "replay/store/report_store.hpp"

namespace rcsim::replay {
namespace {

namespace fs = std::filesystem;

class ReplayRun : public testing::ScratchDirTest {
 protected:
  ReplayRun() : ScratchDirTest("replay") {}

  Recording write_and_read(const Recording& rec, const std::string& name) { return testing::write_and_read(rec, dir_ / name); }
};

TEST_F(ReplayRun, ModelAgainstItselfWithTheSameSeedAgreesToFileRounding) {
  const Scene scene = testing::two_cars_scene();
  const Recording rec = write_and_read(testing::model_recording(scene, 5), "self");
  ASSERT_GT(rec.targets.size(), 100u);
  ReplayOptions options;
  options.seed = 5;
  options.import.effects = {};  // the scene had none
  const auto db = open_report_database((dir_ / "r.sqlite").string(), true);
  ReportWriter writer(*db);
  const ReplaySummary s = replay_recording(rec, options, writer);
  EXPECT_EQ(s.cycles, scene.cycle_count());
  EXPECT_EQ(s.targets_recorded, static_cast<long long>(rec.targets.size()));
  EXPECT_EQ(s.targets_simulated, s.targets_recorded);
  EXPECT_EQ(s.targets_matched, s.targets_recorded);
  EXPECT_LT(s.gospa_mean_m, 1e-3);
  EXPECT_LT(s.residual_range_rms_m, 1e-4);
  EXPECT_EQ(s.merge_artefacts_recorded, s.merge_artefacts_simulated);
  EXPECT_NEAR(s.latency_recorded_s, s.latency_simulated_s, 1e-9);
  // Four-hit confirmation: the first report comes three cycles after the first detection.
  EXPECT_GE(s.latency_recorded_s, 3 * scene.cycle_time_s - 1e-9);
  // Equal up to the file's decimals (ties split by rounding can move the KS statistic a little).
  for (const auto& d : s.distances) {
    if (d.distance.n_recorded == 0 && d.distance.n_simulated == 0) continue;  // no background here
    EXPECT_LT(d.distance.wasserstein1, 1e-3) << d.quantity;
    EXPECT_LT(d.distance.kolmogorov_smirnov, 0.05) << d.quantity;
  }

  long long recorded = 0;
  for_each_target(*db, writer.run_id(), {}, [&](const StoredTarget& t) { recorded += !t.simulated; });
  EXPECT_EQ(recorded, s.targets_recorded);
  int cycles = 0;
  for_each_cycle(*db, writer.run_id(), {}, [&](const StoredCycle&) { ++cycles; });
  EXPECT_EQ(cycles, s.cycles * 2);
}

TEST_F(ReplayRun, AnotherSeedDiffersButStaysClose) {
  const Scene scene = testing::two_cars_scene();
  const Recording rec = write_and_read(testing::model_recording(scene, 5), "self");
  ReplayOptions options;
  options.seed = 6;
  options.import.effects = {};
  const auto db = open_report_database((dir_ / "r.sqlite").string(), true);
  ReportWriter writer(*db);
  const ReplaySummary s = replay_recording(rec, options, writer);
  EXPECT_GT(s.gospa_mean_m, 1e-3);
  EXPECT_LT(s.gospa_mean_m, 1.5);
  EXPECT_GT(s.targets_matched, s.targets_recorded / 2);
}

TEST_F(ReplayRun, SideBySideCarsShowMergeArtefactsInBothLists) {
  // Paper Fig. 10: two cars abreast at equal speed share range-speed cells; the monopulse angle
  // of the merged cell lies between them.
  Scene scene = testing::two_cars_scene(4.0);
  scene.sensors.resize(1);
  scene.sensors.front().X_VS = {3.7, 0.0, 0.0};  // centred, so that both cars are equally strong
  const Recording rec = write_and_read(testing::model_recording(scene, 3), "merge");
  ReplayOptions options;
  options.seed = 4;
  options.import.effects = {};
  const auto db = open_report_database((dir_ / "r.sqlite").string(), true);
  ReportWriter writer(*db);
  const ReplaySummary s = replay_recording(rec, options, writer);
  EXPECT_GT(s.merge_artefacts_recorded, 0);
  EXPECT_GT(s.merge_artefacts_simulated, 0);
  EXPECT_GT(s.merge_artefacts_matched, 0);
}

// Target classes and per-object figures through a whole replay. The ego stands, so a stationary
// point shows range rate 0: a recorded target 5 m from sensor 0 (where no car ever is) with range
// rate 0 is background, one with 3 m/s other. Model against itself: the object figures agree,
// and every object target lies on its box in the object's own frame.
TEST_F(ReplayRun, TargetsAreClassedAndObjectFiguresAgreeWithItself) {
  const Scene scene = testing::two_cars_scene();
  Recording rec = write_and_read(testing::model_recording(scene, 5), "classes");
  ReplayOptions options;
  options.seed = 5;
  options.import.effects = {};
  DiscardingSink discard;
  const ReplaySummary before = replay_recording(rec, options, discard);
  EXPECT_EQ(before.classes.background[0], 0);
  EXPECT_EQ(before.classes.object[0], before.classes.object[1]);
  EXPECT_EQ(before.classes.object[0] + before.classes.other[0], before.targets_recorded);

  for (const double range_rate_mps : {0.0, 3.0}) {
    RecordedTarget t;
    t.cycle = 10;
    t.t_s = rec.ego[10].t_s;
    t.sensor = 0;
    t.range_m = 5.0;
    t.azimuth_rad = -0.6;
    t.range_rate_mps = range_rate_mps;
    t.rcs_dbsm = 7.5;
    rec.targets.push_back(t);
  }
  std::stable_sort(rec.targets.begin(), rec.targets.end(), [](const auto& a, const auto& b) { return a.cycle < b.cycle; });
  const auto db = open_report_database((dir_ / "r.sqlite").string(), true);
  ReportWriter writer(*db);
  const ReplaySummary s = replay_recording(rec, options, writer);
  EXPECT_EQ(s.classes.background[0], 1);
  EXPECT_EQ(s.classes.other[0], before.classes.other[0] + 1);
  EXPECT_EQ(s.classes.object[0], before.classes.object[0]);
  EXPECT_DOUBLE_EQ(s.gospa_object_mean_m, before.gospa_object_mean_m);  // the object subset is untouched
  EXPECT_GT(s.gospa_mean_m, before.gospa_mean_m);
  std::vector<StoredTarget> added;  // by range rate
  for_each_target(*db, writer.run_id(), {10, 10}, [&](const StoredTarget& t) {
    if (t.sensor == 0 && !t.simulated && t.range_m == 5.0) added.push_back(t);
  });
  std::sort(added.begin(), added.end(), [](const auto& a, const auto& b) { return a.range_rate_mps < b.range_rate_mps; });
  ASSERT_EQ(added.size(), 2u);
  EXPECT_EQ(added[0].target_class, metrics::TargetClass::stationary_background);
  EXPECT_DOUBLE_EQ(added[0].rcs_dbsm, 7.5);
  EXPECT_EQ(added[0].object, -1);
  EXPECT_FALSE(added[0].p_OT_O.has_value());
  EXPECT_EQ(added[1].target_class, metrics::TargetClass::other);

  ASSERT_FALSE(s.objects.empty());
  for (const ObjectFigureRow& o : s.objects) {
    EXPECT_EQ(o.cycles_detected_recorded, o.cycles_detected_simulated) << "object " << o.object;
    EXPECT_EQ(o.targets_recorded, o.targets_simulated) << "object " << o.object;
    EXPECT_LE(o.cycles_detected_recorded, o.cycles_in_view);
  }
  // Offsets in the object frame: within the box grown by the association gate.
  const double gate_m = options.association_gate_m;
  double max_x_m = 0.0, max_y_m = 0.0;
  int object_targets = 0, simulated_with_rcs = 0;
  for_each_target(*db, writer.run_id(), {}, [&](const StoredTarget& t) {
    simulated_with_rcs += t.simulated && !std::isnan(t.rcs_dbsm);
    if (t.target_class != metrics::TargetClass::object) return;
    ++object_targets;
    ASSERT_TRUE(t.p_OT_O.has_value());
    max_x_m = std::max(max_x_m, std::abs(t.p_OT_O->x()));
    max_y_m = std::max(max_y_m, std::abs(t.p_OT_O->y()));
  });
  EXPECT_GT(object_targets, 100);
  EXPECT_LE(max_x_m, 0.5 * rec.objects[0].length_m + gate_m);
  EXPECT_LE(max_y_m, 0.5 * rec.objects[0].width_m + gate_m);
  EXPECT_EQ(simulated_with_rcs, 0);
}

// Latency cases computed by hand on a model-made recording replayed with its own seed: both sides
// confirm each car in the same cycle (difference 0). Then the recording is changed:
//   - the left car reported by the recording 3 cycles before the model: the model 3 cycles late;
//   - the recorded targets of the left car in the 5 cycles from its first report are removed: the
//     recording confirms it exactly 5 cycles (0.2 s) later, the episode start does not move;
//   - one stray recorded target on the right car's box a cycle before the episode's reports: no change;
//   - every recorded target of one sensor removed: its episodes stay, censored, and counted.
class LatencyByHand : public ReplayRun {
 protected:
  ReplaySummary replay_changed(const std::function<void(Recording&)>& change) {
    Recording rec = base_;
    change(rec);
    DiscardingSink discard;
    return replay_recording(rec, options_, discard);
  }
  void SetUp() override {
    ReplayRun::SetUp();
    base_ = write_and_read(testing::model_recording(testing::two_cars_scene(), 5), "latency");
    options_.seed = 5;
    options_.import.effects = {};
  }
  Recording base_;
  ReplayOptions options_;
};

TEST_F(LatencyByHand, TheRecordingLateByFiveCyclesShowsExactlyThat) {
  const ReplaySummary same = replay_changed([](Recording&) {});
  // Each sensor confirms the car on its side, 0.2 s into the episode (4 hits, then 3 of 4); the
  // other car is detectable by eq. (1) but never reported: censored on both sides.
  ASSERT_EQ(same.latency_pairs, 2);
  EXPECT_EQ(same.latency_episodes, 4);
  EXPECT_NEAR(same.latency_difference_mean_s, 0.0, 1e-12);
  EXPECT_NEAR(same.latency_recorded_s, 0.2, 1e-9);
  // Sensor 0 (front_left) sees the left car (object 0) left of the right one: remove its five
  // first reported cycles of the left car's targets: those with the larger azimuth in each cycle.
  const ReplaySummary late = replay_changed([&](Recording& rec) {
    int first = -1;
    for (const RecordedTarget& t : rec.targets) {
      if (t.sensor == 0) { first = t.cycle; break; }
    }
    std::erase_if(rec.targets, [&](const RecordedTarget& t) {
      if (t.sensor != 0 || t.cycle >= first + 5) return false;
      for (const RecordedTarget& u : rec.targets) {
        if (u.sensor == 0 && u.cycle == t.cycle && u.azimuth_rad > t.azimuth_rad) return false;
      }
      return true;  // the leftmost target of the cycle: the left car's
    });
  });
  ASSERT_EQ(late.latencies.size(), same.latencies.size());
  for (std::size_t i = 0; i < late.latencies.size(); ++i) {
    const LatencyRow &a = same.latencies[i], &b = late.latencies[i];
    EXPECT_DOUBLE_EQ(b.detectable_from_s, a.detectable_from_s);  // the clock starts from the scene
    EXPECT_DOUBLE_EQ(b.first_simulated_s, a.first_simulated_s);
    const double shift_s = b.first_recorded_s - a.first_recorded_s;
    if (a.sensor == 0 && a.object == 0) {
      EXPECT_NEAR(shift_s, 5 * base_.cycle_time_s, 1e-9);
    } else {
      EXPECT_NEAR(shift_s, 0.0, 1e-9) << "sensor " << a.sensor << " object " << a.object;
    }
  }
  EXPECT_NEAR(late.latency_difference_mean_s, -5 * base_.cycle_time_s / 2, 1e-9);
}

TEST_F(LatencyByHand, TheModelLateByThreeCyclesShowsExactlyThat) {
  // The recording reports the left car on sensor 0 three cycles before the model does (copies of
  // its first reported target, the car moving 0.16 m per cycle): the model is 3 cycles late.
  const ReplaySummary same = replay_changed([](Recording&) {});
  const ReplaySummary early = replay_changed([](Recording& rec) {
    const auto first = std::find_if(rec.targets.begin(), rec.targets.end(), [](const RecordedTarget& t) { return t.sensor == 0; });
    ASSERT_NE(first, rec.targets.end());
    ASSERT_GE(first->cycle, 3);
    std::vector<RecordedTarget> added;
    for (int k = first->cycle - 3; k < first->cycle; ++k) {
      RecordedTarget t = *first;
      t.cycle = k;
      t.t_s = rec.ego[static_cast<std::size_t>(k)].t_s;
      added.push_back(t);
    }
    rec.targets.insert(rec.targets.begin(), added.begin(), added.end());
    std::stable_sort(rec.targets.begin(), rec.targets.end(), [](const auto& a, const auto& b) { return a.cycle < b.cycle; });
  });
  for (std::size_t i = 0; i < same.latencies.size(); ++i) {
    const LatencyRow &a = same.latencies[i], &b = early.latencies[i];
    EXPECT_DOUBLE_EQ(b.detectable_from_s, a.detectable_from_s);
    const double shift_s = b.first_recorded_s - a.first_recorded_s;
    EXPECT_NEAR(shift_s, a.sensor == 0 && a.object == 0 ? -3 * base_.cycle_time_s : 0.0, 1e-9);
  }
  EXPECT_NEAR(early.latency_difference_mean_s, 3 * base_.cycle_time_s / 2, 1e-9);  // one of two pairs
}

TEST_F(LatencyByHand, OneStrayTargetChangesNothingAndANeverReportedObjectIsCensored) {
  const ReplaySummary same = replay_changed([](Recording&) {});
  // A stray recorded target on sensor 0 in the cycle before anything is reported, 25 m ahead.
  const ReplaySummary stray = replay_changed([](Recording& rec) {
    RecordedTarget t;
    t.sensor = 0;
    t.cycle = 0;
    t.t_s = rec.ego[0].t_s;
    t.range_m = 20.0;
    t.azimuth_rad = -0.55;  // the right car's box from the left sensor
    rec.targets.insert(rec.targets.begin(), t);
  });
  ASSERT_EQ(stray.latencies.size(), same.latencies.size());
  for (std::size_t i = 0; i < same.latencies.size(); ++i) {
    EXPECT_DOUBLE_EQ(stray.latencies[i].first_recorded_s, same.latencies[i].first_recorded_s);
  }
  // Nothing recorded on sensor 1: its two episodes stay, censored on the recorded side; the pair of
  // the right car is lost, the simulated figures do not move.
  const ReplaySummary unseen = replay_changed([](Recording& rec) {
    std::erase_if(rec.targets, [](const RecordedTarget& t) { return t.sensor == 1; });
  });
  EXPECT_EQ(unseen.latency_episodes, same.latency_episodes);
  EXPECT_EQ(unseen.latency_unconfirmed_recorded, same.latency_unconfirmed_recorded + 1);
  EXPECT_EQ(unseen.latency_unconfirmed_simulated, same.latency_unconfirmed_simulated);
  EXPECT_DOUBLE_EQ(unseen.latency_simulated_s, same.latency_simulated_s);
  EXPECT_EQ(unseen.latency_pairs, same.latency_pairs - 1);
  int censored = 0;
  for (const LatencyRow& r : unseen.latencies) censored += r.sensor == 1 && r.first_recorded_s < 0.0;
  EXPECT_EQ(censored, 2);
}

}  // namespace
}  // namespace rcsim::replay
