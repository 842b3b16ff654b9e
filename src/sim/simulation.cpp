#include "sim/simulation.hpp"

namespace rcsim {

Simulation::Simulation(const Scene& scene, const SimulationOptions& options) : scene_(scene), objects_(scene.objects) {
  std::size_t reflectors = 0;
  for (const auto& o : scene.objects) reflectors += o.model.reflector_count();
  models_.reserve(scene.sensors.size());
  states_.reserve(scene.sensors.size());
  for (std::size_t i = 0; i < scene.sensors.size(); ++i) {
    models_.emplace_back(scene.sensors[i], scene.effects, options, scene.objects);
    // Each sensor draws from its own stream of the seed: adding a sensor leaves the others' draws alone.
    states_.emplace_back(models_.back(), reflectors, scene.cycle_time_s, options.seed, i);
  }
  snapshot_.objects.resize(scene.objects.size());
  snapshot_.present.resize(scene.objects.size());
}

void Simulation::run_cycle(int cycle) { run_at(scene_.cycle_time_at(cycle)); }

void Simulation::run_at(double t_s) {
  snapshot_.t_s = t_s;
  snapshot_.ego = scene_.ego.state_at(t_s);
  for (std::size_t i = 0; i < scene_.objects.size(); ++i) {
    snapshot_.present[i] = scene_.objects[i].present_at(t_s) ? 1 : 0;
    // An absent object takes no part: its state is not needed (and keeps its last value).
    if (snapshot_.present[i]) snapshot_.objects[i] = scene_.objects[i].trajectory.state_at(t_s);
  }
  for (std::size_t i = 0; i < models_.size(); ++i) run_sensor_cycle(models_[i], objects_, snapshot_, states_[i]);
}

}  // namespace rcsim
