#include "sim/effects.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/decibel.hpp"

namespace rcsim {

namespace {

// Slab test in the box frame: the segment a + t d, t in [0, 1], against the box of length_m by
// width_m centred on the origin.
bool segment_hits_box_in_box_frame(const Vec2& a, const Vec2& d, double length_m, double width_m) {
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

// What apply_occlusion needs of a candidate occluder, the same for every target of the cycle:
// its reach beyond a target's range, its squared distance from the sensor, its rotation into the
// box frame (the cosine and sine inverse_transform_point takes) and the sensor in the box frame.
struct Occluder {
  std::size_t index;
  double half_diagonal_m, squared_distance_m2, cos_yaw, sin_yaw;
  Vec2 p_BS_B;
  // inverse_transform_point(X_WB, p_W), its rotation taken once.
  Vec2 in_box_frame(const Vec2& p_W, const Vec2& p_WB_W) const {
    const Vec2 v = p_W - p_WB_W;
    return {cos_yaw * v.x() - sin_yaw * v.y(), sin_yaw * v.x() + cos_yaw * v.y()};
  }
};

}  // namespace

bool segment_hits_box(const Vec2& a_W, const Vec2& b_W, const Pose2& X_WB, double length_m, double width_m) {
  const Vec2 a = inverse_transform_point(X_WB, a_W);
  const Vec2 d = inverse_transform_point(X_WB, b_W) - a;
  return segment_hits_box_in_box_frame(a, d, length_m, width_m);
}

void apply_occlusion(const OcclusionConfig& occlusion, const SensorKinematics& sensor, std::span<const SceneObject> objects,
                     std::span<const BodyState> object_states, std::span<const unsigned char> candidates,
                     IdealTargets& ideal) {
  const Vec2 p_WS_W = sensor.X_WS.translation();
  // Each candidate's per-cycle figures once, not once per target (the same values, the same
  // arithmetic as segment_hits_box: the outputs do not change).
  std::vector<Occluder> occluders;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (!candidates[i]) continue;
    const auto& model = objects[i].model;
    if (model.clearance_m > 0.0) continue;  // it stands above the road: lines of sight pass beneath
    const Pose2& X_WB = object_states[i].X_WB;
    Occluder o{i, 0.5 * std::hypot(model.length_m, model.width_m), (X_WB.translation() - p_WS_W).squaredNorm(),
               std::cos(-X_WB.yaw_rad), std::sin(-X_WB.yaw_rad), Vec2::Zero()};
    o.p_BS_B = o.in_box_frame(p_WS_W, X_WB.translation());
    occluders.push_back(o);
  }
  const auto occluded = [&](const IdealTarget& t) {
    for (const Occluder& o : occluders) {
      if (static_cast<int>(o.index) == t.object_index) continue;
      const double reach_m = t.range_m + o.half_diagonal_m;
      if (o.squared_distance_m2 > reach_m * reach_m) continue;
      const Pose2& X_WB = object_states[o.index].X_WB;
      const auto& model = objects[o.index].model;
      const Vec2 d = o.in_box_frame(t.p_WT_W, X_WB.translation()) - o.p_BS_B;
      if (segment_hits_box_in_box_frame(o.p_BS_B, d, model.length_m, model.width_m)) return true;
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
