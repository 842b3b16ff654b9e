#include "sim/ideal_targets.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "common/angles.hpp"
#include "sim/culling.hpp"
#include "sim/visibility.hpp"

namespace rcsim {
namespace {

// Range and view-field check by dot products (no trigonometry for what is rejected), in the plane.
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

namespace {

// The sensor frame of one cycle: R_SW once per cycle, R_WO once per object, no trigonometry per
// reflector; and the view check. A radar that measures elevation sees in 3D: the line of sight
// from its height to the reflector's, the pitch turning it about the sensor's y axis.
struct SensorFrame {
  SensorFrame(const FieldOfView& fov_in, const SensorKinematics& sensor)
      : fov(fov_in),
        tan_half(std::tan(fov_in.azimuth_half_rad)),
        p_WS_W(sensor.X_WS.translation()),
        cos_s(std::cos(sensor.X_WS.yaw_rad)),
        sin_s(std::sin(sensor.X_WS.yaw_rad)),
        three_d(fov_in.measures_elevation()),
        z_WS_m(sensor.z_WS_m),
        cos_p(std::cos(sensor.pitch_rad)),
        sin_p(std::sin(sensor.pitch_rad)),
        tan_elevation_half(std::tan(fov_in.elevation_half_rad)),
        t_s(sensor.t_s) {}
  // The target in the sensor's level frame (yawed, not pitched): x ahead, y left.
  Vec2 to_sensor(const Vec2& p_WT_W) const {
    const Vec2 p_ST_W = p_WT_W - p_WS_W;
    return Vec2(cos_s * p_ST_W.x() + sin_s * p_ST_W.y(), -sin_s * p_ST_W.x() + cos_s * p_ST_W.y());
  }
  // The target in the pitched sensor frame S from its level-frame x, y and its height over the
  // sensor's dz_m: p_ST_S = R_y(pitch)^T (x, y, dz).
  Eigen::Vector3d pitched(const Vec2& p_ST_L, double dz_m) const {
    return {cos_p * p_ST_L.x() - sin_p * dz_m, p_ST_L.y(), sin_p * p_ST_L.x() + cos_p * dz_m};
  }
  bool in_view(const Vec2& p_WT_W, double z_WT_m) const {
    const Vec2 p_ST_L = to_sensor(p_WT_W);
    if (!three_d) return rcsim::in_view(fov, tan_half, p_ST_L);
    const double dz_m = z_WT_m - z_WS_m;
    const double range2 = p_ST_L.squaredNorm() + dz_m * dz_m;
    if (range2 > fov.max_range_m * fov.max_range_m || range2 < fov.min_range_m * fov.min_range_m) return false;
    const Eigen::Vector3d p_ST_S = pitched(p_ST_L, dz_m);
    if (!(p_ST_S.x() > 0.0 && std::abs(p_ST_S.y()) <= tan_half * p_ST_S.x())) return false;
    return std::abs(p_ST_S.z()) <= tan_elevation_half * std::hypot(p_ST_S.x(), p_ST_S.y());
  }
  const FieldOfView& fov;
  double tan_half;
  Vec2 p_WS_W;
  double cos_s, sin_s;
  bool three_d;
  double z_WS_m, cos_p, sin_p, tan_elevation_half;
  double t_s;
};

// The heights of a body's diffuse pieces: spread over its height by the golden-ratio sequence
// (piece n at (0.1 + 0.8 frac(0.5 + n phi)) of the height: evenly, the same each cycle), so that
// a radar that measures elevation sees the whole side, bumper to roof edge; 0.5 m where the
// model gives no height.
double diffuse_piece_z_m(const ObjectModel& model, std::size_t piece) {
  if (!(model.height_m > 0.0)) return 0.5;
  constexpr double kGoldenFraction = 0.6180339887498949;
  const double f = 0.5 + static_cast<double>(piece) * kGoldenFraction;
  return model.height_m * (0.1 + 0.8 * (f - std::floor(f)));
}

// The ERCS of points in the fall-off of their visibility function (paper Fig. 6) takes two
// library calls each; those are queued and evaluated a batch at a time, so that the calls of
// different points overlap instead of waiting on each other.
class FalloffQueue {
 public:
  explicit FalloffQueue(IdealTargets& out) : out_(out) {}
  void add(std::size_t target, const PointReflector* point, const VisibilityFunction::Zone& zone) {
    pending_[count_++] = {target, point, zone};
    if (count_ == pending_.size()) flush();
  }
  void flush() {
    for (std::size_t n = 0; n < count_; ++n) {
      const auto& p = pending_[n];
      out_[p.target].ercs = p.point->ercs_max * p.point->visibility.falloff_value(p.zone.cos_delta, p.zone.sin_delta);
    }
    count_ = 0;
  }

 private:
  struct Pending {
    std::size_t target;
    const PointReflector* point;
    VisibilityFunction::Zone zone;
  };
  IdealTargets& out_;
  std::array<Pending, 32> pending_;
  std::size_t count_ = 0;
};

// Object i's visible reflection points that are in view, into `out` (their ERCS: paper II-C).
void add_visible_targets(const SensorFrame& frame, const ObjectModel& model, const BodyState& body, std::size_t i,
                         const IdealTargetFilter& filter, IdealTargets& out, FalloffQueue& falloff) {
  const Vec2 p_WO_W = body.X_WB.translation();
  const double c = std::cos(body.X_WB.yaw_rad), s = std::sin(body.X_WB.yaw_rad);
  const Vec2 d = frame.p_WS_W - p_WO_W;
  const Vec2 p_OS_O(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
  const auto to_world = [&](const Vec2& p_OT_O) {
    return Vec2(p_WO_W.x() + c * p_OT_O.x() - s * p_OT_O.y(), p_WO_W.y() + s * p_OT_O.x() + c * p_OT_O.y());
  };
  // A limb's or a wheel's swing at this cycle (micro-Doppler): its speed along the heading.
  const double speed_mps = model.has_swinging_points ? body.heading_speed_mps() : 0.0;
  const auto add = [&](const Vec2& p_WT_W, double z_WT_m, double ercs, std::size_t index,
                       ReflectorKind kind) __attribute__((always_inline)) -> bool {
    if (!frame.in_view(p_WT_W, z_WT_m)) return false;
    IdealTarget& t = out.emplace_back();  // built in place, not copied from the stack
    t.p_WT_W = p_WT_W;
    t.z_WT_m = z_WT_m;
    t.ercs = ercs;
    t.object_index = static_cast<int>(i);
    t.reflector_index = static_cast<int>(index);
    t.kind = kind;
    return true;
  };
  // A planar radar reads no heights; a model without limbs or wheels has no swing to look up.
  const bool three_d = frame.three_d, swings = model.has_swinging_points;
  for_each_visible_reflector(model, p_OS_O, filter.planes, [&](const VisibleReflector& r) __attribute__((always_inline)) {
    const double z_m = !three_d ? 0.0 : r.kind == ReflectorKind::Point ? r.point->z_m : model.planes[r.index].z_m;
    if (!add(to_world(r.p_OT_O), z_m, r.ercs, r.index, r.kind) || r.kind != ReflectorKind::Point) return;
    if (swings && r.point->swing.active()) out.back().swing_mps = r.point->swing.speed_offset_mps(speed_mps, frame.t_s);
    if (r.zone.kind == VisibilityFunction::Zone::falloff) falloff.add(out.size() - 1, r.point, r.zone);
  });
  if (!filter.planes || !(filter.diffuse_relative_ercs_per_sqrt_m > 0.0)) return;
  // docs/extended-objects.md: a piece of length l has ERCS relative x plane ERCS x sqrt(l / 1 m);
  // a side of the box counts as a face of ERCS 1 m^2.
  std::size_t piece = 0;
  if (filter.diffuse_on_box && has_box_sides(model)) {
    if (!(model.diffuse_ercs_factor > 0.0)) return;  // no body in its box (a gantry's)
    const auto sides = box_sides(model.length_m, model.width_m, filter.box_side_inset_m);
    for (std::size_t k = 0; k < sides.size(); ++k) {
      for_each_face_piece(sides[k].a_O, sides[k].b_O, sides[k].outward_O, p_OS_O, filter.diffuse_piece,
                          [&](const Vec2& p_OT_O, double length_m) {
                            add(to_world(p_OT_O), frame.three_d ? diffuse_piece_z_m(model, piece++) : 0.0,
                                filter.diffuse_relative_ercs_per_sqrt_m * model.diffuse_ercs_factor * std::sqrt(length_m), k,
                                ReflectorKind::BoxDiffuse);
                          });
    }
    return;
  }
  for (std::size_t k = 0; k < model.planes.size(); ++k) {
    const PlaneReflector& plane = model.planes[k];
    for_each_diffuse_piece(plane, p_OS_O, filter.diffuse_piece, [&](const Vec2& p_OT_O, double length_m) {
      add(to_world(p_OT_O), plane.z_m, filter.diffuse_relative_ercs_per_sqrt_m * plane.ercs * std::sqrt(length_m), k,
          ReflectorKind::PlaneDiffuse);
    });
  }
}

// The velocity of target t's reflecting point in the world: its body's, plus a limb's or a
// wheel's swing along the heading.
Vec2 reflector_velocity_W(const IdealTarget& t, std::span<const BodyState> object_states) {
  const BodyState& body = object_states[static_cast<std::size_t>(t.object_index)];
  const Vec2 v_WT_W = body.point_velocity_W(t.p_WT_W);
  if (t.swing_mps == 0.0) return v_WT_W;
  return v_WT_W + t.swing_mps * heading_vector(body.X_WB.yaw_rad);
}

// Range, azimuth and range rate, target after target without branching on the data, so that
// the square roots, divisions and asin of different targets overlap.
void set_polar_coordinates(const SensorFrame& frame, const SensorKinematics& sensor,
                           std::span<const BodyState> object_states, IdealTargets& out) {
  for (auto& t : out) {
    const Vec2 p_ST_S = frame.to_sensor(t.p_WT_W);
    t.range_m = p_ST_S.norm();
    const double inv_range = 1.0 / t.range_m;
    // The line of sight gives sin and cos of the azimuth; the antenna pattern, eq. (6), uses them.
    t.sin_azimuth = p_ST_S.y() * inv_range;
    t.cos_azimuth = p_ST_S.x() * inv_range;
    t.azimuth_rad = angle_of_unit_vector_rad(t.cos_azimuth, t.sin_azimuth);
    // Relative velocity of the reflecting point, projected on the line of sight (negative approaching).
    const Vec2 v_ST_W = reflector_velocity_W(t, object_states) - sensor.v_WS_W;
    t.range_rate_mps = v_ST_W.dot(t.p_WT_W - frame.p_WS_W) * inv_range;
  }
}

// The same in 3D (a radar that measures elevation): the slant range from the sensor's height to
// the reflector's, azimuth and elevation in the pitched sensor frame, the range rate of the
// (level) relative velocity along the slant line of sight.
void set_polar_coordinates_3d(const SensorFrame& frame, const SensorKinematics& sensor,
                              std::span<const BodyState> object_states, IdealTargets& out) {
  for (auto& t : out) {
    const Vec2 p_ST_L = frame.to_sensor(t.p_WT_W);
    const double dz_m = t.z_WT_m - frame.z_WS_m;
    const Eigen::Vector3d p_ST_S = frame.pitched(p_ST_L, dz_m);
    t.range_m = p_ST_S.norm();
    const double horizontal_m = std::hypot(p_ST_S.x(), p_ST_S.y());
    t.sin_azimuth = p_ST_S.y() / horizontal_m;
    t.cos_azimuth = p_ST_S.x() / horizontal_m;
    t.azimuth_rad = angle_of_unit_vector_rad(t.cos_azimuth, t.sin_azimuth);
    t.elevation_rad = std::atan2(p_ST_S.z(), horizontal_m);
    const Vec2 v_ST_W = reflector_velocity_W(t, object_states) - sensor.v_WS_W;
    t.range_rate_mps = v_ST_W.dot(t.p_WT_W - frame.p_WS_W) / t.range_m;
  }
}

}  // namespace

void compute_ideal_targets(const FieldOfView& fov, const SensorKinematics& sensor, std::span<const SceneObject> objects,
                           std::span<const BodyState> object_states, std::span<const std::uint32_t> visited,
                           IdealTargets& out, const IdealTargetFilter& filter) {
  // visited objects => broad phase => visible reflection points in view => ERCS => polar
  out.clear();
  const CullingBounds* culling = filter.culling;
  if (culling != nullptr && culling->radius_m.size() != objects.size()) culling = nullptr;  // built for another scene
  std::vector<unsigned char>* may_occlude = culling != nullptr ? filter.may_occlude : nullptr;
  if (may_occlude != nullptr) may_occlude->assign(objects.size(), 0);  // keeps its capacity: no allocation
  const SensorFrame frame(fov, sensor);
  FalloffQueue falloff(out);
  for (const std::size_t i : visited) {
    const Vec2 p_WO_W = object_states[i].X_WB.translation();
    if (culling != nullptr &&
        !keep_object(*culling, fov, i, frame.to_sensor(p_WO_W), (p_WO_W - frame.p_WS_W).squaredNorm(),
                     may_occlude != nullptr ? &(*may_occlude)[i] : nullptr)) {
      continue;
    }
    add_visible_targets(frame, objects[i].model, object_states[i], i, filter, out, falloff);
  }
  falloff.flush();
  // A point whose ERCS came out 0 (the raised cosine rounds to 0 at the far edge of its fall-off)
  // is invisible after all.
  std::erase_if(out, [](const IdealTarget& t) { return t.kind == ReflectorKind::Point && t.ercs <= 0.0; });
  if (frame.three_d) {
    set_polar_coordinates_3d(frame, sensor, object_states, out);
  } else {
    set_polar_coordinates(frame, sensor, object_states, out);
  }
}

}  // namespace rcsim
