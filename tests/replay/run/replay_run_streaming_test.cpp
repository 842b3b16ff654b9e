// Streaming replay (replay_recording_dir: read, smooth, simulate, compare and store cycle by
// cycle) against the replay of the recording read whole (replay_recording): every compared
// cycle and the run's summary must agree to the last bit, on every bundled recording.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "io/recording.hpp"
#include "replay/replay_fixtures.hpp"
#include "replay/run/replay_run.hpp"
#include "scratch_dir.hpp"

namespace rcsim::replay {
namespace {

namespace fs = std::filesystem;

// Folds every number a sink is handed into one FNV-1a hash (bit patterns: -0.0 and NaNs too).
class HashingSink final : public ReplaySink {
 public:
  void begin_run(const Recording& r, const ImportedScene& i, const Scene& s, const ReplayOptions&) override {
    add(static_cast<double>(r.cycle_count()));
    add(static_cast<double>(r.checksum));
    add(i.time_offset_s);
    add(static_cast<double>(s.objects.size()));
    add(static_cast<double>(i.effects.clutter + 2 * i.effects.multibounce + 4 * i.effects.occlusion));
    for (const SceneObject& o : s.objects) add(static_cast<double>(o.model.reflector_count()));
  }
  void add_cycle(const CycleComparison& c) override {
    ++cycles;
    for (double v : {static_cast<double>(c.cycle), static_cast<double>(c.sensor), c.t_s, c.X_WS.x_m, c.X_WS.y_m,
                     c.X_WS.yaw_rad, c.gospa.gospa_m, c.gospa.localisation_mp, c.gospa.ospa_m, c.gospa_object.gospa_m,
                     static_cast<double>(c.merge_matched), static_cast<double>(c.merge_pairs.size())}) {
      add(v);
    }
    for (const auto* list : {&c.recorded, &c.simulated}) {
      add(static_cast<double>(list->size()));
      for (const ComparedTarget& t : *list) {
        for (double v : {t.range_m, t.azimuth_rad, t.range_rate_mps, t.amplitude_db, t.p_ST_S.x(), t.p_ST_S.y(),
                         t.p_OT_O.x(), t.p_OT_O.y(), static_cast<double>(t.object), static_cast<double>(t.match),
                         static_cast<double>(t.merge_pair), static_cast<double>(t.target_class),
                         static_cast<double>(t.track_id)}) {
          add(v);
        }
      }
    }
    for (const ObjectInCycle& o : c.objects) {
      for (double v : {static_cast<double>(o.object), o.x_m, o.y_m, o.yaw_rad, o.detectable ? 1.0 : 0.0}) add(v);
    }
  }
  void end_run(const ReplaySummary& s) override {
    for (double v : {static_cast<double>(s.cycles), static_cast<double>(s.targets_recorded),
                     static_cast<double>(s.targets_simulated), static_cast<double>(s.targets_matched), s.gospa_mean_m,
                     s.ospa_mean_m, s.gospa_object_mean_m, s.latency_recorded_s, s.latency_simulated_s,
                     s.latency_difference_mean_s, s.residual_range_rms_m, s.residual_azimuth_rms_rad,
                     s.residual_range_rate_rms_mps, s.residual_amplitude_mean_db}) {
      add(v);
    }
    for (int origin = 0; origin < 2; ++origin) {
      for (long long v : {s.classes.object[origin], s.classes.background[origin], s.classes.other[origin]}) {
        add(static_cast<double>(v));
      }
    }
    for (long long v : {s.merge_artefacts_recorded, s.merge_artefacts_simulated, s.merge_artefacts_matched,
                        s.object_pairs_matched, static_cast<long long>(s.latency_pairs),
                        static_cast<long long>(s.latency_episodes)}) {
      add(static_cast<double>(v));
    }
    for (const ObjectRangeRow& r : s.object_ranges) {
      for (double v : {static_cast<double>(r.sensor), static_cast<double>(r.object), r.range_from_m,
                       static_cast<double>(r.cycles_in_view), static_cast<double>(r.cycles_detected_recorded),
                       static_cast<double>(r.cycles_detected_simulated)}) {
        add(v);
      }
    }
    for (const LatencyRow& l : s.latencies) {
      for (double v : {static_cast<double>(l.sensor), static_cast<double>(l.object), l.detectable_from_s,
                       l.first_recorded_s, l.first_simulated_s}) {
        add(v);
      }
    }
    for (const QuantityDistance& d : s.distances) {
      add(d.distance.wasserstein1);
      add(d.distance.kolmogorov_smirnov);
    }
    for (const ObjectFigureRow& o : s.objects) {
      for (double v : {static_cast<double>(o.cycles_in_view), static_cast<double>(o.cycles_detected_recorded),
                       static_cast<double>(o.cycles_detected_simulated), static_cast<double>(o.targets_simulated)}) {
        add(v);
      }
    }
  }
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  long cycles = 0;

 private:
  void add(double v) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    for (int i = 0; i < 8; ++i) {
      hash ^= (bits >> (8 * i)) & 0xffu;
      hash *= 0x100000001b3ULL;
    }
  }
};

std::vector<std::string> bundled_recordings() {
  std::vector<std::string> dirs;
  for (const char* parent : {"recordings_synthetic", "recordings_synthetic/campaign"}) {
    for (const auto& e : fs::directory_iterator(fs::path(RCSIM_SOURCE_DIR) / parent)) {
      if (fs::exists(e.path() / "recording.json")) dirs.push_back(e.path().string());
    }
  }
  std::sort(dirs.begin(), dirs.end());
  return dirs;
}

TEST(StreamingReplay, EveryBundledRecordingReplaysIdenticallyToTheRecordingReadWhole) {
  const auto dirs = bundled_recordings();
  ASSERT_GE(dirs.size(), 20u);
  for (const std::string& dir : dirs) {
    for (std::uint64_t seed : {0u, 7u}) {
      ReplayOptions options;
      options.seed = seed;
      HashingSink whole, streamed;
      replay_recording(read_recording(dir), options, whole);
      replay_recording_dir(dir, options, streamed);
      EXPECT_GT(whole.cycles, 0) << dir;
      EXPECT_EQ(streamed.cycles, whole.cycles) << dir;
      EXPECT_EQ(streamed.hash, whole.hash) << dir << " seed " << seed;
    }
  }
}

// A minute with objects that leave the annotated range and come back (annotation gaps, presence
// spans opening and closing across the streaming window's steps), annotated with noise (so the
// smoothing matters) and replayed both ways.
TEST(StreamingReplay, ObjectsLeavingAndComingBackOverAMinuteReplayIdentically) {
  Scene scene = testing::single_sensor_scene(60.0);
  std::vector<TrajectorySample> circling;  // radius 20 m about (28, 0): 8 m to 48 m from the ego
  for (double t = 0.0; t <= 60.0; t += 0.5) {
    const double angle = -kPi + 0.4 * t;  // 8 m/s, a lap in 15.7 s
    circling.push_back(testing::sample(t, 28.0 + 20.0 * std::cos(angle), 20.0 * std::sin(angle), angle + kPi / 2, 8.0));
  }
  testing::add_object(scene, "circling", "passenger_car", circling);
  testing::add_object(scene, "parked", "passenger_car", {testing::sample(0.0, 30.0, -4.0, 0.0, 0.0)});
  replay::AnnotationNoise noise{0.05, 0.01};
  noise.max_range_m = 35.0;  // the circling car is annotated over part of each lap
  const fs::path dir = testing::fresh_scratch_dir("streaming_replay") / "circling";
  write_recording(dir, replay::model_recording(scene, "circling", 3, noise));
  const Recording whole_rec = read_recording(dir);
  ASSERT_GE(whole_rec.cycle_count(), 800);
  ReplayOptions options;
  options.seed = 5;
  HashingSink whole, streamed;
  const ReplaySummary a = replay_recording(whole_rec, options, whole);
  const ReplaySummary b = replay_recording_dir(dir, options, streamed);
  EXPECT_EQ(streamed.hash, whole.hash);
  EXPECT_EQ(b.targets_simulated, a.targets_simulated);
  EXPECT_GT(a.targets_recorded, 500);
  EXPECT_GE(a.latency_episodes, 2);  // the circling car came back
}

}  // namespace
}  // namespace rcsim::replay
