#include "replay/store/figure_reader.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <string>
#include <string_view>

namespace rcsim::replay::report {

namespace {

// Runs a query bound to the run id that yields (cycle, value[, sensor]) and returns the first row.
std::optional<CycleFound> first_row(SQLite::Database& db, const char* sql, std::int64_t run_id) {
  SQLite::Statement q(db, sql);
  q.bind(1, run_id);
  if (!q.executeStep()) return std::nullopt;
  return CycleFound{q.getColumn(0).getInt(), q.getColumn(1).getDouble(),
                    q.getColumnCount() > 2 ? q.getColumn(2).getInt() : -1};
}

// Residuals of the assigned pairs, simulated - recorded; azimuth wrapped to [-pi, pi].
constexpr const char* kResidualPairs =
    "SELECT s.range_m - r.range_m AS d0, "
    "CASE WHEN s.azimuth_rad - r.azimuth_rad > 3.141592653589793 THEN s.azimuth_rad - r.azimuth_rad - 6.283185307179586 "
    "WHEN s.azimuth_rad - r.azimuth_rad < -3.141592653589793 THEN s.azimuth_rad - r.azimuth_rad + 6.283185307179586 "
    "ELSE s.azimuth_rad - r.azimuth_rad END AS d1, "
    "s.range_rate_mps - r.range_rate_mps AS d2, s.amplitude_db - r.amplitude_db AS d3 "
    "FROM targets r JOIN targets s ON s.run_id = r.run_id AND s.cycle = r.cycle AND s.sensor = r.sensor "
    "AND s.origin = 'simulated' AND s.idx = r.match_idx "
    "WHERE r.run_id = ? AND r.origin = 'recorded' AND r.match_idx IS NOT NULL";

}  // namespace

CycleHighlights read_cycle_highlights(SQLite::Database& db, std::int64_t run_id) {
  CycleHighlights h;
  h.largest_gospa = first_row(
      db, "SELECT cycle, gospa_m, sensor FROM cycles WHERE run_id = ? ORDER BY gospa_m DESC, cycle LIMIT 1", run_id);
  h.most_merge_artefacts = first_row(db,
                                     "SELECT cycle, sum(merge_recorded + merge_simulated) AS m FROM cycles WHERE run_id = ? "
                                     "GROUP BY cycle HAVING m > 0 ORDER BY m DESC, cycle LIMIT 1",
                                     run_id);
  h.first_recorded =
      first_row(db, "SELECT cycle, 0 FROM cycles WHERE run_id = ? AND n_recorded > 0 ORDER BY cycle LIMIT 1", run_id);
  h.first_simulated =
      first_row(db, "SELECT cycle, 0 FROM cycles WHERE run_id = ? AND n_simulated > 0 ORDER BY cycle LIMIT 1", run_id);
  h.largest_count_difference = first_row(db,
                                         "SELECT cycle, sum(abs(n_recorded - n_simulated)) AS d FROM cycles WHERE run_id = ? "
                                         "GROUP BY cycle HAVING d > 0 ORDER BY d DESC, cycle LIMIT 1",
                                         run_id);
  return h;
}

CycleWindow read_cycle_window(SQLite::Database& db, std::int64_t run_id, int first_cycle, int cycle) {
  CycleWindow w;
  w.first_cycle = first_cycle;
  w.cycle = cycle;
  SQLite::Statement cycles(db,
                           "SELECT cycle, sensor, t_s, sensor_x_m, sensor_y_m, sensor_yaw_rad, n_recorded, n_simulated, "
                           "gospa_m FROM cycles WHERE run_id = ? AND cycle BETWEEN ? AND ? ORDER BY cycle, sensor");
  cycles.bind(1, run_id);
  cycles.bind(2, first_cycle);
  cycles.bind(3, cycle);
  while (cycles.executeStep()) {
    w.cycles.push_back({cycles.getColumn(0).getInt(), cycles.getColumn(1).getInt(), cycles.getColumn(2).getDouble(),
                        Pose2{cycles.getColumn(3).getDouble(), cycles.getColumn(4).getDouble(), cycles.getColumn(5).getDouble()},
                        cycles.getColumn(6).getInt64(), cycles.getColumn(7).getInt64(), cycles.getColumn(8).getDouble()});
  }
  SQLite::Statement pairs(db, "SELECT object_a, object_b FROM merge_pairs WHERE run_id = ? AND cycle = ?");
  pairs.bind(1, run_id);
  pairs.bind(2, cycle);
  while (pairs.executeStep()) w.merge_pairs.emplace_back(pairs.getColumn(0).getInt(), pairs.getColumn(1).getInt());
  SQLite::Statement objects(db, "SELECT object, x_m, y_m, yaw_rad FROM object_states WHERE run_id = ? AND cycle = ?");
  objects.bind(1, run_id);
  objects.bind(2, cycle);
  while (objects.executeStep()) {
    w.objects.push_back({objects.getColumn(0).getInt(),
                         Pose2{objects.getColumn(1).getDouble(), objects.getColumn(2).getDouble(), objects.getColumn(3).getDouble()}});
  }
  SQLite::Statement targets(db,
                            "SELECT cycle, sensor, origin, idx, x_s_m, y_s_m, match_idx, merge_artefact, target_class FROM targets "
                            "WHERE run_id = ? AND cycle BETWEEN ? AND ?");
  targets.bind(1, run_id);
  targets.bind(2, first_cycle);
  targets.bind(3, cycle);
  while (targets.executeStep()) {
    TargetRow t;
    t.cycle = targets.getColumn(0).getInt();
    t.sensor = targets.getColumn(1).getInt();
    t.simulated = targets.getColumn(2).getString() == "simulated";
    t.idx = targets.getColumn(3).getInt();
    t.p_ST_S = {targets.getColumn(4).getDouble(), targets.getColumn(5).getDouble()};
    if (!targets.getColumn(6).isNull()) t.match_idx = targets.getColumn(6).getInt();
    t.merge_artefact = targets.getColumn(7).getInt() != 0;
    if (!targets.getColumn(8).isNull()) t.target_class = targets.getColumn(8).getString();
    w.targets.push_back(t);
  }
  return w;
}

std::vector<NearestTargetRow> read_nearest_targets(SQLite::Database& db, std::int64_t run_id, int stride) {
  // SQLite returns the bare columns of the row holding the min().
  SQLite::Statement q(db,
                      "SELECT t.sensor, t.origin, c.t_s, min(t.range_m), t.x_s_m, t.y_s_m FROM targets t "
                      "JOIN cycles c ON c.run_id = t.run_id AND c.cycle = t.cycle AND c.sensor = t.sensor "
                      "WHERE t.run_id = ? AND t.cycle % ? = 0 GROUP BY t.cycle, t.sensor, t.origin "
                      "ORDER BY t.cycle, t.sensor, t.origin");
  q.bind(1, run_id);
  q.bind(2, stride);
  std::vector<NearestTargetRow> rows;
  while (q.executeStep()) {
    rows.push_back({q.getColumn(0).getInt(), q.getColumn(1).getString() == "simulated", q.getColumn(2).getDouble(),
                    q.getColumn(3).getDouble(), Vec2{q.getColumn(4).getDouble(), q.getColumn(5).getDouble()}});
  }
  return rows;
}

std::vector<CycleBucketRow> read_cycle_buckets(SQLite::Database& db, std::int64_t run_id, int stride) {
  SQLite::Statement q(db,
                      "SELECT sensor, cycle / ? AS bucket, min(t_s), avg(n_recorded), avg(n_simulated), avg(gospa_m), "
                      "max(gospa_m) FROM cycles WHERE run_id = ? GROUP BY sensor, bucket ORDER BY sensor, bucket");
  q.bind(1, stride);
  q.bind(2, run_id);
  std::vector<CycleBucketRow> rows;
  while (q.executeStep()) {
    rows.push_back({q.getColumn(0).getInt(), q.getColumn(2).getDouble(), q.getColumn(3).getDouble(),
                    q.getColumn(4).getDouble(), q.getColumn(5).getDouble(), q.getColumn(6).getDouble()});
  }
  return rows;
}

ResidualSampleStats read_residual_sample_stats(SQLite::Database& db, std::int64_t run_id, int stride) {
  SQLite::Statement q(db, std::string("SELECT count(*), avg(d0), avg(d0 * d0), min(d0), max(d0), avg(d1), "
                                      "avg(d1 * d1), min(d1), max(d1), avg(d2), avg(d2 * d2), min(d2), max(d2), "
                                      "avg(d3), avg(d3 * d3), min(d3), max(d3) FROM (") +
                              kResidualPairs + " AND r.cycle % ? = 0)");
  q.bind(1, run_id);
  q.bind(2, stride);
  q.executeStep();
  ResidualSampleStats stats;
  stats.count = q.getColumn(0).getInt64();
  if (stats.count == 0) return stats;
  for (int i = 0; i < 4; ++i) {
    const auto k = static_cast<std::size_t>(i);
    stats.mean[k] = q.getColumn(1 + 4 * i).getDouble();
    stats.mean_square[k] = q.getColumn(2 + 4 * i).getDouble();
    stats.min[k] = q.getColumn(3 + 4 * i).getDouble();
    stats.max[k] = q.getColumn(4 + 4 * i).getDouble();
  }
  return stats;
}

std::int64_t for_each_residual(SQLite::Database& db, std::int64_t run_id, const std::function<void(const Residuals&)>& visit) {
  SQLite::Statement q(db, kResidualPairs);
  q.bind(1, run_id);
  std::int64_t n = 0;
  while (q.executeStep()) {
    ++n;
    visit({q.getColumn(0).getDouble(), q.getColumn(1).getDouble(), q.getColumn(2).getDouble(), q.getColumn(3).getDouble()});
  }
  return n;
}

std::vector<ObjectFrameTarget> read_object_frame_targets(SQLite::Database& db, std::int64_t run_id, int object,
                                                         int max_per_origin) {
  std::vector<ObjectFrameTarget> rows;
  for (const char* origin : {"recorded", "simulated"}) {
    // Evenly thinned by a stride over the object's targets of that origin.
    SQLite::Statement n(db, "SELECT count(*) FROM targets WHERE run_id = ? AND object = ? AND origin = ? "
                            "AND target_class = 'object'");
    n.bind(1, run_id);
    n.bind(2, object);
    n.bind(3, origin);
    n.executeStep();
    const std::int64_t count = n.getColumn(0).getInt64();
    const std::int64_t stride = std::max<std::int64_t>(1, (count + max_per_origin - 1) / std::max(1, max_per_origin));
    SQLite::Statement q(db, "SELECT sensor, x_o_m, y_o_m FROM (SELECT sensor, x_o_m, y_o_m, "
                            "row_number() OVER (ORDER BY cycle, sensor, idx) AS k FROM targets "
                            "WHERE run_id = ? AND object = ? AND origin = ? AND target_class = 'object') "
                            "WHERE (k - 1) % ? = 0");
    q.bind(1, run_id);
    q.bind(2, object);
    q.bind(3, origin);
    q.bind(4, stride);
    while (q.executeStep()) {
      rows.push_back({q.getColumn(0).getInt(), std::string_view(origin) == "simulated",
                      Vec2{q.getColumn(1).getDouble(), q.getColumn(2).getDouble()}});
    }
  }
  return rows;
}

BackgroundHistogram read_background_histogram(SQLite::Database& db, std::int64_t run_id, BackgroundQuantity quantity,
                                              double lo, double bin_width, int bins) {
  BackgroundHistogram h;
  h.lo = lo;
  h.bin_width = bin_width;
  for (auto& counts : h.counts) counts.assign(static_cast<std::size_t>(std::max(0, bins)), 0);
  // The column is one of two fixed names, never text from outside.
  const char* column = quantity == BackgroundQuantity::range ? "range_m" : "azimuth_rad";
  SQLite::Statement q(db, fmt::format("SELECT origin, CAST(({} - ?) / ? AS INTEGER) AS b, count(*) FROM targets "
                                      "WHERE run_id = ? AND target_class = 'background' GROUP BY origin, b",
                                      column));
  q.bind(1, lo);
  q.bind(2, bin_width);
  q.bind(3, run_id);
  while (q.executeStep()) {
    const int origin = q.getColumn(0).getString() == "simulated" ? 1 : 0;
    const auto b = std::clamp<std::int64_t>(q.getColumn(1).getInt64(), 0, std::max(0, bins - 1));
    if (bins > 0) h.counts[origin][static_cast<std::size_t>(b)] += q.getColumn(2).getInt64();
  }
  return h;
}

}  // namespace rcsim::replay::report
