#pragma once
// The annotated objects as one sensor sees them in one cycle: each box in the sensor frame S, its
// nearest contour point (range, azimuth, radial speed of that point) and whether it lies in the
// sensor's field of view. Shared by target-to-object association, merge-artefact detection and
// confirmation latency.
#include <vector>

#include "common/pose2.hpp"

namespace rcsim::metrics {

struct BoxInSensor {
  int object = -1;          // index of the object in the recording
  Pose2 X_SO;               // box centre and heading in the sensor frame
  double half_length_m = 0.0, half_width_m = 0.0;
  Vec2 p_SN_S = Vec2::Zero();  // nearest contour point (N) from the sensor, sensor frame
  double range_m = 0.0;     // |p_SN_S|
  double azimuth_rad = 0.0; // of N
  double range_rate_mps = 0.0;  // radial speed of N relative to the sensor, negative approaching
};

// Distance from a point in the sensor frame to the box (0 inside).
double distance_to_box_m(const BoxInSensor& box, const Vec2& p_ST_S);

// Builds the view of one box. X_WS: sensor pose in the world; sensor_W: the ego body state (for
// the sensor's own velocity); object_W: the object's body state at its box centre.
BoxInSensor box_in_sensor(int object, const Pose2& X_WS, const BodyState& ego_W, const BodyState& object_W,
                          double length_m, double width_m);

// The nearest box within gate_m of the point, or -1 (index into boxes).
int nearest_box(const std::vector<BoxInSensor>& boxes, const Vec2& p_ST_S, double gate_m);

}  // namespace rcsim::metrics
