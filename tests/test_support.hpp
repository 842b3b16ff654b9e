#pragma once
// Small scenes built in code for the stage tests.
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "common/angles.hpp"
#include "model/model_library.hpp"
#include "scene/scene.hpp"
#include "sim/target_list_writer.hpp"
#include "sensor/sensor_config.hpp"
#include "sensor/stationary_background.hpp"
#include "sim/simulation.hpp"

namespace rcsim::testing {

// The recordings bundled with the checkout.
inline const std::filesystem::path kBundledRecordings = std::filesystem::path(RCSIM_SOURCE_DIR) / "recordings_synthetic";
// The aiMotive sample drive's raw layout (../shared/realdata/, never in the repository): tests that
// need it skip, saying so, where it is absent.
inline const std::filesystem::path kAimotiveRaw =
    std::filesystem::path(RCSIM_SOURCE_DIR) / ".." / "shared" / "realdata" / "aimotive_highway_night" / "raw";
// The Astyx HiRes2019 frames (../shared/realdata/astyx_hires2019/raw: dataset_astyx_hires2019/ and
// dataset_astyx_demo/; CC BY-NC-SA 4.0, never in the repository): tests skip, saying so, without it.
inline const std::filesystem::path kAstyxRaw =
    std::filesystem::path(RCSIM_SOURCE_DIR) / ".." / "shared" / "realdata" / "astyx_hires2019" / "raw";

inline const ModelLibrary& library() {
  static const ModelLibrary lib = ModelLibrary::builtin();
  return lib;
}

inline TrajectorySample sample(double t_s, double x_m, double y_m, double yaw_rad, double speed_mps) {
  TrajectorySample s;
  s.t_s = t_s;
  s.x_m = x_m;
  s.y_m = y_m;
  s.yaw_rad = yaw_rad;
  s.speed_mps = speed_mps;
  return s;
}

// A scene with a standing ego at the origin and one srr24 sensor at the origin looking along +x.
inline Scene single_sensor_scene(double duration_s = 1.0) {
  Scene scene;
  scene.source = "test";
  scene.duration_s = duration_s;
  scene.ego = Trajectory({sample(0.0, 0.0, 0.0, 0.0, 0.0)});
  MountedSensor sensor;
  sensor.id = "s";
  sensor.config = builtin_sensor_config("srr24");
  sensor.X_VS = {0.0, 0.0, 0.0};
  scene.sensors.push_back(sensor);
  scene.cycle_time_s = sensor.config.cycle_time_s;
  return scene;
}

inline void add_object(Scene& scene, const std::string& id, const std::string& model,
                       const std::vector<TrajectorySample>& samples) {
  SceneObject object;
  object.id = id;
  object.model_name = model;
  object.model = library().at(model);
  object.trajectory = Trajectory(samples);
  scene.objects.push_back(object);
}

// A car 20 m ahead, one 500 m ahead (beyond the srr24's 40 m + reach), one arriving from 80 m,
// one present for the first 0.5 s only.
inline Scene four_cars_scene() {
  Scene scene = single_sensor_scene(2.0);
  add_object(scene, "near", "passenger_car", {sample(0, 20, 0, kPi, 0)});
  add_object(scene, "far", "passenger_car", {sample(0, 500, 0, kPi, 0)});
  add_object(scene, "arriving", "passenger_car",
                      {sample(0, 80, 0, kPi, 20), sample(2, 40, 0, kPi, 20)});
  add_object(scene, "gone", "passenger_car", {sample(0, 10, 1, 0, 0)});
  scene.objects.back().presence = {{0.0, 0.5}};
  return scene;
}

// One range bin [10, 20) m, two azimuth bins [-0.1, 0) and [0, 0.1) rad weighted 1 : 3, 20 targets
// per cycle, amplitudes 10 to 20 dB evenly (deciles 10, 11, ..., 20).
inline StationaryBackground hand_background() {
  StationaryBackground b;
  b.targets_per_cycle = 20.0;
  b.range_edges_m = {10.0, 20.0};
  b.azimuth_edges_rad = {-0.1, 0.0, 0.1};
  b.weights = {0.25, 0.75};
  auto& q = b.amplitude_deciles_db.emplace_back();
  for (int k = 0; k < kAmplitudeQuantiles; ++k) q[static_cast<std::size_t>(k)] = 10.0 + k;
  return b;
}

// What `rcsim simulate` writes for the scene: every cycle and sensor, one writer.
inline std::string simulate_rows(const Scene& scene, const SimulationOptions& options,
                                 TargetListFormat format = TargetListFormat::Csv) {
  std::ostringstream out;
  Simulation simulation(scene, options);
  TargetListWriter writer(out, format, options.level);
  writer.write_header();
  for (int k = 0; k < simulation.cycle_count(); ++k) {
    simulation.run_cycle(k);
    for (std::size_t s = 0; s < simulation.sensor_count(); ++s) {
      writer.write_sensor_cycle(scene, k, scene.cycle_time_at(k), scene.sensors[s].id, simulation.sensor_state(s));
    }
  }
  return out.str();
}

}  // namespace rcsim::testing
