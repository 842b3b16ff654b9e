#include "replay/store/run_rows.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

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

}  // namespace

std::string_view store_level_name(StoreLevel level) { return level == StoreLevel::full ? "full" : "summary"; }

StoreLevel store_level_from_name(std::string_view name) {
  if (name == "full") return StoreLevel::full;
  if (name == "summary") return StoreLevel::summary;
  throw std::invalid_argument("unknown store level '" + std::string(name) + "' (full, summary)");
}

Vec2 StoredTarget::p_ST_S() const { return {range_m * std::cos(azimuth_rad), range_m * std::sin(azimuth_rad)}; }

void for_each_cycle(SQLite::Database& db, std::int64_t run_id, CycleSpan span,
                    const std::function<void(const StoredCycle&)>& visit) {
  SQLite::Statement q(db,
                      "SELECT cycle, sensor, t_s, sensor_x_m, sensor_y_m, sensor_yaw_rad, n_recorded, n_simulated, "
                      "n_assigned, gospa_m, gospa_localisation_mp, gospa_missed_mp, gospa_false_mp, ospa_m, "
                      "merge_recorded, merge_simulated, merge_matched, n_object_recorded, n_object_simulated, "
                      "n_background_recorded, n_background_simulated, gospa_object_m, ospa_object_m FROM cycles "
                      "WHERE run_id = ? AND cycle BETWEEN ? AND ? ORDER BY cycle, sensor");
  q.bind(1, run_id);
  q.bind(2, span.first);
  q.bind(3, span.last);
  while (q.executeStep()) {
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
    visit(c);
  }
}

void for_each_target(SQLite::Database& db, std::int64_t run_id, CycleSpan span,
                     const std::function<void(const StoredTarget&)>& visit) {
  SQLite::Statement q(db,
                      "SELECT cycle, sensor, origin, idx, track_id, range_m, azimuth_rad, range_rate_mps, amplitude_db, "
                      "object, match_idx, merge_artefact, target_class, x_o_m, y_o_m, rcs_dbsm, snr_db, elevation_rad "
                      "FROM targets WHERE run_id = ? AND cycle BETWEEN ? AND ? ORDER BY cycle, sensor, origin, idx");
  q.bind(1, run_id);
  q.bind(2, span.first);
  q.bind(3, span.last);
  while (q.executeStep()) {
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
    if (!q.getColumn(13).isNull()) t.p_OT_O = Vec2{q.getColumn(13).getDouble(), q.getColumn(14).getDouble()};
    t.rcs_dbsm = or_nan(q.getColumn(15));
    t.snr_db = or_nan(q.getColumn(16));
    t.elevation_rad = or_nan(q.getColumn(17));
    visit(t);
  }
}

void for_each_object_state(SQLite::Database& db, std::int64_t run_id, CycleSpan span,
                           const std::function<void(const StoredObjectState&)>& visit) {
  SQLite::Statement q(db,
                      "SELECT cycle, object, x_m, y_m, yaw_rad FROM object_states WHERE run_id = ? "
                      "AND cycle BETWEEN ? AND ? ORDER BY cycle, object");
  q.bind(1, run_id);
  q.bind(2, span.first);
  q.bind(3, span.last);
  while (q.executeStep()) {
    visit({q.getColumn(0).getInt(), q.getColumn(1).getInt(),
           Pose2{q.getColumn(2).getDouble(), q.getColumn(3).getDouble(), q.getColumn(4).getDouble()}});
  }
}

}  // namespace rcsim::replay
