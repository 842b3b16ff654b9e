#pragma once
// Reads a bench of `rcsim bench` back from the report database (tables bench_runs and
// bench_rows, schemas/report-database.md) with prepared statements, into plain structs. Text
// fields are returned as stored (unescaped).
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

// reference, noise_floor, full, no_monopulse, points_only, no_tracking.
const std::vector<std::string>& bench_level_order();
inline constexpr const char* kDefaultLevel = "full";
// a before b in bench_level_order (unknown names after, alphabetically).
bool level_before(const std::string& a, const std::string& b);

// All bench ids in the database, ascending.
std::vector<std::int64_t> bench_ids(SQLite::Database& db);

// The bench to report: `requested` (must exist, else an InputError naming `db_path` and the
// id), or by default the latest; none when the database holds no bench and none was requested.
std::optional<std::int64_t> select_bench(SQLite::Database& db, const std::string& db_path,
                                         const std::optional<std::int64_t>& requested);

BenchData load_bench(SQLite::Database& db, std::int64_t bench_id);

}  // namespace rcsim::replay::report
