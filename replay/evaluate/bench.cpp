#include "replay/evaluate/bench.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <thread>

#include "common/cpu_time.hpp"
#include "replay/run/simulated_source.hpp"

namespace rcsim::replay {

namespace {

// Keeps the simulated lists as a recording's targets (the noise floor compares against the
// reference's own lists); discards the rest of the per-cycle comparison.
class CollectingSink final : public ReplaySink {
 public:
  explicit CollectingSink(std::vector<RecordedTarget>& simulated) : simulated_(&simulated) {}
  void begin_run(const Recording&, const ImportedScene&, const Scene&, const ReplayOptions&) override {}
  void add_cycle(const CycleComparison& c) override {
    for (const ComparedTarget& t : c.simulated) {
      simulated_->push_back({c.t_s, c.cycle, c.sensor, t.track_id, t.range_m, t.azimuth_rad, t.range_rate_mps, t.amplitude_db});
    }
  }
  void end_run(const ReplaySummary&) override {}

 private:
  std::vector<RecordedTarget>* simulated_;
};

BenchRow row_of(const Recording& rec, int index, std::string_view level, const ReplaySummary& s) {
  BenchRow row;
  row.recording = index;
  row.recording_name = rec.name;
  row.recording_checksum = rec.checksum;
  row.level = std::string(level);
  row.sensor_cycles = rec.sensor_cycle_count();
  row.gospa_mean_m = s.gospa_mean_m;
  row.targets_recorded = s.targets_recorded;
  row.targets_simulated = s.targets_simulated;
  if (s.targets_recorded > 0) row.targets_per_cycle_ratio = static_cast<double>(s.targets_simulated) / static_cast<double>(s.targets_recorded);
  row.merge_recorded = s.merge_artefacts_recorded;
  row.merge_found = s.merge_artefacts_matched;
  row.merge_missed = s.merge_artefacts_recorded - s.merge_artefacts_matched;
  row.merge_spurious = s.merge_artefacts_simulated - s.merge_artefacts_matched;
  row.latency_pairs = s.latency_pairs;
  row.has_latency = s.latency_pairs > 0;
  if (row.has_latency) row.latency_difference_s = s.latency_difference_mean_s;
  return row;
}

void set_speed(BenchRow& row, double cpu_s) {
  row.cpu_s = cpu_s;
  row.sensor_cycles_per_cpu_s = cpu_s > 0.0 ? static_cast<double>(row.sensor_cycles) / cpu_s : -1.0;
}

// CPU seconds of one pass of the model over the recorded cycle times: passes repeat until
// min_cpu_s is spent (short recordings), the mean is returned. Building the model is not timed.
double time_model_pass_cpu_s(const Scene& scene, const Recording& rec, double time_offset_s,
                             const SimulationOptions& options, double min_cpu_s) {
  double total_cpu_s = 0.0;
  int passes = 0;
  do {
    Simulation simulation(scene, options);
    const double start_s = thread_cpu_s();
    for (int k = 0; k < rec.cycle_count(); ++k) simulation.run_at(rec.cycle_t_s(k) - time_offset_s, rec.cycle_sensor(k));
    total_cpu_s += thread_cpu_s() - start_s;
    ++passes;
  } while (total_cpu_s < min_cpu_s && passes < 100000);
  return total_cpu_s / passes;
}

}  // namespace

std::pair<std::uint64_t, std::uint64_t> reference_seeds(std::uint64_t seed, const Recording& recording) {
  std::uint64_t recorded_seed = 0;
  bool has_seed = false;
  if (const auto it = recording.source.find("seed");
      it != recording.source.end() && it->is_number_integer() && it->get<std::int64_t>() >= 0) {
    recorded_seed = static_cast<std::uint64_t>(it->get<std::int64_t>());
    has_seed = true;
  }
  std::uint64_t candidate = seed + 1;
  const auto next = [&] {
    while (has_seed && candidate == recorded_seed) ++candidate;
    return candidate++;
  };
  const std::uint64_t a = next();
  const std::uint64_t b = next();
  return {a, b};
}

std::vector<BenchRow> bench_recording(const Recording& rec, int index, const BenchOptions& options,
                                      const std::function<void(const BenchRow&)>& done,
                                      const std::function<void(const std::string&)>& warn) {
  const ModelLibrary library = ModelLibrary::builtin();
  const ImportedScene imported = import_recording(rec, library, options.replay.import);
  if (warn) {
    for (const std::string& warning : imported.warnings) warn(warning);
  }
  const Scene scene = build_scene(imported, library, rec.dir.string());
  std::vector<BenchRow> rows;
  const auto add = [&](BenchRow row) {
    rows.push_back(std::move(row));
    if (done) done(rows.back());
  };

  if (options.reference) {
    const auto [seed_a, seed_b] = reference_seeds(options.seed, rec);
    ReplayOptions replay = options.replay;
    std::vector<RecordedTarget> reference_targets;
    CollectingSink collect(reference_targets);
    ReferenceSource reference_a(scene, seed_a);
    replay.seed = seed_a;
    const ReplaySummary s = compare_with_recording(rec, imported, scene, reference_a, replay, collect);
    BenchRow row = row_of(rec, index, kReferenceLevel, s);
    set_speed(row, s.simulate_cpu_s);
    add(std::move(row));
    // The noise floor: reference B against reference A, on the same annotations.
    Recording as_recorded = rec;
    as_recorded.targets = std::move(reference_targets);
    DiscardingSink discard;
    ReferenceSource reference_b(scene, seed_b);
    replay.seed = seed_b;
    add(row_of(rec, index, kNoiseFloorLevel, compare_with_recording(as_recorded, imported, scene, reference_b, replay, discard)));
  }
  for (const Fidelity level : options.levels) {
    ReplayOptions replay = options.replay;
    replay.seed = options.seed;
    replay.fidelity = level;
    const SimulationOptions sim_options = model_options(options.seed, level);
    ModelSource model(scene, sim_options);
    DiscardingSink discard;
    BenchRow row = row_of(rec, index, fidelity_name(level), compare_with_recording(rec, imported, scene, model, replay, discard));
    set_speed(row, time_model_pass_cpu_s(scene, rec, imported.time_offset_s, sim_options, options.min_timing_cpu_s));
    add(std::move(row));
  }
  return rows;
}

std::vector<BenchLevelSummary> summarise_levels(const std::vector<BenchRow>& rows) {
  std::vector<BenchLevelSummary> levels;
  std::map<int, double> floor_of;  // recording -> noise floor GOSPA
  for (const BenchRow& r : rows) {
    if (r.level == kNoiseFloorLevel) floor_of[r.recording] = r.gospa_mean_m;
  }
  for (const BenchRow& r : rows) {
    auto it = std::find_if(levels.begin(), levels.end(), [&](const auto& l) { return l.level == r.level; });
    if (it == levels.end()) {
      levels.push_back({});
      it = levels.end() - 1;
      it->level = r.level;
    }
    ++it->recordings;
    it->sensor_cycles += r.sensor_cycles;
    if (r.cpu_s >= 0.0) it->cpu_s = std::max(0.0, it->cpu_s) + r.cpu_s;
    it->gospa_mean_m += r.gospa_mean_m;
    it->latency_pairs += r.latency_pairs;
    it->merge_recorded += r.merge_recorded;
    it->merge_found += r.merge_found;
    it->merge_missed += r.merge_missed;
    it->merge_spurious += r.merge_spurious;
  }
  for (BenchLevelSummary& l : levels) {
    int ratio_n = 0, latency_n = 0;
    double ratio_sum = 0.0, latency_sum = 0.0, with_floor_sum_m = 0.0, floor_sum_m = 0.0, timed_cycles = 0.0;
    for (const BenchRow& r : rows) {
      if (r.level != l.level) continue;
      if (r.targets_per_cycle_ratio >= 0.0) ratio_sum += r.targets_per_cycle_ratio, ++ratio_n;
      if (r.has_latency) latency_sum += r.latency_difference_s, ++latency_n;
      if (r.cpu_s >= 0.0) timed_cycles += static_cast<double>(r.sensor_cycles);
      if (const auto f = floor_of.find(r.recording); f != floor_of.end()) {
        with_floor_sum_m += r.gospa_mean_m;
        floor_sum_m += f->second;
      }
    }
    l.gospa_mean_m /= std::max(1, l.recordings);
    if (ratio_n > 0) l.targets_per_cycle_ratio = ratio_sum / ratio_n;
    if (latency_n > 0) l.has_latency = true, l.latency_difference_s = latency_sum / latency_n;
    if (floor_sum_m > 0.0) l.gospa_over_noise_floor = with_floor_sum_m / floor_sum_m;  // the recordings' counts cancel
    if (l.cpu_s > 0.0) l.sensor_cycles_per_cpu_s = timed_cycles / l.cpu_s;
  }
  return levels;
}

BenchGoals evaluate_goals(const std::vector<BenchRow>& rows) {
  BenchGoals g;
  const auto levels = summarise_levels(rows);
  const auto find = [&](std::string_view name) {
    const auto it = std::find_if(levels.begin(), levels.end(), [&](const auto& l) { return l.level == name; });
    return it == levels.end() ? nullptr : &*it;
  };
  const BenchLevelSummary* full = find(fidelity_name(Fidelity::full));
  const BenchLevelSummary* reference = find(kReferenceLevel);
  if (full == nullptr || reference == nullptr || find(kNoiseFloorLevel) == nullptr) return g;
  g.evaluable = true;
  g.default_error_m = full->gospa_mean_m;
  g.best_error_m = full->gospa_mean_m;
  g.best_level = full->level;
  for (const auto& l : levels) {
    if (l.level == kNoiseFloorLevel) continue;  // not a level: the bound below every level
    if (l.gospa_mean_m < g.best_error_m) g.best_error_m = l.gospa_mean_m, g.best_level = l.level;
  }
  g.within_10_percent = g.default_error_m <= 1.1 * g.best_error_m;
  if (reference->sensor_cycles_per_cpu_s > 0.0) g.speedup = full->sensor_cycles_per_cpu_s / reference->sensor_cycles_per_cpu_s;
  g.at_least_100x = g.speedup >= 100.0;
  g.all_within_1_5 = true;
  g.all_within_1_1_reference = true;
  for (const BenchRow& r : rows) {
    if (r.level != fidelity_name(Fidelity::full)) continue;
    const auto floor = std::find_if(rows.begin(), rows.end(), [&](const BenchRow& f) {
      return f.recording == r.recording && f.level == kNoiseFloorLevel;
    });
    if (floor == rows.end()) continue;
    BenchGoals::PerRecording p;
    p.recording = r.recording_name;
    p.ratio = floor->gospa_mean_m > 0.0 ? r.gospa_mean_m / floor->gospa_mean_m : (r.gospa_mean_m > 0.0 ? 1e300 : 1.0);
    p.within_1_5 = p.ratio <= 1.5;
    const auto ref = std::find_if(rows.begin(), rows.end(), [&](const BenchRow& f) {
      return f.recording == r.recording && f.level == kReferenceLevel;
    });
    if (ref != rows.end() && floor->gospa_mean_m > 0.0) p.reference_ratio = ref->gospa_mean_m / floor->gospa_mean_m;
    if (ref != rows.end()) {
      p.over_reference = ref->gospa_mean_m > 0.0 ? r.gospa_mean_m / ref->gospa_mean_m : (r.gospa_mean_m > 0.0 ? 1e300 : 1.0);
    }
    p.within_1_1_reference = ref != rows.end() && p.over_reference <= 1.1;
    g.all_within_1_5 = g.all_within_1_5 && p.within_1_5;
    g.all_within_1_1_reference = g.all_within_1_1_reference && p.within_1_1_reference;
    g.per_recording.push_back(p);
  }
  return g;
}

std::string machine_description() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) model = line.substr(line.find_first_not_of(' ', colon + 1));
      break;
    }
  }
  return fmt::format("{}, {} logical cores", model, std::thread::hardware_concurrency());
}

}  // namespace rcsim::replay
