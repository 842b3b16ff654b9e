// rcsim bench's core (replay/evaluate/bench.hpp): rows against replay, the reference and
// noise-floor rows, hand-computed summaries and goals.
#include "replay/evaluate/bench.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "replay/evaluate/hand_bench_rows.hpp"
#include "replay/store/report_store.hpp"
#include "replay/run/simulated_source.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay {
namespace {

namespace fs = std::filesystem;

Recording bundled(const std::string& name) {
  return read_recording(fs::path(RCSIM_SOURCE_DIR) / "recordings_synthetic" / name);
}

TEST(BenchRun, ModelRowsAgreeWithReplayOfTheSameLevelAndSeed) {
  const Recording rec = bundled("standstill_1m");
  BenchOptions options;
  options.seed = 3;
  options.reference = false;
  options.min_timing_cpu_s = 0.0;
  std::vector<std::string> seen;
  const auto rows = bench_recording(rec, 7, options, [&](const BenchRow& r) { seen.push_back(r.level); });
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(seen, (std::vector<std::string>{"full", "no_monopulse", "points_only", "no_tracking"}));
  for (const BenchRow& row : rows) {
    SCOPED_TRACE(row.level);
    ReplayOptions replay;
    replay.seed = 3;
    replay.fidelity = *parse_fidelity(row.level);
    DiscardingSink sink;
    const ReplaySummary s = replay_recording(rec, replay, sink);
    EXPECT_EQ(row.recording, 7);
    EXPECT_EQ(row.recording_name, "standstill_1m");
    EXPECT_EQ(row.recording_checksum, rec.checksum);
    EXPECT_EQ(row.sensor_cycles, 2LL * rec.cycle_count());
    EXPECT_DOUBLE_EQ(row.gospa_mean_m, s.gospa_mean_m);
    EXPECT_EQ(row.targets_recorded, static_cast<long long>(rec.targets.size()));
    EXPECT_EQ(row.targets_simulated, s.targets_simulated);
    EXPECT_DOUBLE_EQ(row.targets_per_cycle_ratio, static_cast<double>(s.targets_simulated) / static_cast<double>(rec.targets.size()));
    EXPECT_EQ(row.merge_found + row.merge_missed, row.merge_recorded);
    EXPECT_GT(row.cpu_s, 0.0);
    EXPECT_DOUBLE_EQ(row.sensor_cycles_per_cpu_s, static_cast<double>(row.sensor_cycles) / row.cpu_s);
  }
  // points_only drops the plane reflectors: at 1 m before the car's front the model sees nothing else.
  EXPECT_NE(rows[0].targets_simulated, rows[2].targets_simulated);
}

TEST(BenchRun, ReferenceSeedsSkipTheRecordingsOwnSeed) {
  Recording rec;
  EXPECT_EQ(reference_seeds(4, rec), (std::pair<std::uint64_t, std::uint64_t>{5, 6}));
  rec.source = {{"seed", 1}};
  EXPECT_EQ(reference_seeds(0, rec), (std::pair<std::uint64_t, std::uint64_t>{2, 3}));
  rec.source = {{"seed", 6}};
  EXPECT_EQ(reference_seeds(4, rec), (std::pair<std::uint64_t, std::uint64_t>{5, 7}));
}

TEST(BenchRun, ReferenceAgainstItselfWithTheSameSeedHasNoError) {
  // The comparison machinery behind the noise floor: the reference's own lists as the recording,
  // the reference with the same seed as the simulation => every target matched exactly.
  const Recording rec = bundled("standstill_1m");
  const ModelLibrary library = ModelLibrary::builtin();
  const ImportedScene imported = import_recording(rec, library, ImportOptions{});
  const Scene scene = build_scene(imported, library, rec.dir.string());
  Recording as_recorded = rec;
  as_recorded.targets.clear();
  {
    ReferenceSource source(scene, 11);
    for (int k = 0; k < rec.cycle_count(); ++k) {
      source.run_at(rec.ego[k].t_s - imported.time_offset_s, -1);
      for (std::size_t s = 0; s < rec.sensors.size(); ++s) {
        std::vector<ComparedTarget> list;
        source.append_targets(s, list);
        for (const auto& t : list) {
          as_recorded.targets.push_back({rec.ego[k].t_s, k, static_cast<int>(s), t.track_id, t.range_m, t.azimuth_rad, t.range_rate_mps, t.amplitude_db});
        }
      }
    }
  }
  ASSERT_GT(as_recorded.targets.size(), 20u);
  ReferenceSource again(scene, 11);
  DiscardingSink sink;
  const ReplaySummary s = compare_with_recording(as_recorded, imported, scene, again, ReplayOptions{}, sink);
  EXPECT_EQ(s.targets_matched, static_cast<long long>(as_recorded.targets.size()));
  EXPECT_DOUBLE_EQ(s.gospa_mean_m, 0.0);
  EXPECT_GT(s.simulate_cpu_s, 0.0);
}

TEST(BenchRun, ReferenceAndNoiseFloorRows) {
  const Recording rec = bundled("standstill_1m");
  BenchOptions options;
  options.levels = {Fidelity::full};
  options.min_timing_cpu_s = 0.0;
  const auto rows = bench_recording(rec, 0, options);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].level, "reference");
  EXPECT_EQ(rows[1].level, "noise_floor");
  EXPECT_EQ(rows[2].level, "full");
  EXPECT_GT(rows[0].sensor_cycles_per_cpu_s, 0.0);
  EXPECT_LT(rows[1].cpu_s, 0.0);  // the noise floor is not a speed
  EXPECT_LT(rows[1].sensor_cycles_per_cpu_s, 0.0);
  EXPECT_GT(rows[1].gospa_mean_m, 0.0);  // two seeds: different noise
  EXPECT_GT(rows[1].targets_recorded, 0);  // the first reference run's targets, not the recording's
  // The model is thousands of times faster than the signal-level reference.
  EXPECT_GT(rows[2].sensor_cycles_per_cpu_s, 100.0 * rows[0].sensor_cycles_per_cpu_s);
}

TEST(BenchRun, LevelSummariesByHand) {
  const auto levels = summarise_levels(hand_rows());
  ASSERT_EQ(levels.size(), 4u);
  const BenchLevelSummary& full = levels[2];
  EXPECT_EQ(full.level, "full");
  EXPECT_EQ(full.recordings, 2);
  EXPECT_EQ(full.sensor_cycles, 400);
  EXPECT_DOUBLE_EQ(full.cpu_s, 3e-4);
  EXPECT_DOUBLE_EQ(full.sensor_cycles_per_cpu_s, 400.0 / 3e-4);
  EXPECT_DOUBLE_EQ(full.gospa_mean_m, (0.5 + 1.6) / 2);
  EXPECT_DOUBLE_EQ(full.gospa_over_noise_floor, ((0.5 + 1.6) / 2) / ((0.4 + 1.0) / 2));
  EXPECT_DOUBLE_EQ(full.targets_per_cycle_ratio, 60.0 / 50.0);  // recording 1 recorded nothing: left out
  EXPECT_TRUE(full.has_latency);
  EXPECT_DOUBLE_EQ(full.latency_difference_s, (-0.2 + 0.1) / 2);
  EXPECT_EQ(full.merge_found, 4);
  EXPECT_EQ(full.merge_missed, 2);
  EXPECT_EQ(full.merge_spurious, 5);
  EXPECT_LT(levels[1].sensor_cycles_per_cpu_s, 0.0);  // noise floor: no speed
  EXPECT_DOUBLE_EQ(levels[0].sensor_cycles_per_cpu_s, 400.0 / 3.0);
  EXPECT_FALSE(levels[3].has_latency);
  EXPECT_EQ(full.latency_pairs, 3);
}

TEST(BenchRun, GoalsByHand) {
  const BenchGoals g = evaluate_goals(hand_rows());
  ASSERT_TRUE(g.evaluable);
  // Errors: reference 0.8, full 1.05, points_only 1.2 => best is the reference; 1.05 > 1.1 * 0.8.
  EXPECT_EQ(g.best_level, "reference");
  EXPECT_DOUBLE_EQ(g.best_error_m, 0.8);
  EXPECT_DOUBLE_EQ(g.default_error_m, 1.05);
  EXPECT_FALSE(g.within_10_percent);
  EXPECT_DOUBLE_EQ(g.speedup, (400.0 / 3e-4) / (400.0 / 3.0));
  EXPECT_TRUE(g.at_least_100x);
  ASSERT_EQ(g.per_recording.size(), 2u);
  EXPECT_DOUBLE_EQ(g.per_recording[0].ratio, 1.25);
  EXPECT_TRUE(g.per_recording[0].within_1_5);
  EXPECT_DOUBLE_EQ(g.per_recording[1].ratio, 1.6);
  EXPECT_FALSE(g.per_recording[1].within_1_5);
  EXPECT_FALSE(g.all_within_1_5);
  EXPECT_DOUBLE_EQ(g.per_recording[0].reference_ratio, 0.6 / 0.4);  // the reference row over the floor
  EXPECT_DOUBLE_EQ(g.per_recording[1].reference_ratio, 1.0);
  // The goal: full over the reference on the imported scene, <= 1.1: 0.5 / 0.6 met, 1.6 / 1.0 not.
  EXPECT_DOUBLE_EQ(g.per_recording[0].over_reference, 0.5 / 0.6);
  EXPECT_TRUE(g.per_recording[0].within_1_1_reference);
  EXPECT_DOUBLE_EQ(g.per_recording[1].over_reference, 1.6);
  EXPECT_FALSE(g.per_recording[1].within_1_1_reference);
  EXPECT_FALSE(g.all_within_1_1_reference);

  auto rows = hand_rows();
  rows.erase(rows.begin() + 1);  // a noise floor missing
  rows.erase(rows.begin() + 4);
  EXPECT_FALSE(evaluate_goals(rows).evaluable);
}

}  // namespace
}  // namespace rcsim::replay
