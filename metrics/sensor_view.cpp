#include "metrics/sensor_view.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rcsim::metrics {

namespace {

// Point relative to the box centre in the box frame.
Vec2 in_box_frame(const BoxInSensor& box, const Vec2& p_ST_S) { return inverse_transform_point(box.X_SO, p_ST_S); }

}  // namespace

double distance_to_box_m(const BoxInSensor& box, const Vec2& p_ST_S) {
  const Vec2 p_O = in_box_frame(box, p_ST_S);
  const double dx = std::max(std::abs(p_O.x()) - box.half_length_m, 0.0);
  const double dy = std::max(std::abs(p_O.y()) - box.half_width_m, 0.0);
  return std::hypot(dx, dy);
}

BoxInSensor box_in_sensor(int object, const Pose2& X_WS, const BodyState& ego_W, const BodyState& object_W,
                          double length_m, double width_m) {
  BoxInSensor box;
  box.object = object;
  box.half_length_m = 0.5 * length_m;
  box.half_width_m = 0.5 * width_m;
  const Vec2 p_SO_S = inverse_transform_point(X_WS, object_W.X_WB.translation());
  box.X_SO = {p_SO_S.x(), p_SO_S.y(), object_W.X_WB.yaw_rad - X_WS.yaw_rad};
  // Nearest contour point: the sensor's position in the box frame clamped to the box.
  const Vec2 p_OS_O = inverse_transform_point(box.X_SO, Vec2::Zero());
  const Vec2 p_ON_O(std::clamp(p_OS_O.x(), -box.half_length_m, box.half_length_m),
                    std::clamp(p_OS_O.y(), -box.half_width_m, box.half_width_m));
  box.p_SN_S = transform_point(box.X_SO, p_ON_O);
  box.range_m = box.p_SN_S.norm();
  box.azimuth_rad = std::atan2(box.p_SN_S.y(), box.p_SN_S.x());
  if (box.range_m > 0.0) {
    // Radial speed of the contour point relative to the sensor, both as points of their bodies.
    const Vec2 p_WN = transform_point(X_WS, box.p_SN_S);
    const Vec2 v_rel_W = object_W.point_velocity_W(p_WN) - ego_W.point_velocity_W(X_WS.translation());
    const Vec2 los_W = (p_WN - X_WS.translation()) / box.range_m;
    box.range_rate_mps = v_rel_W.dot(los_W);
  }
  return box;
}

int nearest_box(const std::vector<BoxInSensor>& boxes, const Vec2& p_ST_S, double gate_m) {
  int best = -1;
  double best_m = gate_m;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    // A bound first, without the rotation into the box frame: the box lies within
    // half_length + half_width of its centre, so a point farther than best_m + that (and a margin
    // far above rounding) from the centre lies farther than best_m from the box, and cannot win.
    const BoxInSensor& box = boxes[i];
    const double reach_m = best_m + box.half_length_m + box.half_width_m + 1e-6 * (1.0 + best_m);
    if ((p_ST_S - box.X_SO.translation()).squaredNorm() > reach_m * reach_m) continue;
    const double d = distance_to_box_m(box, p_ST_S);
    if (d <= best_m) {
      best_m = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace rcsim::metrics
