#pragma once
// Recordings made by the reflection-center model itself (for harness tests that need a known
// answer): the scene is simulated at the tracks level and written as a recording whose boxes are
// the true poses, optionally with annotation noise.
#include <filesystem>

#include "common/rng.hpp"
#include "io/recording.hpp"
#include "sim/simulation.hpp"
#include "test_support.hpp"

namespace rcsim::testing {

inline Recording model_recording(const Scene& scene, std::uint64_t seed, double position_noise_m = 0.0,
                                 double yaw_noise_rad = 0.0) {
  Recording rec;
  rec.name = "model_made";
  rec.description = "made by the reflection-center model for tests";
  rec.cycle_time_s = scene.cycle_time_s;
  for (const auto& s : scene.sensors) rec.sensors.push_back({s.id, "srr24", s.X_VS.x_m, s.X_VS.y_m, s.X_VS.yaw_rad});
  for (const auto& o : scene.objects) rec.objects.push_back({o.id, o.model_name, o.model.length_m, o.model.width_m});
  rec.boxes.resize(scene.objects.size());
  SimulationOptions options;
  options.seed = seed;
  Simulation simulation(scene, options);
  Rng annotation(seed + 1000, 0);
  for (int k = 0; k < scene.cycle_count(); ++k) {
    const double t_s = scene.cycle_time_at(k);
    simulation.run_cycle(k);
    const BodyState& ego = simulation.snapshot().ego;
    rec.ego.push_back({t_s, ego.X_WB.x_m, ego.X_WB.y_m, ego.X_WB.yaw_rad, ego.v_WB_W.norm(), ego.yaw_rate_radps});
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
      const BodyState& s = simulation.snapshot().objects[o];
      AnnotatedBox box;
      box.t_s = t_s;
      box.x_m = s.X_WB.x_m + position_noise_m * annotation.normal();
      box.y_m = s.X_WB.y_m + position_noise_m * annotation.normal();
      box.yaw_rad = s.X_WB.yaw_rad + yaw_noise_rad * annotation.normal();
      box.speed_mps = s.v_WB_W.norm();
      rec.boxes[o].push_back(box);
    }
    for (std::size_t i = 0; i < simulation.sensor_count(); ++i) {
      for (const auto& t : simulation.sensor_state(i).reported) {
        rec.targets.push_back({t_s, k, static_cast<int>(i), t.id, t.range_m, t.azimuth_rad, t.range_rate_mps,
                               t.amplitude_db});
      }
    }
  }
  return rec;
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
