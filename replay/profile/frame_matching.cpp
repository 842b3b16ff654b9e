#include "replay/profile/frame_matching.hpp"

#include <cmath>
#include <map>
#include <optional>
#include <utility>

#include "common/quantile.hpp"

namespace rcsim::replay::profile {
namespace {

constexpr double kGateM = 0.5;

Vec2 position(const PooledDetection& d) { return point_from_polar(d.range_m, d.azimuth_rad); }

// The static world seen at cycle a moves by -v dt in the sensor frame (and turns with the ego);
// dt is the one that matches the most stationary detections of b within the gate.
std::optional<FramePair> match_frames(const PooledCycle& a, const PooledCycle& b, double nominal_dt_s, double threshold_db,
                                      const ViewLimits& view) {
  std::vector<Vec2> pa, pb;
  std::vector<const PooledDetection*> da, db;
  for (const PooledDetection& d : a.detections) {
    if (d.stationary()) pa.push_back(position(d)), da.push_back(&d);
  }
  for (const PooledDetection& d : b.detections) {
    if (d.stationary()) pb.push_back(position(d)), db.push_back(&d);
  }
  if (pa.size() < 5 || pb.size() < 5) return std::nullopt;
  const Vec2 v = 0.5 * (a.v_S_S + b.v_S_S);
  const double turn_rad = b.X_WV.yaw_rad - a.X_WV.yaw_rad;
  const auto predicted = [&](const Vec2& p, double dt_s) { return rotate(-turn_rad, p - v * dt_s); };
  const auto nearest = [&](const Vec2& q, std::size_t& index) {
    double best = INFINITY;
    for (std::size_t i = 0; i < pb.size(); ++i) {
      const double d = (pb[i] - q).norm();
      if (d < best) best = d, index = i;
    }
    return best;
  };
  double best_dt_s = 0.0;
  std::size_t best_matches = 0;
  for (double dt_s = 0.2 * nominal_dt_s; dt_s <= 3.0 * nominal_dt_s; dt_s += 0.001) {
    std::size_t matches = 0, index = 0;
    for (const Vec2& p : pa) matches += nearest(predicted(p, dt_s), index) < kGateM ? 1 : 0;
    if (matches > best_matches) best_matches = matches, best_dt_s = dt_s;
  }
  if (best_matches < 5) return std::nullopt;
  // The count is flat over a gate's worth of dt: refine by the matched pairs' own shifts along v,
  // dt_i = (p_a - R^-1 p_b) . v / |v|^2, their median.
  std::vector<double> dt_i;
  for (const Vec2& p : pa) {
    std::size_t index = 0;
    if (nearest(predicted(p, best_dt_s), index) >= kGateM) continue;
    dt_i.push_back((p - rotate(turn_rad, pb[index])).dot(v) / v.squaredNorm());
  }
  best_dt_s = median(dt_i);
  FramePair pair;
  pair.dt_s = best_dt_s;
  for (std::size_t i = 0; i < pa.size(); ++i) {
    std::size_t index = 0;
    const Vec2 q = predicted(pa[i], best_dt_s);
    const bool seen = nearest(q, index) < kGateM;
    // Re-detection counts only where the later cycle still looks, away from the view field's edge.
    if (std::abs(std::atan2(q.y(), q.x())) < 0.9 * view.azimuth_half_rad && q.norm() < 0.9 * view.max_range_m) {
      pair.redetections.push_back({da[i]->amplitude_db - threshold_db, seen});
    }
    if (seen) {
      // Both radial speeds against the stationary world's along one line of sight, the earlier
      // azimuth's (moved by the ego): its error cancels in the difference.
      const Vec2 u_a = pa[i].normalized(), u_b = q.normalized();
      const double residual_a = da[i]->range_rate_mps + v.dot(u_a), residual_b = db[index]->range_rate_mps + v.dot(u_b);
      pair.matches.push_back({db[index]->range_m - q.norm(), residual_b - residual_a, da[i]->amplitude_db - threshold_db,
                              db[index]->amplitude_db - threshold_db});
    }
  }
  // What every match shares is the ego's change of speed between the cycles (and the fits' errors),
  // not noise: the radial-speed differences about their median.
  std::vector<double> rate_differences;
  for (const MatchedDetection& m : pair.matches) rate_differences.push_back(m.range_rate_mps);
  if (!rate_differences.empty()) {
    const double shared_mps = median(rate_differences);
    for (MatchedDetection& m : pair.matches) m.range_rate_mps -= shared_mps;
  }
  return pair;
}

}  // namespace

std::optional<double> fundamental_period(const std::vector<double>& dt_s) {
  const double shortest = quantile(dt_s, 0.05);
  for (double t = 1.05 * shortest; t >= 0.2 * shortest; t -= 1e-4) {
    std::vector<double> errors;
    for (const double d : dt_s) errors.push_back(std::abs(d / t - std::max(1.0, std::round(d / t))));
    if (quantile(errors, 0.9) >= 0.1) continue;
    // The steps' whole multiples k fit at t; the period is their least-squares one, sum(k d) / sum(k^2)
    // over the steps within a tenth of a period of theirs (the search's t is only the first that fits:
    // up to 5 % long).
    double kd = 0.0, kk = 0.0;
    for (const double d : dt_s) {
      const double k = std::max(1.0, std::round(d / t));
      if (std::abs(d / t - k) >= 0.1) continue;
      kd += k * d, kk += k * k;
    }
    return kd / kk;
  }
  return std::nullopt;
}

std::vector<FramePair> match_consecutive_cycles(const DetectionPool& pool, double threshold_db, const ViewLimits& view) {
  std::vector<FramePair> pairs;
  if (pool.snapshots) return pairs;
  // Each cycle with the same sensor's next one (the pool holds them in time order).
  std::map<std::pair<int, int>, std::size_t> previous;  // (recording, sensor) -> its latest cycle so far
  for (std::size_t j = 0; j < pool.cycles.size(); ++j) {
    const PooledCycle& b = pool.cycles[j];
    const auto key = std::pair{b.recording, b.sensor};
    const auto found = previous.find(key);
    const std::size_t i = found == previous.end() ? j : found->second;
    previous[key] = j;
    if (i == j) continue;  // the sensor's first cycle
    const PooledCycle& a = pool.cycles[i];
    if (b.sensor_cycle != a.sensor_cycle + 1 || !a.valid_fit || !b.valid_fit) continue;
    if (auto pair = match_frames(a, b, b.t_s - a.t_s, threshold_db, view)) {
      pair->recording = a.recording, pair->sensor = a.sensor, pair->cycle = a.cycle, pair->next_cycle = b.cycle;
      pairs.push_back(std::move(*pair));
    }
  }
  return pairs;
}

}  // namespace rcsim::replay::profile
