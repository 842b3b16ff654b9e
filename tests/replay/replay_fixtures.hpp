#pragma once
// Scenes and model-made recordings for the harness tests.
#include <filesystem>
#include <vector>

#include "app/cli/run_rcsim.hpp"
#include "replay/run/model_recording.hpp"
#include "test_support.hpp"

namespace rcsim::testing {

// How often needle occurs in text (non-overlapping).
inline std::size_t count_occurrences(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto pos = text.find(needle); pos != std::string::npos; pos = text.find(needle, pos + needle.size())) ++n;
  return n;
}

inline Recording model_recording(const Scene& scene, std::uint64_t seed, double position_noise_m = 0.0,
                                 double yaw_noise_rad = 0.0) {
  return replay::model_recording(scene, "model_made", seed, {position_noise_m, yaw_noise_rad});
}

// A recording written to dir/name and read back, as replay reads files (rounded as written).
inline Recording write_and_read(const Recording& rec, const std::filesystem::path& dir) {
  write_recording(dir, rec);
  return read_recording(dir);
}

// Two cars side by side driving towards a standing ego with two sensors, as in paper Fig. 10.
inline Scene two_cars_scene(double duration_s = 3.0) {
  Scene scene = single_sensor_scene(duration_s);
  scene.sensors.front().id = "front_left";
  scene.sensors.front().X_VS = {3.7, 0.7, 0.5};
  MountedSensor right = scene.sensors.front();
  right.id = "front_right";
  right.X_VS = {3.7, -0.7, -0.5};
  scene.sensors.push_back(right);
  add_object(scene, "left", "passenger_car", {sample(0.0, 25.0, 1.6, kPi, 4.0)});
  add_object(scene, "right", "passenger_car", {sample(0.0, 25.0, -1.6, kPi, 4.0)});
  return scene;
}

// The recording with its sensors on their own clocks (recording v4): sensor s keeps the cycles k
// with k % stride[s] == phase[s] (its cycle time stride[s] times the shared one), its targets
// renumbered into the cycles kept; the ego log keeps every ego_stride-th row and the last.
inline Recording on_own_clocks(const Recording& shared, const std::vector<int>& stride, const std::vector<int>& phase,
                               int ego_stride) {
  Recording own = shared;
  own.clock = Clock::per_sensor;
  own.cycles.clear();
  own.targets.clear();
  own.ego.clear();
  for (std::size_t s = 0; s < own.sensors.size(); ++s) own.sensors[s].cycle_time_s = shared.cycle_time_s * stride[s];
  std::size_t cursor = 0;
  for (int k = 0; k < shared.cycle_count(); ++k) {
    const EgoSample& e = shared.ego[static_cast<std::size_t>(k)];
    if (k % ego_stride == 0 || k + 1 == shared.cycle_count()) own.ego.push_back(e);
    const std::size_t first = cursor;
    while (cursor < shared.targets.size() && shared.targets[cursor].cycle == k) ++cursor;
    for (std::size_t s = 0; s < own.sensors.size(); ++s) {
      if (k % stride[s] != phase[s]) continue;
      const int cycle = static_cast<int>(own.cycles.size());
      own.cycles.push_back({e.t_s, static_cast<int>(s)});
      for (std::size_t i = first; i < cursor; ++i) {
        if (shared.targets[i].sensor != static_cast<int>(s)) continue;
        own.targets.push_back(shared.targets[i]);
        own.targets.back().cycle = cycle;
      }
    }
  }
  return own;
}

}  // namespace rcsim::testing
