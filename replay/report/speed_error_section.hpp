#pragma once
// The "Speed against error" section of the HTML report: one bench of `rcsim bench` (tables
// bench_runs and bench_rows of the report database, schemas/report-database.md), read with
// prepared statements, summarised per fidelity level over its recordings, and rendered as the
// Pareto plot, one small plot per recording and two tables. Text fields are read as stored and
// escaped only when rendered.
#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rcsim::replay::report {

struct BenchInfo {
  std::int64_t bench_id = 0;
  std::int64_t seed = 0;
  std::string machine, parameters, rcsim_version, created_utc;
};

// One row of bench_rows: one level on one recording.
struct BenchRow {
  int recording = 0;
  std::string recording_name, recording_checksum, level;
  std::int64_t sensor_cycles = 0;
  std::optional<double> cpu_s, sensor_cycles_per_cpu_s;  // NULL for noise_floor
  double gospa_mean_m = 0.0;
  std::int64_t targets_recorded = 0, targets_simulated = 0;
  std::optional<double> targets_per_cycle_ratio;  // NULL when nothing was recorded
  std::int64_t merge_recorded = 0, merge_found = 0, merge_missed = 0, merge_spurious = 0;
  std::optional<double> latency_difference_s;  // NULL: no paired episode
  std::int64_t latency_pairs = 0;
};

struct BenchData {
  BenchInfo info;
  std::vector<BenchRow> rows;           // by recording, then level (kBenchLevelOrder, unknown names last)
  std::vector<int> recordings() const;  // the recording positions, ascending
};

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

// reference, noise_floor, full, no_monopulse, points_only, no_tracking.
const std::vector<std::string>& bench_level_order();
inline constexpr const char* kDefaultLevel = "full";

// All bench ids in the database, ascending.
std::vector<std::int64_t> bench_ids(SQLite::Database& db);

// The bench to report: `requested` (must exist, else an InputError naming `db_path` and the
// id), or by default the latest; none when the database holds no bench and none was requested.
std::optional<std::int64_t> select_bench(SQLite::Database& db, const std::string& db_path,
                                         const std::optional<std::int64_t>& requested);

BenchData load_bench(SQLite::Database& db, std::int64_t bench_id);

// The rows of `bench` whose recording is `recording`, or all rows when it is absent, per level.
BenchSummary summarise_bench(const BenchData& bench, std::optional<int> recording = std::nullopt);

// The section (`<section class="bench">`), everything from the database escaped.
std::string bench_section(const BenchData& bench);

}  // namespace rcsim::replay::report
