#include "replay/run/model_recording.hpp"

#include "common/rng.hpp"
#include "sim/simulation.hpp"

namespace rcsim::replay {

Recording model_recording(const Scene& scene, const std::string& name, std::uint64_t seed,
                          const AnnotationNoise& noise) {
  Recording rec;
  rec.name = name;
  rec.description = "made by the reflection-center model (rcsim), not a measurement";
  rec.cycle_time_s = scene.cycle_time_s;
  rec.source = {{"generator", "rcsim reflection-center model"},
                {"seed", seed},
                {"effects",
                 {{"clutter", scene.effects.clutter},
                  {"multibounce", scene.effects.multibounce},
                  {"occlusion", scene.effects.occlusion}}}};
  for (const auto& s : scene.sensors) {
    rec.sensors.push_back({s.id, s.config.name, s.X_VS.x_m, s.X_VS.y_m, s.X_VS.yaw_rad});
  }
  rec.boxes.resize(scene.objects.size());
  SimulationOptions options;
  options.seed = seed;
  Simulation simulation(scene, options);
  Rng annotation(seed, 1000);  // its own stream: the sensors' draws stay those of a plain simulation
  for (int k = 0; k < scene.cycle_count(); ++k) {
    const double t_s = scene.cycle_time_at(k);
    simulation.run_cycle(k);
    const BodyState& ego = simulation.snapshot().ego;
    rec.ego.push_back(ego_sample(t_s, ego));
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
      if (!scene.objects[o].present_at(t_s)) continue;
      const BodyState s = simulation.object_state(o);
      if ((s.X_WB.translation() - ego.X_WB.translation()).norm() > noise.max_range_m) continue;
      AnnotatedBox box;
      box.t_s = t_s;
      box.x_m = s.X_WB.x_m + noise.position_sigma_m * annotation.normal();
      box.y_m = s.X_WB.y_m + noise.position_sigma_m * annotation.normal();
      box.yaw_rad = s.X_WB.yaw_rad + noise.yaw_sigma_rad * annotation.normal();
      box.speed_mps = s.heading_speed_mps();
      rec.boxes[o].push_back(box);
    }
    for (std::size_t i = 0; i < simulation.sensor_count(); ++i) {
      for (const auto& t : simulation.sensor_state(i).reported) {
        rec.targets.push_back({t_s, k, static_cast<int>(i), t.id, t.range_m, t.azimuth_rad, t.range_rate_mps,
                               t.amplitude_db});
      }
    }
  }
  // Objects never annotated are not listed (a recording lists what was annotated).
  Recording listed = std::move(rec);
  rec = Recording{};
  std::vector<std::vector<AnnotatedBox>> boxes = std::move(listed.boxes);
  listed.boxes.clear();
  for (std::size_t o = 0; o < scene.objects.size(); ++o) {
    if (boxes[o].empty()) continue;
    const SceneObject& object = scene.objects[o];
    listed.objects.push_back({object.id, object.model_name, object.model.length_m, object.model.width_m});
    listed.boxes.push_back(std::move(boxes[o]));
  }
  return listed;
}

}  // namespace rcsim::replay
