#include "replay/store/campaign_store.hpp"

#include <cmath>
#include <utility>

#include "replay/store/sql_column.hpp"

namespace rcsim::replay {

namespace {

// The query's columns after run_id, recording_name, recording_dir, seed, cycles, cycle_time_s,
// level and the fidelity level are those of kFigureColumns, in that order.
constexpr const char* kRunQuery = R"SQL(
SELECT r.run_id, r.recording_name, r.recording_dir, r.seed, r.cycles, r.cycle_time_s,
  r.level, json_extract(r.parameters, '$.fidelity.level'),
  s.gospa_mean, s.ospa_mean, s.gospa_object_mean, s.ospa_object_mean,
  s.targets_recorded, s.targets_simulated, s.targets_matched,
  s.latency_recorded_s, s.latency_simulated_s, s.latency_difference_mean_s, s.latency_pairs, s.latency_episodes,
  s.latency_unconfirmed_recorded, s.latency_unconfirmed_simulated,
  s.merge_artefacts_recorded, s.merge_artefacts_simulated, s.merge_artefacts_matched,
  s.residual_range_rms_m, s.residual_azimuth_rms_rad, s.residual_range_rate_rms_mps, s.residual_amplitude_mean_db,
  s.simulate_cpu_s, s.total_wall_s,
  s.targets_object_recorded, s.targets_object_simulated, s.targets_background_recorded, s.targets_background_simulated,
  f.in_view, f.detected_recorded, f.detected_simulated
FROM runs r JOIN summaries s USING (run_id)
LEFT JOIN (SELECT run_id, sum(cycles_in_view) AS in_view, sum(cycles_detected_recorded) AS detected_recorded,
                  sum(cycles_detected_simulated) AS detected_simulated
           FROM object_figures GROUP BY run_id) f USING (run_id)
ORDER BY r.run_id
)SQL";
constexpr int kFirstFigureColumn = 8;
constexpr double RunFigureSources::*kFigureColumns[] = {
    &RunFigureSources::gospa_mean,
    &RunFigureSources::ospa_mean,
    &RunFigureSources::gospa_object_mean,
    &RunFigureSources::ospa_object_mean,
    &RunFigureSources::targets_recorded,
    &RunFigureSources::targets_simulated,
    &RunFigureSources::targets_matched,
    &RunFigureSources::latency_recorded_s,
    &RunFigureSources::latency_simulated_s,
    &RunFigureSources::latency_difference_mean_s,
    &RunFigureSources::latency_pairs,
    &RunFigureSources::latency_episodes,
    &RunFigureSources::latency_unconfirmed_recorded,
    &RunFigureSources::latency_unconfirmed_simulated,
    &RunFigureSources::merge_recorded,
    &RunFigureSources::merge_simulated,
    &RunFigureSources::merge_matched,
    &RunFigureSources::residual_range_rms_m,
    &RunFigureSources::residual_azimuth_rms_rad,
    &RunFigureSources::residual_range_rate_rms_mps,
    &RunFigureSources::residual_amplitude_mean_db,
    &RunFigureSources::simulate_cpu_s,
    &RunFigureSources::wall_s,
    &RunFigureSources::object_recorded,
    &RunFigureSources::object_simulated,
    &RunFigureSources::background_recorded,
    &RunFigureSources::background_simulated,
    &RunFigureSources::in_view,
    &RunFigureSources::detected_recorded,
    &RunFigureSources::detected_simulated,
};

}  // namespace

std::vector<CriterionRow> read_criterion_rows(SQLite::Database& db) {
  std::vector<CriterionRow> out;
  SQLite::Statement q(db, "SELECT figure, scope, statistic, bound, threshold, if_missing FROM criteria ORDER BY criterion");
  while (q.executeStep()) {
    CriterionRow row;
    row.figure = q.getColumn(0).getString();
    row.scope = q.getColumn(1).getString();
    row.statistic = q.getColumn(2).getString();
    row.bound = q.getColumn(3).getString();
    row.threshold = q.getColumn(4).getDouble();
    row.if_missing = q.getColumn(5).getString();
    out.push_back(std::move(row));
  }
  return out;
}

void replace_criterion_rows(SQLite::Database& db, const std::vector<CriterionRow>& rows) {
  // A savepoint: all or nothing, on its own or within the caller's transaction.
  db.exec("SAVEPOINT store_criteria");
  try {
    db.exec("DELETE FROM criteria");
    SQLite::Statement insert(db, "INSERT INTO criteria VALUES (?, ?, ?, ?, ?, ?, ?)");
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const CriterionRow& row = rows[i];
      insert.bind(1, static_cast<std::int64_t>(i));
      insert.bind(2, row.figure);
      insert.bind(3, row.scope);
      insert.bind(4, row.statistic);
      insert.bind(5, row.bound);
      insert.bind(6, row.threshold);
      insert.bind(7, row.if_missing);
      insert.exec();
      insert.reset();
    }
  } catch (...) {
    db.exec("ROLLBACK TO store_criteria");
    db.exec("RELEASE store_criteria");
    throw;
  }
  db.exec("RELEASE store_criteria");
}

std::int64_t count_criterion_rows(SQLite::Database& db) {
  return db.execAndGet("SELECT count(*) FROM criteria").getInt64();
}

std::optional<std::string> read_campaign_name(SQLite::Database& db) {
  SQLite::Statement q(db, "SELECT name FROM campaign LIMIT 1");
  if (!q.executeStep()) return std::nullopt;
  return q.getColumn(0).getString();
}

std::optional<StoredCampaign> claim_campaign(SQLite::Database& db, const std::string& name, const std::string& manifest,
                                             const std::vector<CriterionRow>& criteria) {
  SQLite::Transaction transaction(db);
  SQLite::Statement stored(db, "SELECT name FROM campaign");
  if (stored.executeStep()) return StoredCampaign{stored.getColumn(0).getString(), read_criterion_rows(db)};
  SQLite::Statement insert(db, "INSERT INTO campaign (name, manifest) VALUES (?, ?)");
  insert.bind(1, name);
  insert.bind(2, manifest);
  insert.exec();
  replace_criterion_rows(db, criteria);
  transaction.commit();
  return std::nullopt;
}

std::vector<RunFigureSources> read_run_figure_sources(SQLite::Database& db) {
  std::vector<RunFigureSources> out;
  SQLite::Statement query(db, kRunQuery);
  while (query.executeStep()) {
    RunFigureSources run;
    run.run_id = query.getColumn(0).getInt64();
    run.recording_name = query.getColumn(1).getString();
    run.recording_dir = query.getColumn(2).getString();
    run.seed = query.getColumn(3).getInt64();
    run.duration_s = query.getColumn(4).getDouble() * query.getColumn(5).getDouble();
    run.kind = compared_level(query.getColumn(6).getString(), query.getColumn(7).isNull() ? "" : query.getColumn(7).getString());
    int c = kFirstFigureColumn;
    for (const auto field : kFigureColumns) run.*field = optional_double(query.getColumn(c++)).value_or(std::nan(""));
    out.push_back(std::move(run));
  }
  return out;
}

std::vector<RunDistance> read_run_distances(SQLite::Database& db) {
  std::vector<RunDistance> out;
  SQLite::Statement q(db, "SELECT run_id, quantity, wasserstein1, kolmogorov_smirnov FROM distribution_distances");
  while (q.executeStep()) {
    out.push_back({q.getColumn(0).getInt64(), q.getColumn(1).getString(), optional_double(q.getColumn(2)),
                   optional_double(q.getColumn(3))});
  }
  return out;
}

std::vector<DistanceQuantity> read_distance_quantities(SQLite::Database& db) {
  std::vector<DistanceQuantity> out;
  SQLite::Statement q(db, "SELECT quantity, min(unit) FROM distribution_distances GROUP BY quantity ORDER BY min(rowid)");
  while (q.executeStep()) out.push_back({q.getColumn(0).getString(), q.getColumn(1).getString()});
  return out;
}

}  // namespace rcsim::replay
