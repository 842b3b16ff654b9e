#pragma once
// Scenes and model-made recordings for the harness tests.
#include <filesystem>

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

}  // namespace rcsim::testing
