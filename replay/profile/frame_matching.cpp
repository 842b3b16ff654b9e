#include "replay/profile/frame_matching.hpp"

#include <cmath>
#include <optional>

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
  FramePair pair{best_dt_s, {}, {}};
  for (std::size_t i = 0; i < pa.size(); ++i) {
    std::size_t index = 0;
    const Vec2 q = predicted(pa[i], best_dt_s);
    const bool seen = nearest(q, index) < kGateM;
    // Re-detection counts only where the later cycle still looks, away from the view field's edge.
    if (std::abs(std::atan2(q.y(), q.x())) < 0.9 * view.azimuth_half_rad && q.norm() < 0.9 * view.max_range_m) {
      pair.redetections.push_back({da[i]->amplitude_db - threshold_db, seen});
    }
    if (seen) pair.range_residuals.emplace_back(db[index]->range_m - q.norm(), db[index]->amplitude_db - threshold_db);
  }
  return pair;
}

}  // namespace

std::vector<FramePair> match_consecutive_cycles(const DetectionPool& pool, double threshold_db, const ViewLimits& view) {
  std::vector<FramePair> pairs;
  if (pool.snapshots) return pairs;
  for (std::size_t i = 0; i + 1 < pool.cycles.size(); ++i) {
    // The same sensor's next cycle: the pool holds a recording's cycles sensor after sensor.
    for (std::size_t j = i + 1; j < pool.cycles.size(); ++j) {
      const PooledCycle &a = pool.cycles[i], &b = pool.cycles[j];
      if (b.recording != a.recording || b.cycle > a.cycle + 1) break;
      if (b.sensor != a.sensor || b.cycle != a.cycle + 1 || !a.valid_fit || !b.valid_fit) continue;
      if (auto pair = match_frames(a, b, b.t_s - a.t_s, threshold_db, view)) pairs.push_back(std::move(*pair));
    }
  }
  return pairs;
}

}  // namespace rcsim::replay::profile
