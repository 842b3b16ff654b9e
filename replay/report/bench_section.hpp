#pragma once
// The "Speed against error" section of the HTML report: one bench of `rcsim bench` (read by
// store/bench_reader.hpp), summarised per fidelity level over its recordings, and rendered
// as the Pareto plot, one small plot per recording and two tables. Text is escaped here.
#include "replay/store/bench_reader.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rcsim::replay::report {

// One level over a set of recordings.
struct LevelSummary {
  std::string level;
  int recordings = 0;
  std::int64_t sensor_cycles = 0;
  std::optional<double> cpu_s;             // sum over the rows with a CPU time
  std::optional<double> cycles_per_cpu_s;  // sum of their sensor cycles / sum of their CPU time
  double gospa_mean_m = 0.0;               // mean over the recordings of each one's GOSPA mean
  // Mean GOSPA / mean noise-floor GOSPA, both over the recordings that have this level and a
  // noise_floor row; absent without such a recording.
  std::optional<double> gospa_over_noise_floor;
  std::optional<double> targets_per_cycle_ratio;  // mean of the non-NULL ratios
  std::int64_t merge_recorded = 0, merge_found = 0, merge_missed = 0, merge_spurious = 0;
  std::optional<double> latency_difference_s;  // mean of the non-NULL values
  std::int64_t latency_pairs = 0;
};

struct BenchSummary {
  std::vector<LevelSummary> levels;     // in kBenchLevelOrder, unknown names last
  std::optional<double> noise_floor_m;  // mean GOSPA of the noise_floor rows
};

// The rows of `bench` whose recording is `recording`, or all rows when it is absent, per level.
BenchSummary summarise_bench(const BenchData& bench, std::optional<int> recording = std::nullopt);

// The section (`<section class="bench">`), everything from the database escaped.
std::string bench_section(const BenchData& bench);

}  // namespace rcsim::replay::report
