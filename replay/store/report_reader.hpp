#pragma once
// What the HTML report reads from a report database (`rcsim-report` v6,
// schemas/report-database.md): the per-run tables, and aggregates over the run's cycles (read
// block by block through run_rows.hpp), never the per-target rows of a whole run. Text fields
// are returned as stored (unescaped).
#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/pose2.hpp"

namespace rcsim::replay::report {

struct RunInfo {
  std::int64_t run_id = 0;
  std::string recording_name, recording_dir, recording_checksum, recording_source;
  double cycle_time_s = 0.0;
  int cycles = 0;
  std::int64_t seed = 0;
  std::string level, parameters, rcsim_version, created_utc;
  std::string store = "full";  // full | summary (rcsim replay --store): a summary run has no targets
  bool has_targets() const { return store == "full"; }
};

struct RunSummary {
  int cycles = 0;
  std::int64_t targets_recorded = 0, targets_simulated = 0, targets_matched = 0;
  double gospa_mean_m = 0.0, ospa_mean_m = 0.0;
  double gospa_localisation_mean_mp = 0.0, gospa_missed_mean_mp = 0.0, gospa_false_mean_mp = 0.0;
  std::int64_t merge_recorded = 0, merge_simulated = 0, merge_matched = 0;
  std::optional<double> latency_recorded_s, latency_simulated_s;
  int latency_pairs = 0;
  double residual_range_rms_m = 0.0, residual_azimuth_rms_rad = 0.0, residual_range_rate_rms_mps = 0.0,
         residual_amplitude_mean_db = 0.0;
  double simulate_cpu_s = 0.0, total_wall_s = 0.0;
  // Real-drive figures (schema v3); absent in runs stored before.
  struct Classes {
    double gospa_object_mean_m = 0.0, ospa_object_mean_m = 0.0;
    std::int64_t object[2] = {0, 0}, background[2] = {0, 0}, other[2] = {0, 0};  // [0] recorded, [1] simulated
    std::optional<double> latency_difference_mean_s;  // over the pairs
    int latency_episodes = 0, latency_unconfirmed[2] = {0, 0};
  };
  std::optional<Classes> classes;
};

struct SensorInfo {
  int sensor = 0;
  std::string id, type;
  Pose2 X_VS;
  double azimuth_half_rad = 0.0, max_range_m = 0.0;
  std::string configuration;
};

struct ObjectInfo {
  int object = 0;
  std::string id, object_class;
  double length_m = 0.0, width_m = 0.0;
  std::int64_t reflectors = 0;
};

struct DistanceRow {
  std::string quantity, unit;
  std::optional<double> wasserstein1, kolmogorov_smirnov;
  std::int64_t n_recorded = 0, n_simulated = 0;
};

struct LatencyRow {
  int sensor = 0, object = 0;
  double detectable_from_s = 0.0;
  std::optional<double> first_recorded_s, first_simulated_s, latency_recorded_s, latency_simulated_s;
};

// One pair of objects sharing a range-speed cell for one sensor, over the run.
struct MergePairRow {
  int sensor = 0, object_a = 0, object_b = 0;
  std::int64_t cycles = 0;
  double first_t_s = 0.0, last_t_s = 0.0;
  std::int64_t recorded = 0, simulated = 0, matched = 0;  // artefacts in those cycles (all pairs)
};

// Per-sensor totals over the run's cycles.
struct SensorTotals {
  int sensor = 0;
  std::int64_t cycles = 0, recorded = 0, simulated = 0, assigned = 0;
  double gospa_mean_m = 0.0, gospa_max_m = 0.0, ospa_mean_m = 0.0;
  std::int64_t merge_recorded = 0, merge_simulated = 0, merge_matched = 0;
  double first_t_s = 0.0, last_t_s = 0.0;  // its first and last cycle's recording time
};

// One annotated object and sensor over the run (object_figures), with its bins of range.
struct ObjectFigures {
  int sensor = 0, object = 0;
  int cycles_in_view = 0, detected_recorded = 0, detected_simulated = 0;
  std::int64_t targets_recorded = 0, targets_simulated = 0;
};
struct ObjectRangeBin {
  int sensor = 0, object = 0;
  double range_from_m = 0.0, range_to_m = 0.0;
  int cycles_in_view = 0, detected_recorded = 0, detected_simulated = 0;
  // Object targets in those cycles (schema v6); not known (NULL) in runs stored before.
  std::optional<std::int64_t> targets_recorded, targets_simulated;
};

struct RunData {
  RunInfo info;
  std::optional<RunSummary> summary;  // absent only in a damaged database
  std::vector<SensorInfo> sensors;
  std::vector<ObjectInfo> objects;
  std::vector<DistanceRow> distances;
  std::vector<LatencyRow> latencies;
  std::vector<MergePairRow> merge_pairs;
  std::vector<SensorTotals> sensor_totals;
  std::vector<ObjectFigures> object_figures;  // by object, sensor
  std::vector<ObjectRangeBin> object_ranges;  // by object, sensor, range

  std::string sensor_label(int sensor) const;  // its id, or "#N"
  // The sensors' cycles compared: counted per sensor where the cycles are stored (sensors on their
  // own clocks have cycles of one sensor each), else cycles × sensors.
  std::int64_t sensor_cycles() const;
  bool on_own_clocks() const;  // each cycle one sensor's (recording v4)
  std::string object_label(int object) const;
};

// All run ids in the database, ascending.
std::vector<std::int64_t> run_ids(SQLite::Database& db);

// The runs to report: the requested ones (each must exist, else an InputError naming
// `db_path` and the id), or by default the last `last_runs` runs.
std::vector<std::int64_t> select_runs(SQLite::Database& db, const std::string& db_path,
                                      const std::vector<std::int64_t>& requested, int last_runs);

RunData load_run(SQLite::Database& db, std::int64_t run_id);

}  // namespace rcsim::replay::report
