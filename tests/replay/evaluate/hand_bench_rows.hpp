#pragma once
// Bench rows made by hand (two recordings, four levels each), for the summaries, goals and
// storage tests of the speed-against-error bench.
#include <string>
#include <vector>

#include "replay/evaluate/bench.hpp"

namespace rcsim::replay {

inline BenchRow hand_row(int recording, const std::string& level, long long cycles, double cpu_s, double gospa_m, long long rec,
                  long long sim) {
  BenchRow r;
  r.recording = recording;
  r.recording_name = "rec" + std::to_string(recording);
  r.level = level;
  r.sensor_cycles = cycles;
  r.cpu_s = cpu_s;
  r.sensor_cycles_per_cpu_s = cpu_s > 0.0 ? static_cast<double>(cycles) / cpu_s : -1.0;
  r.gospa_mean_m = gospa_m;
  r.targets_recorded = rec;
  r.targets_simulated = sim;
  r.targets_per_cycle_ratio = rec > 0 ? static_cast<double>(sim) / static_cast<double>(rec) : -1.0;
  return r;
}

inline std::vector<BenchRow> hand_rows() {
  std::vector<BenchRow> rows{
      hand_row(0, "reference", 100, 1.0, 0.6, 50, 50),  hand_row(0, "noise_floor", 100, -1.0, 0.4, 50, 50),
      hand_row(0, "full", 100, 1e-4, 0.5, 50, 60),      hand_row(0, "points_only", 100, 5e-5, 0.9, 50, 40),
      hand_row(1, "reference", 300, 2.0, 1.0, 90, 0),   hand_row(1, "noise_floor", 300, -1.0, 1.0, 90, 90),
      hand_row(1, "full", 300, 2e-4, 1.6, 0, 10),       hand_row(1, "points_only", 300, 1e-4, 1.5, 90, 45)};
  rows[2].has_latency = true;
  rows[2].latency_difference_s = -0.2;
  rows[6].has_latency = true;
  rows[6].latency_difference_s = 0.1;
  rows[2].latency_pairs = 2;
  rows[6].latency_pairs = 1;
  rows[2].merge_recorded = 5, rows[2].merge_found = 3, rows[2].merge_missed = 2, rows[2].merge_spurious = 1;
  rows[6].merge_recorded = 1, rows[6].merge_found = 1, rows[6].merge_missed = 0, rows[6].merge_spurious = 4;
  return rows;
}

}  // namespace rcsim::replay
