#include "replay/store/bench_store.hpp"

#include <chrono>
#include <fmt/chrono.h>
#include <fmt/format.h>

namespace rcsim::replay {

namespace {

void bind_or_null(SQLite::Statement& s, int index, bool present, double value) {
  if (present) {
    s.bind(index, value);
  } else {
    s.bind(index);
  }
}

}  // namespace

nlohmann::ordered_json bench_parameters_json(const BenchOptions& options) {
  nlohmann::ordered_json levels = nlohmann::ordered_json::array();
  if (options.reference) {
    levels.push_back(kReferenceLevel);
    levels.push_back(kNoiseFloorLevel);
  }
  for (const Fidelity f : options.levels) levels.push_back(fidelity_name(f));
  return {{"levels", levels},
          {"documentation", "docs/bench.md, docs/fidelity.md"},
          {"speed", "sensor cycles per CPU second of the simulation alone (thread CPU time); model levels: mean of "
                    "passes over the recording repeated until min_timing_cpu_s; reference: its one replay"},
          {"min_timing_cpu_s", options.min_timing_cpu_s},
          {"reference_seeds", "seed + 1 and seed + 2, skipping the recording's own seed"},
          {"noise_floor", "the reference with the second seed against the reference with the first seed"},
          {"gospa", {{"cutoff_m", options.replay.gospa.cutoff_m}, {"order_p", options.replay.gospa.order_p}, {"alpha", 2}}},
          {"association_gate_m", options.replay.association_gate_m},
          {"merge_match_distance_m", options.replay.merge_match_distance_m},
          {"calibration", options.replay.import.calibration_dir.empty() ? nlohmann::ordered_json()
                                                                          : nlohmann::ordered_json(options.replay.import.calibration_dir)}};
}

std::int64_t store_bench(SQLite::Database& db, const BenchOptions& options, const std::string& machine,
                         const std::vector<BenchRow>& rows) {
  SQLite::Transaction transaction(db);
  SQLite::Statement run(db,
                        "INSERT INTO bench_runs (seed, machine, parameters, rcsim_version, created_utc) "
                        "VALUES (?, ?, ?, ?, ?)");
  run.bind(1, static_cast<std::int64_t>(options.seed));
  run.bind(2, machine);
  run.bind(3, bench_parameters_json(options).dump());
  run.bind(4, RCSIM_VERSION);
  run.bind(5, fmt::format("{:%Y-%m-%dT%H:%M:%SZ}",
                          fmt::gmtime(std::chrono::system_clock::to_time_t(std::chrono::system_clock::now()))));
  run.exec();
  const std::int64_t bench_id = db.getLastInsertRowid();
  SQLite::Statement row(db, "INSERT INTO bench_rows VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  for (const BenchRow& r : rows) {
    row.bind(1, bench_id);
    row.bind(2, r.recording);
    row.bind(3, r.recording_name);
    row.bind(4, fmt::format("{:016x}", r.recording_checksum));
    row.bind(5, r.level);
    row.bind(6, static_cast<std::int64_t>(r.sensor_cycles));
    bind_or_null(row, 7, r.cpu_s >= 0.0, r.cpu_s);
    bind_or_null(row, 8, r.sensor_cycles_per_cpu_s >= 0.0, r.sensor_cycles_per_cpu_s);
    row.bind(9, r.gospa_mean_m);
    row.bind(10, static_cast<std::int64_t>(r.targets_recorded));
    row.bind(11, static_cast<std::int64_t>(r.targets_simulated));
    bind_or_null(row, 12, r.targets_per_cycle_ratio >= 0.0, r.targets_per_cycle_ratio);
    row.bind(13, static_cast<std::int64_t>(r.merge_recorded));
    row.bind(14, static_cast<std::int64_t>(r.merge_found));
    row.bind(15, static_cast<std::int64_t>(r.merge_missed));
    row.bind(16, static_cast<std::int64_t>(r.merge_spurious));
    bind_or_null(row, 17, r.has_latency, r.latency_difference_s);
    row.bind(18, r.latency_pairs);
    row.exec();
    row.reset();
  }
  transaction.commit();
  return bench_id;
}

}  // namespace rcsim::replay
