// Writes a long two-sensor recording for the replay benchmark (not committed: regenerate it).
// The ego drives laps of a 500 m radius ring road at 20 m/s; six vehicles drive in the
// neighbouring lanes, each surging back and forth around the ego (its arc distance to the ego
// oscillates between about 5 m behind and 45 m ahead), so that there is always traffic in view;
// thirty cars are parked along the inner edge. The targets are the reflection-center model's
// own; objects are annotated while within 60 m of the ego, with annotation noise (3 cm, 0.5°).
//   usage: rcsim_make_long_recording OUTPUT_DIR [DURATION_S=3600] [SEED=1]   (--help: the usage)
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

#include "common/angles.hpp"
#include "tool_arguments.hpp"
#include "io/recording.hpp"
#include "model/model_library.hpp"
#include "replay/run/model_recording.hpp"
#include "scene/scene.hpp"
#include "sensor/sensor_config.hpp"

namespace {

using namespace rcsim;

constexpr double kRingRadius_m = 500.0;

// Arc position s(t) = s0 + v t + a sin(ω t + φ) along a ring of the given radius,
// counter-clockwise, sampled every second.
struct RingMotion {
  double radius_m, s0_m, speed_mps, surge_m = 0.0, surge_radps = 0.0, surge_phase_rad = 0.0;
};

Trajectory ring_trajectory(const RingMotion& m, double duration_s) {
  std::vector<TrajectorySample> samples;
  for (double t = 0.0; t <= duration_s + 1.0; t += 1.0) {
    const double arc_m = m.s0_m + m.speed_mps * t + m.surge_m * std::sin(m.surge_radps * t + m.surge_phase_rad);
    const double arc_speed_mps = m.speed_mps + m.surge_m * m.surge_radps * std::cos(m.surge_radps * t + m.surge_phase_rad);
    const double angle = arc_m / m.radius_m;
    TrajectorySample s;
    s.t_s = t;
    s.x_m = m.radius_m * std::cos(angle);
    s.y_m = m.radius_m * std::sin(angle);
    s.yaw_rad = angle + kPi / 2;  // unwrapped: grows lap after lap
    s.speed_mps = arc_speed_mps;
    s.yaw_rate_radps = arc_speed_mps / m.radius_m;
    samples.push_back(s);
  }
  return Trajectory(samples);
}

const bench_tools::ToolUsage kLongRecordingUsage{
    "rcsim_make_long_recording", "OUTPUT_DIR [DURATION_S=3600] [SEED=1]",
    "Writes a long two-sensor recording (rcsim-recording) for the replay benchmark: laps of a 500 m\n"
    "ring road with six vehicles surging around the ego and thirty parked cars; the targets are the\n"
    "reflection-center model's own. OUTPUT_DIR is replaced if it holds a recording.",
    1, 3};

}  // namespace

int main(int argc, char** argv) {
  int exit_status = 0;
  const auto arguments = bench_tools::tool_arguments(argc, argv, kLongRecordingUsage, exit_status);
  if (!arguments) return exit_status;
  const std::optional<double> duration_s =
      arguments->size() > 1 ? bench_tools::number_argument<double>((*arguments)[1]) : std::optional<double>(3600.0);
  const std::optional<std::uint64_t> seed =
      arguments->size() > 2 ? bench_tools::number_argument<std::uint64_t>((*arguments)[2]) : std::optional<std::uint64_t>(1);
  if (!duration_s || !(*duration_s > 0.0)) {
    return bench_tools::refuse_command_line(kLongRecordingUsage, "DURATION_S must be a number > 0");
  }
  if (!seed) return bench_tools::refuse_command_line(kLongRecordingUsage, "SEED must be a whole number >= 0");
  const std::string output_dir = arguments->front();
  const ModelLibrary library = ModelLibrary::builtin();

  Scene scene;
  scene.source = "long ring drive";
  scene.duration_s = *duration_s;
  scene.cycle_time_s = 0.04;
  scene.effects = {true, false, true};
  scene.ego = ring_trajectory({kRingRadius_m, 0.0, 20.0}, *duration_s);
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
    const double lane_m = i % 2 == 0 ? 3.5 : -3.5;  // outer and inner neighbouring lanes
    const double radius_m = kRingRadius_m + lane_m;
    // Same angular speed as the ego on average; the surge moves it between ~5 m behind and ~45 m ahead.
    const RingMotion motion{radius_m, radius_m / kRingRadius_m * (20.0 + 6.0 * i), 20.0 * radius_m / kRingRadius_m,
                            12.0 + 2.0 * i, 2.0 * kPi / (40.0 + 13.0 * i), 1.3 * i};
    add("car" + std::to_string(i + 1), i == 3 ? "truck_trailer" : "passenger_car", ring_trajectory(motion, *duration_s));
  }
  for (int i = 0; i < 30; ++i) {
    const double radius_m = kRingRadius_m - 7.5;
    add("parked" + std::to_string(i + 1), "passenger_car",
        ring_trajectory({radius_m, radius_m * (2 * kPi * i / 30.0 + 0.05), 0.0}, *duration_s));
  }
  const Recording rec = replay::model_recording(scene, "long_ring_drive", *seed, {0.03, deg_to_rad(0.5), 60.0});
  write_recording(output_dir, rec);
  std::cout << rec.cycle_count() << " cycles, " << rec.targets.size() << " targets, " << rec.objects.size()
            << " objects written to " << output_dir << '\n';
  return 0;
}
