#include "replay/store/report_reader.hpp"

#include <limits>
#include <algorithm>
#include <fmt/format.h>
#include <map>
#include <tuple>

#include "common/input_error.hpp"
#include "replay/store/run_rows.hpp"
#include "replay/store/sql_column.hpp"

namespace rcsim::replay::report {

std::int64_t RunData::sensor_cycles() const {
  if (sensor_totals.empty()) return static_cast<std::int64_t>(info.cycles) * static_cast<std::int64_t>(sensors.size());
  std::int64_t cycles = 0;
  for (const SensorTotals& t : sensor_totals) cycles += t.cycles;
  return cycles;
}

bool RunData::on_own_clocks() const {
  return sensor_cycles() != static_cast<std::int64_t>(info.cycles) * static_cast<std::int64_t>(sensors.size());
}

std::string RunData::sensor_label(int sensor) const {
  for (const auto& s : sensors) {
    if (s.sensor == sensor) return s.id;
  }
  return fmt::format("#{}", sensor);
}

std::string RunData::object_label(int object) const {
  for (const auto& o : objects) {
    if (o.object == object) return o.id;
  }
  return fmt::format("#{}", object);
}

std::vector<std::int64_t> run_ids(SQLite::Database& db) {
  std::vector<std::int64_t> ids;
  SQLite::Statement q(db, "SELECT run_id FROM runs ORDER BY run_id");
  while (q.executeStep()) ids.push_back(q.getColumn(0).getInt64());
  return ids;
}

std::vector<std::int64_t> select_runs(SQLite::Database& db, const std::string& db_path,
                                      const std::vector<std::int64_t>& requested, int last_runs) {
  const std::vector<std::int64_t> all = run_ids(db);
  if (all.empty()) throw InputError(db_path, "", "the report database holds no runs");
  if (requested.empty()) {
    const std::size_t keep = std::min(all.size(), static_cast<std::size_t>(std::max(1, last_runs)));
    return {all.end() - static_cast<std::ptrdiff_t>(keep), all.end()};
  }
  std::vector<std::int64_t> selected;
  for (const std::int64_t id : requested) {
    if (!std::binary_search(all.begin(), all.end(), id)) {
      throw InputError(db_path, "", fmt::format("no run with id {} (the database holds runs {} to {}, {} in all)", id,
                                                all.front(), all.back(), all.size()));
    }
    if (std::find(selected.begin(), selected.end(), id) == selected.end()) selected.push_back(id);
  }
  return selected;
}

namespace {

void read_info(SQLite::Database& db, std::int64_t run_id, RunData& run) {
  SQLite::Statement q(db,
                      "SELECT recording_name, recording_dir, recording_checksum, recording_source, cycle_time_s, "
                      "cycles, seed, level, parameters, rcsim_version, created_utc, store FROM runs WHERE run_id = ?");
  q.bind(1, run_id);
  if (!q.executeStep()) throw std::runtime_error(fmt::format("run {} vanished from the database", run_id));
  RunInfo& i = run.info;
  i.run_id = run_id;
  i.recording_name = q.getColumn(0).getString();
  i.recording_dir = q.getColumn(1).getString();
  i.recording_checksum = q.getColumn(2).getString();
  i.recording_source = q.getColumn(3).getString();
  i.cycle_time_s = q.getColumn(4).getDouble();
  i.cycles = q.getColumn(5).getInt();
  i.seed = q.getColumn(6).getInt64();
  i.level = q.getColumn(7).getString();
  i.parameters = q.getColumn(8).getString();
  i.rcsim_version = q.getColumn(9).getString();
  i.created_utc = q.getColumn(10).getString();
  i.store = q.getColumn(11).getString();
}

void read_summary(SQLite::Database& db, std::int64_t run_id, RunData& run) {
  SQLite::Statement q(db,
                      "SELECT cycles, targets_recorded, targets_simulated, targets_matched, gospa_mean, ospa_mean, "
                      "gospa_localisation_mean, gospa_missed_mean, gospa_false_mean, merge_artefacts_recorded, "
                      "merge_artefacts_simulated, merge_artefacts_matched, latency_recorded_s, latency_simulated_s, "
                      "latency_pairs, residual_range_rms_m, residual_azimuth_rms_rad, residual_range_rate_rms_mps, "
                      "residual_amplitude_mean_db, simulate_cpu_s, total_wall_s, gospa_object_mean, ospa_object_mean, "
                      "targets_object_recorded, targets_object_simulated, targets_background_recorded, "
                      "targets_background_simulated, targets_other_recorded, targets_other_simulated, latency_difference_mean_s, "
                      "latency_episodes, latency_unconfirmed_recorded, latency_unconfirmed_simulated "
                      "FROM summaries WHERE run_id = ?");
  q.bind(1, run_id);
  if (q.executeStep()) {
    RunSummary s;
    int c = 0;
    s.cycles = q.getColumn(c++).getInt();
    s.targets_recorded = q.getColumn(c++).getInt64();
    s.targets_simulated = q.getColumn(c++).getInt64();
    s.targets_matched = q.getColumn(c++).getInt64();
    s.gospa_mean_m = q.getColumn(c++).getDouble();
    s.ospa_mean_m = q.getColumn(c++).getDouble();
    s.gospa_localisation_mean_mp = q.getColumn(c++).getDouble();
    s.gospa_missed_mean_mp = q.getColumn(c++).getDouble();
    s.gospa_false_mean_mp = q.getColumn(c++).getDouble();
    s.merge_recorded = q.getColumn(c++).getInt64();
    s.merge_simulated = q.getColumn(c++).getInt64();
    s.merge_matched = q.getColumn(c++).getInt64();
    s.latency_recorded_s = optional_double(q.getColumn(c++));
    s.latency_simulated_s = optional_double(q.getColumn(c++));
    s.latency_pairs = q.getColumn(c++).getInt();
    s.residual_range_rms_m = q.getColumn(c++).getDouble();
    s.residual_azimuth_rms_rad = q.getColumn(c++).getDouble();
    s.residual_range_rate_rms_mps = q.getColumn(c++).getDouble();
    if (s.residual_range_rate_rms_mps < 0.0) s.residual_range_rate_rms_mps = std::numeric_limits<double>::quiet_NaN();  // -1: not compared
    s.residual_amplitude_mean_db = q.getColumn(c++).getDouble();
    s.simulate_cpu_s = q.getColumn(c++).getDouble();
    s.total_wall_s = q.getColumn(c++).getDouble();
    if (!q.getColumn(c).isNull()) {
      RunSummary::Classes k;
      k.gospa_object_mean_m = q.getColumn(c++).getDouble();
      k.ospa_object_mean_m = q.getColumn(c++).getDouble();
      for (std::int64_t* counts : {k.object, k.background, k.other}) {
        counts[0] = q.getColumn(c++).getInt64();
        counts[1] = q.getColumn(c++).getInt64();
      }
      k.latency_difference_mean_s = optional_double(q.getColumn(c++));
      k.latency_episodes = q.getColumn(c++).getInt();
      k.latency_unconfirmed[0] = q.getColumn(c++).getInt();
      k.latency_unconfirmed[1] = q.getColumn(c++).getInt();
      s.classes = k;
    }
    run.summary = s;
  }
}

void read_sensors(SQLite::Database& db, std::int64_t run_id, RunData& run) {
  SQLite::Statement q(db,
                      "SELECT sensor, sensor_id, type, x_m, y_m, yaw_rad, azimuth_half_rad, max_range_m, configuration "
                      "FROM run_sensors WHERE run_id = ? ORDER BY sensor");
  q.bind(1, run_id);
  while (q.executeStep()) {
    SensorInfo s;
    s.sensor = q.getColumn(0).getInt();
    s.id = q.getColumn(1).getString();
    s.type = q.getColumn(2).getString();
    s.X_VS = {q.getColumn(3).getDouble(), q.getColumn(4).getDouble(), q.getColumn(5).getDouble()};
    s.azimuth_half_rad = q.getColumn(6).getDouble();
    s.max_range_m = q.getColumn(7).getDouble();
    s.configuration = q.getColumn(8).getString();
    run.sensors.push_back(std::move(s));
  }
}

void read_objects(SQLite::Database& db, std::int64_t run_id, RunData& run) {
  SQLite::Statement q(db,
                      "SELECT object, object_id, class, length_m, width_m, reflectors FROM run_objects "
                      "WHERE run_id = ? ORDER BY object");
  q.bind(1, run_id);
  while (q.executeStep()) {
    run.objects.push_back({q.getColumn(0).getInt(), q.getColumn(1).getString(), q.getColumn(2).getString(),
                           q.getColumn(3).getDouble(), q.getColumn(4).getDouble(), q.getColumn(5).getInt64()});
  }
}

void read_distances(SQLite::Database& db, std::int64_t run_id, RunData& run) {
  SQLite::Statement q(db,
                      "SELECT quantity, unit, wasserstein1, kolmogorov_smirnov, n_recorded, n_simulated "
                      "FROM distribution_distances WHERE run_id = ? ORDER BY rowid");
  q.bind(1, run_id);
  while (q.executeStep()) {
    run.distances.push_back({q.getColumn(0).getString(), q.getColumn(1).getString(), optional_double(q.getColumn(2)),
                             optional_double(q.getColumn(3)), q.getColumn(4).getInt64(), q.getColumn(5).getInt64()});
  }
}

void read_latencies(SQLite::Database& db, std::int64_t run_id, RunData& run) {
  SQLite::Statement q(db,
                      "SELECT sensor, object, detectable_from_s, first_recorded_s, first_simulated_s, "
                      "latency_recorded_s, latency_simulated_s FROM latencies WHERE run_id = ? "
                      "ORDER BY object, sensor");
  q.bind(1, run_id);
  while (q.executeStep()) {
    run.latencies.push_back({q.getColumn(0).getInt(), q.getColumn(1).getInt(), q.getColumn(2).getDouble(),
                             optional_double(q.getColumn(3)), optional_double(q.getColumn(4)),
                             optional_double(q.getColumn(5)), optional_double(q.getColumn(6))});
  }
}

// Each pair of objects sharing a cell, over the cycles it was listed in, with those cycles' times
// and artefact counts.
void read_merge_pairs(SQLite::Database& db, std::int64_t run_id, RunData& run) {
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> pairs_of_cycle;  // (cycle, sensor) -> pairs
  SQLite::Statement q(db, "SELECT cycle, sensor, object_a, object_b FROM merge_pairs WHERE run_id = ?");
  q.bind(1, run_id);
  while (q.executeStep()) {
    pairs_of_cycle[{q.getColumn(0).getInt(), q.getColumn(1).getInt()}].emplace_back(q.getColumn(2).getInt(),
                                                                                  q.getColumn(3).getInt());
  }
  if (pairs_of_cycle.empty()) return;
  std::map<std::tuple<int, int, int>, MergePairRow> rows;  // (object_a, object_b, sensor)
  for_each_cycle(db, run_id, {pairs_of_cycle.begin()->first.first, pairs_of_cycle.rbegin()->first.first},
                 [&](const StoredCycle& c) {
                   const auto it = pairs_of_cycle.find({c.cycle, c.sensor});
                   if (it == pairs_of_cycle.end()) return;
                   for (const auto& [a, b] : it->second) {
                     auto [row, added] = rows.try_emplace({a, b, c.sensor});
                     MergePairRow& r = row->second;
                     if (added) r = {c.sensor, a, b, 0, c.t_s, c.t_s, 0, 0, 0};
                     ++r.cycles;
                     r.first_t_s = std::min(r.first_t_s, c.t_s);
                     r.last_t_s = std::max(r.last_t_s, c.t_s);
                     r.recorded += c.merge_recorded;
                     r.simulated += c.merge_simulated;
                     r.matched += c.merge_matched;
                   }
                 });
  for (const auto& [key, row] : rows) run.merge_pairs.push_back(row);
}

void read_sensor_totals(SQLite::Database& db, std::int64_t run_id, RunData& run) {
  std::map<int, SensorTotals> totals;
  std::map<int, double> gospa_sum, ospa_sum;
  for_each_cycle(db, run_id, {}, [&](const StoredCycle& c) {
    auto [it, added] = totals.try_emplace(c.sensor);
    SensorTotals& t = it->second;
    if (added) {
      t.sensor = c.sensor;
      t.gospa_max_m = c.gospa_m;
      t.first_t_s = c.t_s;
    }
    t.last_t_s = c.t_s;
    ++t.cycles;
    t.recorded += c.n_recorded;
    t.simulated += c.n_simulated;
    t.assigned += c.n_assigned;
    gospa_sum[c.sensor] += c.gospa_m;
    ospa_sum[c.sensor] += c.ospa_m;
    t.gospa_max_m = std::max(t.gospa_max_m, c.gospa_m);
    t.merge_recorded += c.merge_recorded;
    t.merge_simulated += c.merge_simulated;
    t.merge_matched += c.merge_matched;
  });
  for (auto& [sensor, t] : totals) {
    t.gospa_mean_m = gospa_sum[sensor] / static_cast<double>(t.cycles);
    t.ospa_mean_m = ospa_sum[sensor] / static_cast<double>(t.cycles);
    run.sensor_totals.push_back(t);
  }
}

void read_object_figures(SQLite::Database& db, std::int64_t run_id, RunData& run) {
  SQLite::Statement q(db,
                      "SELECT sensor, object, cycles_in_view, cycles_detected_recorded, cycles_detected_simulated, "
                      "targets_recorded, targets_simulated FROM object_figures WHERE run_id = ? ORDER BY object, sensor");
  q.bind(1, run_id);
  while (q.executeStep()) {
    run.object_figures.push_back({q.getColumn(0).getInt(), q.getColumn(1).getInt(), q.getColumn(2).getInt(),
                                  q.getColumn(3).getInt(), q.getColumn(4).getInt(), q.getColumn(5).getInt64(),
                                  q.getColumn(6).getInt64()});
  }
  SQLite::Statement r(db,
                      "SELECT sensor, object, range_from_m, range_to_m, cycles_in_view, cycles_detected_recorded, "
                      "cycles_detected_simulated, targets_recorded, targets_simulated FROM object_ranges "
                      "WHERE run_id = ? ORDER BY object, sensor, range_from_m");
  r.bind(1, run_id);
  while (r.executeStep()) {
    run.object_ranges.push_back({r.getColumn(0).getInt(), r.getColumn(1).getInt(), r.getColumn(2).getDouble(),
                                 r.getColumn(3).getDouble(), r.getColumn(4).getInt(), r.getColumn(5).getInt(),
                                 r.getColumn(6).getInt(), optional_int64(r.getColumn(7)),  // NULL: stored before v6
                                 optional_int64(r.getColumn(8))});
  }
}

}  // namespace

RunData load_run(SQLite::Database& db, std::int64_t run_id) {
  RunData run;
  read_info(db, run_id, run);
  read_summary(db, run_id, run);
  read_sensors(db, run_id, run);
  read_objects(db, run_id, run);
  read_distances(db, run_id, run);
  read_latencies(db, run_id, run);
  read_merge_pairs(db, run_id, run);
  read_sensor_totals(db, run_id, run);
  read_object_figures(db, run_id, run);
  return run;
}

}  // namespace rcsim::replay::report
