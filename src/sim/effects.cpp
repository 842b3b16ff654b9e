#include "sim/effects.hpp"

#include <algorithm>
#include <cmath>

#include "common/decibel.hpp"

namespace rcsim {

bool segment_hits_box(const Vec2& a_W, const Vec2& b_W, const Pose2& X_WB, double length_m, double width_m) {
  // Slab test in the box frame.
  const Vec2 a = inverse_transform_point(X_WB, a_W);
  const Vec2 d = inverse_transform_point(X_WB, b_W) - a;
  const double half[2] = {0.5 * length_m, 0.5 * width_m};
  double t_enter = 0.0, t_exit = 1.0;
  for (int axis = 0; axis < 2; ++axis) {
    const double origin = a[axis];
    const double direction = d[axis];
    if (std::abs(direction) < 1e-12) {
      if (origin < -half[axis] || origin > half[axis]) return false;
      continue;
    }
    double t0 = (-half[axis] - origin) / direction;
    double t1 = (half[axis] - origin) / direction;
    if (t0 > t1) std::swap(t0, t1);
    t_enter = std::max(t_enter, t0);
    t_exit = std::min(t_exit, t1);
    if (t_enter > t_exit) return false;
  }
  return true;
}

void apply_occlusion(const OcclusionConfig& occlusion, const SensorKinematics& sensor, std::span<const SceneObject> objects,
                     std::span<const BodyState> object_states, std::span<const unsigned char> candidates,
                     IdealTargets& ideal) {
  const Vec2 p_WS_W = sensor.X_WS.translation();
  const auto occluded = [&](const IdealTarget& t) {
    for (std::size_t i = 0; i < objects.size(); ++i) {
      if (static_cast<int>(i) == t.object_index || !candidates[i]) continue;
      const auto& model = objects[i].model;
      const double reach_m = t.range_m + 0.5 * std::hypot(model.length_m, model.width_m);
      if ((object_states[i].X_WB.translation() - p_WS_W).squaredNorm() > reach_m * reach_m) continue;
      if (segment_hits_box(p_WS_W, t.p_WT_W, object_states[i].X_WB, model.length_m, model.width_m)) return true;
    }
    return false;
  };
  if (std::isinf(occlusion.loss_db)) {
    std::erase_if(ideal, occluded);
    return;
  }
  const double factor = db_to_amplitude(-occlusion.loss_db);
  for (auto& t : ideal) {
    if (occluded(t)) t.ercs *= factor;
  }
}

double multibounce_ercs_factor(const MultibounceConfig& config, int order) {
  return db_to_amplitude(-config.loss_per_bounce_db * (order - 1));
}

void add_multibounce_targets(const MultibounceConfig& config, IdealTargets& ideal) {
  const std::size_t direct_count = ideal.size();
  for (std::size_t i = 0; i < direct_count; ++i) {
    if (ideal[i].range_m >= config.max_range_m) continue;
    for (int order = 2; order <= config.max_order; ++order) {
      IdealTarget copy = ideal[i];
      copy.range_m *= order;
      copy.range_rate_mps *= order;
      copy.ercs *= multibounce_ercs_factor(config, order);
      copy.bounce_order = order;
      ideal.push_back(copy);
    }
  }
}

void add_clutter(const SensorConfig& config, const SensorKinematics& sensor, Rng& rng, Detections& detections) {
  const int count = rng.poisson(config.clutter.false_detections_per_cycle);
  for (int i = 0; i < count; ++i) {
    Detection d;
    d.range_m = rng.uniform(config.fov.min_range_m, config.fov.max_range_m);
    d.azimuth_rad = rng.uniform(-config.fov.azimuth_half_rad, config.fov.azimuth_half_rad);
    const Vec2 u_W = rotate(sensor.X_WS.yaw_rad + d.azimuth_rad, Vec2(1.0, 0.0));
    d.range_rate_mps = -sensor.v_WS_W.dot(u_W);  // a stationary reflector
    d.amplitude_db = config.amplitude.detection_threshold_db + rng.exponential(config.clutter.amplitude_excess_mean_db);
    d.object_index = -1;
    detections.push_back(d);
  }
}

}  // namespace rcsim
