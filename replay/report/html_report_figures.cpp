#include "replay/report/html_report_figures.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>

#include "common/angles.hpp"
#include "replay/report/svg_writer.hpp"

namespace rcsim::replay::report {

namespace {

Pose2 inverse(const Pose2& X_AB) {
  const Vec2 p = rotate(-X_AB.yaw_rad, -X_AB.translation());
  return {p.x(), p.y(), -X_AB.yaw_rad};
}

const SensorInfo* find_sensor(const RunData& run, int sensor) {
  for (const auto& s : run.sensors) {
    if (s.sensor == sensor) return &s;
  }
  return nullptr;
}

// Runs a query bound to the run id that yields (cycle, value) and returns the first row.
bool first_row(SQLite::Database& db, const char* sql, std::int64_t run_id, int& cycle, double& value, int& sensor) {
  SQLite::Statement q(db, sql);
  q.bind(1, run_id);
  if (!q.executeStep()) return false;
  cycle = q.getColumn(0).getInt();
  value = q.getColumn(1).getDouble();
  sensor = q.getColumnCount() > 2 ? q.getColumn(2).getInt() : -1;
  return true;
}

}  // namespace

std::vector<ChosenCycle> choose_cycles(SQLite::Database& db, const RunData& run, std::size_t max_count) {
  std::vector<ChosenCycle> chosen;
  const auto add = [&](int cycle, const std::string& reason) {
    for (auto& c : chosen) {
      if (c.cycle == cycle) {
        c.reason += "; " + reason;
        return;
      }
    }
    if (chosen.size() < max_count) chosen.push_back({cycle, reason});
  };
  const std::int64_t id = run.info.run_id;
  int cycle = 0, sensor = 0;
  double value = 0.0;
  if (first_row(db, "SELECT cycle, gospa_m, sensor FROM cycles WHERE run_id = ? ORDER BY gospa_m DESC, cycle LIMIT 1",
                id, cycle, value, sensor) &&
      value > 0.0) {
    add(cycle, fmt::format("largest GOSPA ({:.2f} m, sensor {})", value, run.sensor_label(sensor)));
  }
  if (first_row(db,
                "SELECT cycle, sum(merge_recorded + merge_simulated) AS m FROM cycles WHERE run_id = ? "
                "GROUP BY cycle HAVING m > 0 ORDER BY m DESC, cycle LIMIT 1",
                id, cycle, value, sensor)) {
    add(cycle, fmt::format("most merge artefacts ({:.0f}, recorded + simulated)", value));
  }
  if (first_row(db, "SELECT cycle, 0 FROM cycles WHERE run_id = ? AND n_recorded > 0 ORDER BY cycle LIMIT 1", id,
                cycle, value, sensor)) {
    add(cycle, "first recorded target");
  }
  if (run.info.cycles > 0) add(run.info.cycles / 2, "middle of the run");
  if (first_row(db, "SELECT cycle, 0 FROM cycles WHERE run_id = ? AND n_simulated > 0 ORDER BY cycle LIMIT 1", id,
                cycle, value, sensor)) {
    add(cycle, "first simulated target");
  }
  if (first_row(db,
                "SELECT cycle, sum(abs(n_recorded - n_simulated)) AS d FROM cycles WHERE run_id = ? "
                "GROUP BY cycle HAVING d > 0 ORDER BY d DESC, cycle LIMIT 1",
                id, cycle, value, sensor)) {
    add(cycle, fmt::format("largest count difference ({:.0f})", value));
  }
  // Fill up with the last cycle and the quarters, so that quiet runs still show their course.
  if (run.info.cycles > 0) {
    add(run.info.cycles - 1, "last cycle");
    add(run.info.cycles / 4, "first quarter");
    add(3 * run.info.cycles / 4, "third quarter");
  }
  std::sort(chosen.begin(), chosen.end(), [](const auto& a, const auto& b) { return a.cycle < b.cycle; });
  return chosen;
}

svg::BirdsEyeSpec birdseye_of_cycle(SQLite::Database& db, const RunData& run, const ChosenCycle& chosen,
                                    int trace_cycles) {
  const int k = chosen.cycle, k0 = std::max(0, k - std::max(0, trace_cycles));
  svg::BirdsEyeSpec spec;
  spec.trace_cycles = k - k0;

  // Sensor poses in the world for the pictured cycle and its traces.
  std::map<std::pair<int, int>, Pose2> X_WS;  // (cycle, sensor)
  double t_s = 0.0;
  long long n_recorded = 0, n_simulated = 0;
  std::string gospa_text;
  {
    SQLite::Statement q(db,
                        "SELECT cycle, sensor, t_s, sensor_x_m, sensor_y_m, sensor_yaw_rad, n_recorded, n_simulated, "
                        "gospa_m FROM cycles WHERE run_id = ? AND cycle BETWEEN ? AND ? ORDER BY cycle, sensor");
    q.bind(1, run.info.run_id);
    q.bind(2, k0);
    q.bind(3, k);
    while (q.executeStep()) {
      const int cycle = q.getColumn(0).getInt(), sensor = q.getColumn(1).getInt();
      X_WS[{cycle, sensor}] = {q.getColumn(3).getDouble(), q.getColumn(4).getDouble(), q.getColumn(5).getDouble()};
      if (cycle != k) continue;
      t_s = q.getColumn(2).getDouble();
      n_recorded += q.getColumn(6).getInt64();
      n_simulated += q.getColumn(7).getInt64();
      gospa_text += fmt::format("{}{:.2f} m ({})", gospa_text.empty() ? "" : ", ", q.getColumn(8).getDouble(),
                                run.sensor_label(sensor));
    }
  }
  // The vehicle pose from the first sensor: X_WV = X_WS * X_VS^-1.
  Pose2 X_VW;
  for (const auto& s : run.sensors) {
    const auto it = X_WS.find({k, s.sensor});
    if (it == X_WS.end()) continue;
    X_VW = inverse(compose(it->second, inverse(s.X_VS)));
    break;
  }
  spec.title = fmt::format("Cycle {} at t = {:.2f} s", k, t_s);
  spec.notes.push_back(chosen.reason);
  spec.notes.push_back(fmt::format("{} recorded / {} simulated targets; GOSPA {}", n_recorded, n_simulated,
                                   gospa_text.empty() ? "-" : gospa_text));
  if (spec.trace_cycles > 0) spec.notes.push_back(fmt::format("faded: the {} cycles before", spec.trace_cycles));
  for (const auto& s : run.sensors) spec.sensors.push_back({s.id, s.X_VS, s.azimuth_half_rad, s.max_range_m});

  {
    std::vector<std::pair<int, int>> merge_objects;
    SQLite::Statement pairs(db, "SELECT object_a, object_b FROM merge_pairs WHERE run_id = ? AND cycle = ?");
    pairs.bind(1, run.info.run_id);
    pairs.bind(2, k);
    while (pairs.executeStep()) merge_objects.emplace_back(pairs.getColumn(0).getInt(), pairs.getColumn(1).getInt());
    SQLite::Statement q(db, "SELECT object, x_m, y_m, yaw_rad FROM object_states WHERE run_id = ? AND cycle = ?");
    q.bind(1, run.info.run_id);
    q.bind(2, k);
    while (q.executeStep()) {
      const int object = q.getColumn(0).getInt();
      const Pose2 X_WO{q.getColumn(1).getDouble(), q.getColumn(2).getDouble(), q.getColumn(3).getDouble()};
      svg::BirdsEyeBox box;
      box.label = svg::shorten(run.object_label(object), 14);
      box.X_VO = compose(X_VW, X_WO);
      for (const auto& o : run.objects) {
        if (o.object == object) box.length_m = o.length_m, box.width_m = o.width_m;
      }
      for (const auto& [a, b] : merge_objects) box.in_merge_pair = box.in_merge_pair || a == object || b == object;
      spec.boxes.push_back(std::move(box));
    }
  }

  // Targets of the cycle and its traces, into the pictured cycle's vehicle frame.
  std::map<std::pair<int, int>, Vec2> simulated_now;              // (sensor, idx) -> p_V
  std::vector<std::pair<std::pair<int, int>, Vec2>> recorded_now;  // ((sensor, match), p_V)
  SQLite::Statement q(db,
                      "SELECT cycle, sensor, origin, idx, x_s_m, y_s_m, match_idx, merge_artefact FROM targets "
                      "WHERE run_id = ? AND cycle BETWEEN ? AND ?");
  q.bind(1, run.info.run_id);
  q.bind(2, k0);
  q.bind(3, k);
  while (q.executeStep()) {
    const int cycle = q.getColumn(0).getInt(), sensor = q.getColumn(1).getInt();
    const auto pose = X_WS.find({cycle, sensor});
    if (pose == X_WS.end()) continue;
    svg::BirdsEyeTarget t;
    t.simulated = q.getColumn(2).getString() == "simulated";
    t.age = k - cycle;
    t.merge_artefact = q.getColumn(7).getInt() != 0;
    t.p_V = transform_point(X_VW, transform_point(pose->second, {q.getColumn(4).getDouble(), q.getColumn(5).getDouble()}));
    spec.targets.push_back(t);
    if (cycle != k) continue;
    if (t.simulated) {
      simulated_now[{sensor, q.getColumn(3).getInt()}] = t.p_V;
    } else if (!q.getColumn(6).isNull()) {
      recorded_now.push_back({{sensor, q.getColumn(6).getInt()}, t.p_V});
    }
  }
  for (const auto& [key, p_V] : recorded_now) {
    const auto it = simulated_now.find(key);
    if (it != simulated_now.end()) spec.links.push_back({p_V, it->second});
  }
  return spec;
}

std::vector<svg::PlotSpec> time_series(SQLite::Database& db, const RunData& run, int max_points) {
  const int cycles = std::max(1, run.info.cycles);
  const int stride = std::max(1, (cycles + max_points - 1) / std::max(1, max_points));
  struct PerSensor {
    svg::PlotSeries range[2], lateral[2], count[2], gospa_mean, gospa_max;
  };
  std::map<int, PerSensor> series;
  for (const auto& s : run.sensors) series[s.sensor];

  // Nearest target of every `stride`-th cycle (SQLite returns the bare columns of the row
  // holding the min()).
  {
    SQLite::Statement q(db,
                        "SELECT t.sensor, t.origin, c.t_s, min(t.range_m), t.x_s_m, t.y_s_m FROM targets t "
                        "JOIN cycles c ON c.run_id = t.run_id AND c.cycle = t.cycle AND c.sensor = t.sensor "
                        "WHERE t.run_id = ? AND t.cycle % ? = 0 GROUP BY t.cycle, t.sensor, t.origin "
                        "ORDER BY t.cycle, t.sensor, t.origin");
    q.bind(1, run.info.run_id);
    q.bind(2, stride);
    while (q.executeStep()) {
      const int sensor = q.getColumn(0).getInt();
      const int origin = q.getColumn(1).getString() == "simulated" ? 1 : 0;
      const SensorInfo* info = find_sensor(run, sensor);
      if (info == nullptr) continue;
      const double t = q.getColumn(2).getDouble();
      const Vec2 p_V = transform_point(info->X_VS, {q.getColumn(4).getDouble(), q.getColumn(5).getDouble()});
      PerSensor& p = series[sensor];
      p.range[origin].points.emplace_back(t, q.getColumn(3).getDouble());
      p.lateral[origin].points.emplace_back(t, p_V.y());
    }
  }
  // Counts and GOSPA: means (and the GOSPA maximum) over buckets of `stride` cycles.
  {
    SQLite::Statement q(db,
                        "SELECT sensor, cycle / ? AS bucket, min(t_s), avg(n_recorded), avg(n_simulated), avg(gospa_m), "
                        "max(gospa_m) FROM cycles WHERE run_id = ? GROUP BY sensor, bucket ORDER BY sensor, bucket");
    q.bind(1, stride);
    q.bind(2, run.info.run_id);
    while (q.executeStep()) {
      PerSensor& p = series[q.getColumn(0).getInt()];
      const double t = q.getColumn(2).getDouble();
      p.count[0].points.emplace_back(t, q.getColumn(3).getDouble());
      p.count[1].points.emplace_back(t, q.getColumn(4).getDouble());
      p.gospa_mean.points.emplace_back(t, q.getColumn(5).getDouble());
      p.gospa_max.points.emplace_back(t, q.getColumn(6).getDouble());
    }
  }

  const std::string dots_note = stride > 1 ? fmt::format("every {}th cycle shown", stride) : "";
  const std::string mean_note = stride > 1 ? fmt::format("mean over {} cycles per point", stride) : "";
  std::vector<svg::PlotSpec> plots;
  for (auto& [sensor, p] : series) {
    const std::string name = run.sensor_label(sensor);
    const auto pair = [&](svg::PlotSeries (&s)[2], bool dots) {
      s[0].label = "recorded", s[0].colour = svg::kRecordedColour, s[0].dots = dots;
      s[1].label = "simulated", s[1].colour = svg::kSimulatedColour, s[1].dots = dots, s[1].dashed = !dots;
      return std::vector<svg::PlotSeries>{std::move(s[0]), std::move(s[1])};
    };
    plots.push_back({"Nearest target range, sensor " + name, "t / s", "range / m", dots_note, 600, 250, false,
                     pair(p.range, true)});
    plots.push_back({"Nearest target lateral position, sensor " + name, "t / s", "y / m (vehicle frame)",
                     dots_note, 600, 250, false, pair(p.lateral, true)});
    plots.push_back({"Targets per cycle, sensor " + name, "t / s", "targets", mean_note, 600, 250, true,
                     pair(p.count, false)});
    std::vector<svg::PlotSeries> gospa;
    if (stride > 1) {
      p.gospa_max.label = "maximum", p.gospa_max.colour = "#adb5bd";
      gospa.push_back(std::move(p.gospa_max));
    }
    p.gospa_mean.label = stride > 1 ? "mean" : "GOSPA", p.gospa_mean.colour = "#212529";
    gospa.push_back(std::move(p.gospa_mean));
    plots.push_back({"GOSPA, sensor " + name, "t / s", "GOSPA / m", mean_note, 600, 250, true, std::move(gospa)});
  }
  return plots;
}

std::vector<svg::HistogramSpec> residual_histograms(SQLite::Database& db, const RunData& run, int bins) {
  // Residuals of the assigned pairs, simulated - recorded; azimuth wrapped to [-pi, pi].
  static const char* const kPairs =
      "SELECT s.range_m - r.range_m AS d0, "
      "CASE WHEN s.azimuth_rad - r.azimuth_rad > 3.141592653589793 THEN s.azimuth_rad - r.azimuth_rad - 6.283185307179586 "
      "WHEN s.azimuth_rad - r.azimuth_rad < -3.141592653589793 THEN s.azimuth_rad - r.azimuth_rad + 6.283185307179586 "
      "ELSE s.azimuth_rad - r.azimuth_rad END AS d1, "
      "s.range_rate_mps - r.range_rate_mps AS d2, s.amplitude_db - r.amplitude_db AS d3 "
      "FROM targets r JOIN targets s ON s.run_id = r.run_id AND s.cycle = r.cycle AND s.sensor = r.sensor "
      "AND s.origin = 'simulated' AND s.idx = r.match_idx "
      "WHERE r.run_id = ? AND r.origin = 'recorded' AND r.match_idx IS NOT NULL";
  struct Quantity {
    const char* title;
    const char* label;
    double scale;     // stored unit -> shown unit
    double min_span;  // in the shown unit
  };
  const Quantity quantities[4] = {{"Range residual", "range, simulated - recorded / m", 1.0, 0.02},
                                  {"Azimuth residual", "azimuth, simulated - recorded / deg", 180.0 / kPi, 0.02},
                                  {"Range-rate residual", "range rate, simulated - recorded / (m/s)", 1.0, 0.02},
                                  {"Amplitude residual", "amplitude, simulated - recorded / dB", 1.0, 0.02}};

  // First pass, in SQL, over the pairs of about 5000 cycles spread over the run: count, mean,
  // mean square, min, max of each residual, to choose the histogram ranges.
  const int stride = std::max(1, run.info.cycles / 5000);
  SQLite::Statement stats(db, std::string("SELECT count(*), avg(d0), avg(d0 * d0), min(d0), max(d0), avg(d1), "
                                          "avg(d1 * d1), min(d1), max(d1), avg(d2), avg(d2 * d2), min(d2), max(d2), "
                                          "avg(d3), avg(d3 * d3), min(d3), max(d3) FROM (") +
                                  kPairs + " AND r.cycle % ? = 0)");
  stats.bind(1, run.info.run_id);
  stats.bind(2, stride);
  stats.executeStep();
  const long long n_sample = stats.getColumn(0).getInt64();
  std::vector<svg::HistogramSpec> out(4);
  double lo[4], width[4], sum[4] = {0, 0, 0, 0}, sum_sq[4] = {0, 0, 0, 0};
  for (int i = 0; i < 4; ++i) {
    const Quantity& quantity = quantities[i];
    svg::HistogramSpec& h = out[static_cast<std::size_t>(i)];
    h.title = quantity.title;
    h.x_label = quantity.label;
    h.counts.assign(static_cast<std::size_t>(std::max(1, bins)), 0);
    double a = 0.0, b = 0.0;
    if (n_sample > 0) {
      const double mean = stats.getColumn(1 + 4 * i).getDouble() * quantity.scale;
      const double mean_sq = stats.getColumn(2 + 4 * i).getDouble() * quantity.scale * quantity.scale;
      const double sigma = std::sqrt(std::max(0.0, mean_sq - mean * mean));
      // The view: the data, but no more than four standard deviations about the mean, so that
      // a few gross mismatches do not squeeze the bulk into one bin.
      a = std::max(stats.getColumn(3 + 4 * i).getDouble() * quantity.scale, mean - 4.0 * sigma);
      b = std::min(stats.getColumn(4 + 4 * i).getDouble() * quantity.scale, mean + 4.0 * sigma);
    }
    svg::widen(a, b, quantity.min_span, 0.02);
    lo[i] = a;
    width[i] = (b - a) / static_cast<double>(h.counts.size());
    h.lo = a;
    h.bin_width = width[i];
  }
  // Second pass: stream all pairs, bin them and sum for the exact mean and RMS.
  SQLite::Statement pairs(db, kPairs);
  pairs.bind(1, run.info.run_id);
  long long n = 0;
  while (pairs.executeStep()) {
    ++n;
    for (int i = 0; i < 4; ++i) {
      svg::HistogramSpec& h = out[static_cast<std::size_t>(i)];
      const double v = pairs.getColumn(i).getDouble() * quantities[i].scale;
      sum[i] += v;
      sum_sq[i] += v * v;
      const double bin = std::floor((v - lo[i]) / width[i]);
      const double last = static_cast<double>(h.counts.size() - 1);
      if (bin < 0.0) ++h.below;
      if (bin > last) ++h.above;
      ++h.counts[static_cast<std::size_t>(std::clamp(bin, 0.0, last))];
    }
  }
  for (int i = 0; i < 4 && n > 0; ++i) {
    const double count = static_cast<double>(n);
    out[static_cast<std::size_t>(i)].note =
        fmt::format("{} pairs, mean {:.3g}, RMS {:.3g}", n, sum[i] / count, std::sqrt(sum_sq[i] / count));
  }
  return out;
}

}  // namespace rcsim::replay::report
