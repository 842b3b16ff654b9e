// Writes a long two-sensor recording for the replay benchmark (not committed: regenerate it).
// The ego drives laps of a 500 m radius ring road at 20 m/s; six cars drive in the neighbouring
// lanes at other speeds, so that they keep overtaking and being overtaken; thirty cars are parked
// along the outer edge. The targets are the reflection-center model's own, the boxes carry
// annotation noise (3 cm, 0.5°).
//   usage: rcsim_make_long_recording OUTPUT_DIR [DURATION_S=3600] [SEED=1]
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

#include "common/angles.hpp"
#include "io/recording.hpp"
#include "model/model_library.hpp"
#include "replay/model_recording.hpp"
#include "scene/scene.hpp"
#include "sensor/sensor_config.hpp"

namespace {

using namespace rcsim;

constexpr double kRingRadius_m = 500.0;

// Samples of a body driving counter-clockwise around the ring at a constant speed.
Trajectory ring_trajectory(double radius_m, double speed_mps, double phase_rad, double duration_s) {
  std::vector<TrajectorySample> samples;
  for (double t = 0.0; t <= duration_s + 1.0; t += 1.0) {
    const double angle = phase_rad + speed_mps * t / radius_m;
    TrajectorySample s;
    s.t_s = t;
    s.x_m = radius_m * std::cos(angle);
    s.y_m = radius_m * std::sin(angle);
    s.yaw_rad = angle + kPi / 2;  // unwrapped: grows lap after lap
    s.speed_mps = speed_mps;
    s.yaw_rate_radps = speed_mps / radius_m;
    samples.push_back(s);
  }
  return Trajectory(samples);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: rcsim_make_long_recording OUTPUT_DIR [DURATION_S=3600] [SEED=1]\n";
    return 2;
  }
  const double duration_s = argc > 2 ? std::atof(argv[2]) : 3600.0;
  const std::uint64_t seed = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 1;
  const ModelLibrary library = ModelLibrary::builtin();

  Scene scene;
  scene.source = "long ring drive";
  scene.duration_s = duration_s;
  scene.cycle_time_s = 0.04;
  scene.effects = {true, false, true};
  scene.ego = ring_trajectory(kRingRadius_m, 20.0, 0.0, duration_s);
  for (const auto& [id, y_m, yaw_rad] : {std::tuple{"front_left", 0.7, 0.5}, std::tuple{"front_right", -0.7, -0.5}}) {
    MountedSensor sensor;
    sensor.id = id;
    sensor.config = builtin_sensor_config("srr24");
    sensor.X_VS = {3.7, y_m, yaw_rad};
    scene.sensors.push_back(sensor);
  }
  const auto add = [&](const std::string& id, const std::string& model, Trajectory trajectory) {
    SceneObject object;
    object.id = id;
    object.model_name = model;
    object.model = library.at(model);
    object.trajectory = std::move(trajectory);
    scene.objects.push_back(std::move(object));
  };
  for (int i = 0; i < 6; ++i) {
    const double lane_m = i % 2 == 0 ? 3.5 : -3.5;  // inner and outer neighbouring lanes
    add("car" + std::to_string(i + 1), i == 3 ? "truck_trailer" : "passenger_car",
        ring_trajectory(kRingRadius_m + lane_m, 20.0 + (i - 2.5) * 0.8, 0.01 + 0.02 * i, duration_s));
  }
  for (int i = 0; i < 30; ++i) {
    add("parked" + std::to_string(i + 1), "passenger_car",
        ring_trajectory(kRingRadius_m - 7.5, 0.0, 2 * kPi * i / 30.0 + 0.05, duration_s));
  }
  const Recording rec = replay::model_recording(scene, "long_ring_drive", seed, {0.03, deg_to_rad(0.5)});
  write_recording(argv[1], rec);
  std::cout << rec.cycle_count() << " cycles, " << rec.targets.size() << " targets, " << rec.objects.size()
            << " objects written to " << argv[1] << '\n';
  return 0;
}
