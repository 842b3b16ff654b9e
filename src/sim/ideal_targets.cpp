#include "sim/ideal_targets.hpp"

#include <cmath>

#include "sim/visibility.hpp"

namespace rcsim {
namespace {

// Range and view-field check by dot products (no trigonometry for what is rejected).
bool in_view(const FieldOfView& fov, double tan_half, const Vec2& p_ST_S) {
  const double range2 = p_ST_S.squaredNorm();
  if (range2 > fov.max_range_m * fov.max_range_m || range2 < fov.min_range_m * fov.min_range_m) return false;
  return p_ST_S.x() > 0.0 && std::abs(p_ST_S.y()) <= tan_half * p_ST_S.x();
}

}  // namespace

SensorKinematics sensor_kinematics(const BodyState& ego, const Pose2& X_VS) {
  SensorKinematics k;
  k.X_WS = compose(ego.X_WB, X_VS);
  k.v_WS_W = ego.point_velocity_W(k.X_WS.translation());
  return k;
}

void compute_ideal_targets(const FieldOfView& fov, const SensorKinematics& sensor, std::span<const SceneObject> objects,
                           std::span<const BodyState> object_states, std::span<const double> bounding_radius_m,
                           IdealTargets& out) {
  out.clear();
  const double tan_half = std::tan(fov.azimuth_half_rad);
  const Vec2 p_WS_W = sensor.X_WS.translation();
  // R_SW once per cycle, R_WO once per object: no trigonometry per reflector but the azimuth.
  const double cos_s = std::cos(sensor.X_WS.yaw_rad), sin_s = std::sin(sensor.X_WS.yaw_rad);

  auto emit = [&](const BodyState& body, const Vec2& p_WT_W, double ercs, int object_index, int reflector_index,
                  ReflectorKind kind) {
    const Vec2 p_ST_W = p_WT_W - p_WS_W;
    const Vec2 p_ST_S(cos_s * p_ST_W.x() + sin_s * p_ST_W.y(), -sin_s * p_ST_W.x() + cos_s * p_ST_W.y());
    if (!in_view(fov, tan_half, p_ST_S)) return;
    IdealTarget t;
    t.p_WT_W = p_WT_W;
    t.range_m = p_ST_S.norm();
    t.azimuth_rad = std::atan2(p_ST_S.y(), p_ST_S.x());
    // Relative velocity of the reflecting point, projected on the line of sight (negative approaching).
    const Vec2 v_ST_W = body.point_velocity_W(p_WT_W) - sensor.v_WS_W;
    t.range_rate_mps = v_ST_W.dot(p_ST_W) / t.range_m;
    t.ercs = ercs;
    t.object_index = object_index;
    t.reflector_index = reflector_index;
    t.kind = kind;
    out.push_back(t);
  };

  for (std::size_t i = 0; i < objects.size(); ++i) {
    const auto& model = objects[i].model;
    const auto& body = object_states[i];
    // Whole objects out of range are skipped at once (their bounding circle).
    const double reach_m = fov.max_range_m + bounding_radius_m[i];
    const Vec2 p_WO_W = body.X_WB.translation();
    if ((p_WO_W - p_WS_W).squaredNorm() > reach_m * reach_m) continue;
    const double c = std::cos(body.X_WB.yaw_rad), s = std::sin(body.X_WB.yaw_rad);
    const auto to_world = [&](const Vec2& p_O) { return Vec2(p_WO_W.x() + c * p_O.x() - s * p_O.y(), p_WO_W.y() + s * p_O.x() + c * p_O.y()); };
    const Vec2 d = p_WS_W - p_WO_W;
    const Vec2 p_OS_O(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
    for (std::size_t k = 0; k < model.points.size(); ++k) {
      const auto& point = model.points[k];
      const double ercs = point_reflector_ercs(point, p_OS_O);
      if (ercs <= 0.0) continue;
      emit(body, to_world(point.p_OR_O), ercs, static_cast<int>(i), static_cast<int>(k), ReflectorKind::Point);
    }
    for (std::size_t k = 0; k < model.planes.size(); ++k) {
      const auto& plane = model.planes[k];
      const auto p_OT_O = plane_reflection_point_O(plane, p_OS_O);
      if (!p_OT_O) continue;
      emit(body, to_world(*p_OT_O), plane.ercs, static_cast<int>(i), static_cast<int>(k), ReflectorKind::Plane);
    }
  }
}

}  // namespace rcsim
