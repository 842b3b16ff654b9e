#include "sim/ideal_targets.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "common/angles.hpp"
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
  const Pose2& X_WV = ego.X_WB;  // the ego's body frame is the vehicle frame V
  k.X_WS = compose(X_WV, X_VS);
  k.v_WS_W = ego.point_velocity_W(k.X_WS.translation());
  return k;
}

void compute_ideal_targets(const FieldOfView& fov, const SensorKinematics& sensor, std::span<const SceneObject> objects,
                           std::span<const BodyState> object_states, std::span<const std::uint32_t> visited,
                           IdealTargets& out, const IdealTargetFilter& filter) {
  out.clear();
  const CullingBounds* culling = filter.culling;
  if (culling != nullptr && culling->radius_m.size() != objects.size()) culling = nullptr;  // built for another scene
  std::vector<unsigned char>* may_occlude = culling != nullptr ? filter.may_occlude : nullptr;
  if (may_occlude != nullptr) may_occlude->assign(objects.size(), 0);  // keeps its capacity: no allocation
  const double tan_half = std::tan(fov.azimuth_half_rad);
  const Vec2 p_WS_W = sensor.X_WS.translation();
  // R_SW once per cycle, R_WO once per object: no trigonometry per reflector.
  const double cos_s = std::cos(sensor.X_WS.yaw_rad), sin_s = std::sin(sensor.X_WS.yaw_rad);
  const auto to_sensor = [&](const Vec2& p_WT_W) {
    const Vec2 p_ST_W = p_WT_W - p_WS_W;
    return Vec2(cos_s * p_ST_W.x() + sin_s * p_ST_W.y(), -sin_s * p_ST_W.x() + cos_s * p_ST_W.y());
  };
  // Appends a reflection point that is in view; returns false if it is not.
  const auto emit = [&](const Vec2& p_WT_W, double ercs, std::size_t object_index, std::size_t reflector_index,
                        ReflectorKind kind) {
    if (!in_view(fov, tan_half, to_sensor(p_WT_W))) return false;
    IdealTarget& t = out.emplace_back();  // built in place, not copied from the stack
    t.p_WT_W = p_WT_W;
    t.ercs = ercs;
    t.object_index = static_cast<int>(object_index);
    t.reflector_index = static_cast<int>(reflector_index);
    t.kind = kind;
    return true;
  };
  // The ERCS of points in the fall-off of their visibility function (paper Fig. 6) takes two
  // library calls each; those are queued and evaluated a batch at a time, so that the calls of
  // different points overlap instead of waiting on each other.
  struct PendingFalloff {
    std::size_t target;
    const PointReflector* point;
    VisibilityFunction::Zone zone;
  };
  std::array<PendingFalloff, 32> pending;
  std::size_t pending_count = 0;
  const auto evaluate_pending = [&] {
    for (std::size_t n = 0; n < pending_count; ++n) {
      const auto& p = pending[n];
      out[p.target].ercs = p.point->ercs_max * p.point->visibility.falloff_value(p.zone.cos_delta, p.zone.sin_delta);
    }
    pending_count = 0;
  };

  // Pass 1: the reflection points that are visible and in view, in object and reflector order.
  for (const std::size_t i : visited) {
    const auto& model = objects[i].model;
    const auto& body = object_states[i];
    const Vec2 p_WO_W = body.X_WB.translation();
    const double distance2_m2 = (p_WO_W - p_WS_W).squaredNorm();
    if (culling != nullptr) {
      // Broad phase (culling.hpp): the whole reflection circle outside the view wedge by more than
      // a margin, or too far for any echo of the object to change a cell that passes the threshold.
      const double margin_m = culling->radius_m[i] + 1e-3 + 1e-9 * std::sqrt(distance2_m2);
      if (culling->by_view) {
        const Vec2 p_SO_S = to_sensor(p_WO_W);
        // Signed distances beyond the wedge's two edges y = +-tan(half) x.
        if (p_SO_S.y() * culling->cos_half - p_SO_S.x() * culling->sin_half > margin_m ||
            -p_SO_S.y() * culling->cos_half - p_SO_S.x() * culling->sin_half > margin_m) {
          continue;
        }
      }
      // Before range culling: a far or faint object still hides what is behind it.
      const double occlude_reach_m = fov.max_range_m + margin_m;
      if (may_occlude != nullptr && distance2_m2 <= occlude_reach_m * occlude_reach_m) (*may_occlude)[i] = 1;
      // Beyond the view range by more than the reflection circle: no reflection point in view.
      const double reach_m = fov.max_range_m + culling->radius_m[i];
      if (distance2_m2 > reach_m * reach_m) continue;
      const double cull_m = culling->by_range ? culling->cull_distance_m[i] : 0.0;
      if (culling->by_range && distance2_m2 > cull_m * cull_m) continue;
    }
    const double c = std::cos(body.X_WB.yaw_rad), s = std::sin(body.X_WB.yaw_rad);
    const auto to_world = [&](const Vec2& p_O) {
      return Vec2(p_WO_W.x() + c * p_O.x() - s * p_O.y(), p_WO_W.y() + s * p_O.x() + c * p_O.y());
    };
    const Vec2 d = p_WS_W - p_WO_W;
    const Vec2 p_OS_O(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
    for (std::size_t k = 0; k < model.points.size(); ++k) {
      const auto& point = model.points[k];
      const Vec2 p_RS_O = p_OS_O - point.p_OR_O;  // reflector -> sensor: the impinging direction
      const auto zone = point.visibility.zone(p_RS_O.x(), p_RS_O.y());
      if (zone.kind == VisibilityFunction::Zone::zero) continue;
      // paper II-C: ERCS = ercs_max * visibility (1 here, or pending in the fall-off)
      if (!emit(to_world(point.p_OR_O), point.ercs_max, i, k, ReflectorKind::Point)) continue;
      if (zone.kind == VisibilityFunction::Zone::falloff) {
        pending[pending_count++] = {out.size() - 1, &point, zone};
        if (pending_count == pending.size()) evaluate_pending();
      }
    }
    for (std::size_t k = 0; filter.planes && k < model.planes.size(); ++k) {
      const auto& plane = model.planes[k];
      const auto p_OT_O = plane_reflection_point_O(plane, p_OS_O);
      if (!p_OT_O) continue;
      emit(to_world(*p_OT_O), plane.ercs, i, k, ReflectorKind::Plane);
    }
  }
  evaluate_pending();
  // A point whose ERCS came out 0 (the raised cosine rounds to 0 at the far edge of its fall-off)
  // is invisible after all.
  std::erase_if(out, [](const IdealTarget& t) { return t.kind == ReflectorKind::Point && t.ercs <= 0.0; });

  // Pass 2: range, azimuth and range rate, target after target without branching on the data,
  // so that the square roots, divisions and asin of different targets overlap.
  for (auto& t : out) {
    const Vec2 p_ST_S = to_sensor(t.p_WT_W);
    t.range_m = p_ST_S.norm();
    const double inv_range = 1.0 / t.range_m;
    // The line of sight gives sin and cos of the azimuth; the antenna pattern, eq. (6), uses them.
    t.sin_azimuth = p_ST_S.y() * inv_range;
    t.cos_azimuth = p_ST_S.x() * inv_range;
    t.azimuth_rad = angle_of_unit_vector_rad(t.cos_azimuth, t.sin_azimuth);
    // Relative velocity of the reflecting point, projected on the line of sight (negative approaching).
    const Vec2 v_ST_W = object_states[static_cast<std::size_t>(t.object_index)].point_velocity_W(t.p_WT_W) - sensor.v_WS_W;
    t.range_rate_mps = v_ST_W.dot(t.p_WT_W - p_WS_W) * inv_range;
  }
}

}  // namespace rcsim
