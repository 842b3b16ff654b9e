#include "replay/store/run_copies.hpp"

#include <SQLiteCpp/SQLiteCpp.h>
#include <fmt/format.h>

#include <vector>

namespace rcsim::replay {
namespace {

// "INSERT INTO t (a, b, ...) SELECT ?1, b, ... FROM t WHERE run_id = ?2" for a table with a run_id.
std::string copy_statement(SQLite::Database& db, const std::string& table) {
  std::vector<std::string> columns;
  SQLite::Statement info(db, "SELECT name FROM pragma_table_info(?)");
  info.bind(1, table);
  while (info.executeStep()) columns.push_back(info.getColumn(0).getString());
  std::string names, values;
  for (const std::string& c : columns) {
    names += (names.empty() ? "" : ", ") + c;
    values += (values.empty() ? "" : ", ") + (c == "run_id" ? std::string("?1") : c);
  }
  return fmt::format("INSERT INTO {0} ({1}) SELECT {2} FROM {0} WHERE run_id = ?2", table, names, values);
}

// Every table but runs that refers to a run.
std::vector<std::string> run_tables(SQLite::Database& db) {
  std::vector<std::string> tables;
  SQLite::Statement q(db, "SELECT m.name FROM sqlite_master m WHERE m.type = 'table' AND m.name <> 'runs' AND "
                          "EXISTS (SELECT 1 FROM pragma_table_info(m.name) WHERE name = 'run_id') ORDER BY m.name");
  while (q.executeStep()) tables.push_back(q.getColumn(0).getString());
  return tables;
}

void run(SQLite::Statement& s) {
  s.exec();
  s.reset();
}

}  // namespace

SourceRunFigures source_run_figures(ReportDatabase& db, std::int64_t run_id) {
  SourceRunFigures f;
  SQLite::Statement q(db, "SELECT gospa_mean FROM summaries WHERE run_id = ?");
  q.bind(1, run_id);
  if (q.executeStep()) f.gospa_mean_m = q.getColumn(0).getDouble();
  SQLite::Statement r(db, "SELECT CAST(sum(cycles_detected_simulated) AS REAL) / max(1, sum(cycles_in_view)) "
                          "FROM object_figures WHERE run_id = ?");
  r.bind(1, run_id);
  if (r.executeStep()) f.object_detection_rate_simulated = r.getColumn(0).getDouble();
  SQLite::Statement w(db, "SELECT coalesce(wasserstein1, 0) FROM distribution_distances WHERE run_id = ? AND quantity = 'range'");
  w.bind(1, run_id);
  if (w.executeStep()) f.wasserstein1_range_m = w.getColumn(0).getDouble();
  return f;
}

struct RunCopier::Impl {
  Impl(ReportDatabase& db, std::int64_t source)
      : source_run(source),
        transaction(db),
        copy_run(db, copy_statement(db, "runs")),
        rename(db, "UPDATE runs SET recording_name = ?, recording_dir = ?, seed = ?, recording_checksum = ? WHERE run_id = ?"),
        vary_summary(db, R"SQL(
UPDATE summaries SET gospa_mean = gospa_mean * ?1, ospa_mean = ospa_mean * sqrt(?1),
  gospa_object_mean = gospa_object_mean * ?1, ospa_object_mean = ospa_object_mean * sqrt(?1),
  residual_range_rms_m = residual_range_rms_m * ?1, residual_azimuth_rms_rad = residual_azimuth_rms_rad * ?1,
  residual_range_rate_rms_mps = residual_range_rate_rms_mps * ?1,
  residual_amplitude_mean_db = residual_amplitude_mean_db + ?2,
  targets_simulated = CAST(round(targets_simulated * ?3) AS INTEGER),
  targets_matched = min(targets_recorded, CAST(round(targets_matched / sqrt(?1)) AS INTEGER)),
  latency_difference_mean_s = CASE WHEN ?4 THEN NULL ELSE ?5 END,
  latency_pairs = CASE WHEN ?4 THEN 0 ELSE max(latency_pairs, 1) END,
  simulate_cpu_s = simulate_cpu_s * ?6, total_wall_s = total_wall_s * ?6
WHERE run_id = ?7)SQL"),
        vary_objects(db, "UPDATE object_figures SET cycles_detected_simulated = "
                         "max(0, min(cycles_in_view, CAST(round(cycles_detected_simulated * ?1) AS INTEGER))) WHERE run_id = ?2"),
        vary_distances(db, "UPDATE distribution_distances SET wasserstein1 = wasserstein1 * ?1, "
                           "kolmogorov_smirnov = min(1.0, kolmogorov_smirnov * sqrt(?1)) WHERE run_id = ?2") {
    for (const std::string& t : run_tables(db)) copies.push_back(std::make_unique<SQLite::Statement>(db, copy_statement(db, t)));
  }
  std::int64_t source_run;
  SQLite::Transaction transaction;
  SQLite::Statement copy_run, rename, vary_summary, vary_objects, vary_distances;
  std::vector<std::unique_ptr<SQLite::Statement>> copies;
};

RunCopier::RunCopier(ReportDatabase& db, std::int64_t source_run) : impl_(std::make_unique<Impl>(db, source_run)) {}
RunCopier::~RunCopier() = default;

void RunCopier::copy(std::int64_t id) {
  const auto copy_rows = [&](SQLite::Statement& s) {
    s.bind(1, id);
    s.bind(2, impl_->source_run);
    run(s);
  };
  copy_rows(impl_->copy_run);
  for (auto& c : impl_->copies) copy_rows(*c);
}

void RunCopier::rename(std::int64_t id, const std::string& recording_name, const std::string& recording_dir, std::int64_t seed,
                       const std::string& checksum) {
  SQLite::Statement& s = impl_->rename;
  s.bind(1, recording_name);
  s.bind(2, recording_dir);
  s.bind(3, seed);
  s.bind(4, checksum);
  s.bind(5, id);
  run(s);
}

void RunCopier::vary(std::int64_t id, const RunVariation& v) {
  SQLite::Statement& s = impl_->vary_summary;
  s.bind(1, v.quality);
  s.bind(2, v.amplitude_shift_db);
  s.bind(3, v.simulated_targets_factor);
  s.bind(4, v.no_latency_pair ? 1 : 0);
  s.bind(5, v.latency_difference_s);
  s.bind(6, v.time_factor);
  s.bind(7, id);
  run(s);
  impl_->vary_objects.bind(1, v.detection_factor);
  impl_->vary_objects.bind(2, id);
  run(impl_->vary_objects);
  impl_->vary_distances.bind(1, v.distance_factor);
  impl_->vary_distances.bind(2, id);
  run(impl_->vary_distances);
}

void RunCopier::commit() { impl_->transaction.commit(); }

}  // namespace rcsim::replay
