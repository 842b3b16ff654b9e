// Version 3 -> 4 of the report database (schemas/report-database.md): the rows of the tables
// `cycles`, `targets` and `object_states` of every run are converted into the v4 blocks
// (run_rows.hpp), inside the caller's transaction; the caller then drops those tables. The
// cycles' figures and poses and the boxes come over bit for bit, the targets' reals at float32.
#include "replay/store/report_migration.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "common/json_reader.hpp"
#include "replay/store/run_rows.hpp"

namespace rcsim::replay {

namespace {

std::optional<metrics::TargetClass> class_from_name(const SQLite::Column& column) {
  if (column.isNull()) return std::nullopt;
  const std::string name = column.getString();
  if (name == "object") return metrics::TargetClass::object;
  if (name == "background") return metrics::TargetClass::stationary_background;
  return metrics::TargetClass::other;
}

double or_nan(const SQLite::Column& column) {
  return column.isNull() ? std::numeric_limits<double>::quiet_NaN() : column.getDouble();
}

StoredCycle read_cycle(SQLite::Statement& q) {
  StoredCycle c;
  c.cycle = q.getColumn(0).getInt();
  c.sensor = q.getColumn(1).getInt();
  c.t_s = q.getColumn(2).getDouble();
  c.X_WS = Pose2{q.getColumn(3).getDouble(), q.getColumn(4).getDouble(), q.getColumn(5).getDouble()};
  c.n_recorded = q.getColumn(6).getInt();
  c.n_simulated = q.getColumn(7).getInt();
  c.n_assigned = q.getColumn(8).getInt();
  c.gospa_m = q.getColumn(9).getDouble();
  c.gospa_localisation_mp = q.getColumn(10).getDouble();
  c.gospa_missed_mp = q.getColumn(11).getDouble();
  c.gospa_false_mp = q.getColumn(12).getDouble();
  c.ospa_m = q.getColumn(13).getDouble();
  c.merge_recorded = q.getColumn(14).getInt();
  c.merge_simulated = q.getColumn(15).getInt();
  c.merge_matched = q.getColumn(16).getInt();
  if (!q.getColumn(17).isNull()) {
    c.classes = StoredCycle::Classes{q.getColumn(17).getInt(),    q.getColumn(18).getInt(),
                                     q.getColumn(19).getInt(),    q.getColumn(20).getInt(),
                                     q.getColumn(21).getDouble(), q.getColumn(22).getDouble()};
  }
  return c;
}

StoredTarget read_target(SQLite::Statement& q) {
  StoredTarget t;
  t.cycle = q.getColumn(0).getInt();
  t.sensor = q.getColumn(1).getInt();
  t.simulated = q.getColumn(2).getString() == "simulated";
  t.idx = q.getColumn(3).getInt();
  t.track_id = q.getColumn(4).isNull() ? -1 : q.getColumn(4).getInt();
  t.range_m = q.getColumn(5).getDouble();
  t.azimuth_rad = q.getColumn(6).getDouble();
  t.range_rate_mps = q.getColumn(7).getDouble();
  t.amplitude_db = q.getColumn(8).getDouble();
  t.object = q.getColumn(9).isNull() ? -1 : q.getColumn(9).getInt();
  t.match_idx = q.getColumn(10).isNull() ? -1 : q.getColumn(10).getInt();
  t.merge_artefact = q.getColumn(11).getInt() != 0;
  t.target_class = class_from_name(q.getColumn(12));
  if (!q.getColumn(13).isNull() && !q.getColumn(14).isNull()) {
    t.p_OT_O = Vec2{q.getColumn(13).getDouble(), q.getColumn(14).getDouble()};
  } else if (t.object >= 0) {
    t.target_class.reset();  // a class without its offset cannot be kept as one
  }
  t.rcs_dbsm = or_nan(q.getColumn(15));
  t.snr_db = or_nan(q.getColumn(16));
  t.elevation_rad = or_nan(q.getColumn(17));
  return t;
}

// The run's GOSPA parameters from runs.parameters; they only make the blocks smaller.
std::pair<double, double> gospa_parameters(const std::string& parameters) {
  const auto json = parse_stored_json(parameters);
  double cutoff_m = 2.0, order_p = 2.0;
  if (json.is_object() && json.contains("gospa") && json["gospa"].is_object()) {
    const auto& g = json["gospa"];
    if (g.contains("cutoff_m") && g["cutoff_m"].is_number()) cutoff_m = g["cutoff_m"].get<double>();
    if (g.contains("order_p") && g["order_p"].is_number()) order_p = g["order_p"].get<double>();
  }
  return {cutoff_m, order_p};
}

void convert_run(SQLite::Database& db, std::int64_t run_id, const std::string& parameters) {
  const auto [cutoff_m, order_p] = gospa_parameters(parameters);
  RunRowWriter writer(db, run_id, StoreLevel::full, cutoff_m, order_p);
  SQLite::Statement cycles(db,
                           "SELECT cycle, sensor, t_s, sensor_x_m, sensor_y_m, sensor_yaw_rad, n_recorded, n_simulated, "
                           "n_assigned, gospa_m, gospa_localisation_mp, gospa_missed_mp, gospa_false_mp, ospa_m, "
                           "merge_recorded, merge_simulated, merge_matched, n_object_recorded, n_object_simulated, "
                           "n_background_recorded, n_background_simulated, gospa_object_m, ospa_object_m FROM cycles "
                           "WHERE run_id = ? ORDER BY cycle, sensor");
  SQLite::Statement targets(db,
                            "SELECT cycle, sensor, origin, idx, track_id, range_m, azimuth_rad, range_rate_mps, "
                            "amplitude_db, object, match_idx, merge_artefact, target_class, x_o_m, y_o_m, rcs_dbsm, "
                            "snr_db, elevation_rad FROM targets WHERE run_id = ? ORDER BY cycle, sensor, origin, idx");
  SQLite::Statement states(db, "SELECT cycle, object, x_m, y_m, yaw_rad FROM object_states WHERE run_id = ? "
                               "ORDER BY cycle, object");
  cycles.bind(1, run_id);
  targets.bind(1, run_id);
  states.bind(1, run_id);
  bool target_ahead = targets.executeStep(), state_ahead = states.executeStep();
  std::vector<StoredTarget> recorded, simulated;
  std::vector<StoredObjectState> boxes;
  while (cycles.executeStep()) {
    const StoredCycle c = read_cycle(cycles);
    recorded.clear();
    simulated.clear();
    // Both queries run in (cycle, sensor) order: the targets of this cycle and sensor are next.
    while (target_ahead && std::pair(targets.getColumn(0).getInt(), targets.getColumn(1).getInt()) <=
                               std::pair(c.cycle, c.sensor)) {
      const StoredTarget t = read_target(targets);
      if (t.cycle != c.cycle || t.sensor != c.sensor) {
        throw std::runtime_error(fmt::format("run {}: targets of cycle {}, sensor {} have no row in the table cycles",
                                             run_id, t.cycle, t.sensor));
      }
      (t.simulated ? simulated : recorded).push_back(t);
      target_ahead = targets.executeStep();
    }
    writer.add_cycle(c, recorded, simulated);
    if (c.sensor == 0) {  // the boxes were stored with each cycle's first sensor
      boxes.clear();
      while (state_ahead && states.getColumn(0).getInt() <= c.cycle) {
        if (states.getColumn(0).getInt() == c.cycle) {
          boxes.push_back({c.cycle, states.getColumn(1).getInt(),
                           Pose2{states.getColumn(2).getDouble(), states.getColumn(3).getDouble(),
                                 states.getColumn(4).getDouble()}});
        }
        state_ahead = states.executeStep();
      }
      writer.add_object_states(c.cycle, boxes);
    }
  }
  if (target_ahead) {
    throw std::runtime_error(fmt::format("run {}: targets of cycle {}, sensor {} have no row in the table cycles", run_id,
                                         targets.getColumn(0).getInt(), targets.getColumn(1).getInt()));
  }
  writer.finish();
}

}  // namespace

void convert_row_tables_to_blocks(SQLite::Database& db) {
  std::vector<std::pair<std::int64_t, std::string>> runs;
  SQLite::Statement q(db, "SELECT run_id, parameters FROM runs ORDER BY run_id");
  while (q.executeStep()) runs.emplace_back(q.getColumn(0).getInt64(), q.getColumn(1).getString());
  for (const auto& [run_id, parameters] : runs) convert_run(db, run_id, parameters);
}

}  // namespace rcsim::replay
