#pragma once
// A recording of single frames (timeline snapshots), as a labelled dataset of frames comes (the
// Astyx and View-of-Delft importers): every frame its own cycle, every object boxed in its one
// frame only, a radar that reports raw detections (aimotive_lrr, radar equation), the ego standing.
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "io/recording.hpp"

namespace rcsim::testing {

struct SnapshotFrames {
  int frames = 3;
  int objects_per_frame = 1;
  // Object detections per object and frame, and background detections per frame.
  int object_targets = 4, background_targets = 3;
  bool objects_in_view = true;  // false: every box 500 m behind the radar, never in its view
};

// Frame k at t_s = k (cycle_time_s 1 only orders them); object j of frame k is "car_k_j", 25 + 10 k
// m ahead, 3 m to the side per j; its detections on its rear face, the background's far off it.
inline Recording snapshot_frames(const SnapshotFrames& spec = {}) {
  Recording r;
  r.dir = "snapshot_frames";
  r.name = "snapshot_frames";
  r.description = "single frames, each object boxed in its frame only";
  r.cycle_time_s = 1.0;
  r.timeline = Timeline::snapshots;
  constexpr double kMountX_m = 3.6;
  r.sensors.push_back({"front", "aimotive_lrr", kMountX_m, 0.0, 0.0, ListLevel::detections});
  r.boxes.clear();
  for (int k = 0; k < spec.frames; ++k) {
    const double t_s = static_cast<double>(k);
    r.ego.push_back({t_s, 0.0, 0.0, 0.0, 0.0, 0.0});
    for (int j = 0; j < spec.objects_per_frame; ++j) {
      const double x_m = spec.objects_in_view ? 25.0 + 10.0 * k : -500.0, y_m = 3.0 * j;
      r.objects.push_back({fmt::format("car_{}_{}", k, j), "passenger_car", 4.6, 1.8});
      r.boxes.push_back({{t_s, x_m, y_m, 0.0, 0.0, 0}});
      for (int i = 0; i < spec.object_targets; ++i) {
        RecordedTarget t;
        const double rear_x_m = 25.0 + 10.0 * k - 2.3 - kMountX_m, side_m = y_m - 0.6 + 0.4 * i;
        t.t_s = t_s, t.cycle = k, t.range_m = std::hypot(rear_x_m, side_m), t.azimuth_rad = std::atan2(side_m, rear_x_m);
        t.amplitude_db = 30.0 + i;
        r.targets.push_back(t);
      }
    }
    for (int i = 0; i < spec.background_targets; ++i) {
      RecordedTarget t;
      t.t_s = t_s, t.cycle = k, t.range_m = 60.0 + 15.0 * i, t.azimuth_rad = 0.15 * (i % 2 == 0 ? 1.0 : -1.0);
      t.amplitude_db = 18.0 + i;
      r.targets.push_back(t);
    }
  }
  return r;
}

}  // namespace rcsim::testing
