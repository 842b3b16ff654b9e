#include "sim/simulation.hpp"

namespace rcsim {

Simulation::Simulation(const Scene& scene, const SimulationOptions& options) : scene_(scene), objects_(scene.objects) {
  const std::size_t reflectors = scene.most_reflectors_present();
  models_.reserve(scene.sensors.size());
  states_.reserve(scene.sensors.size());
  for (std::size_t i = 0; i < scene.sensors.size(); ++i) {
    models_.emplace_back(scene.sensors[i], scene.effects, options, scene.objects);
    // Each sensor draws from its own stream of the seed: adding a sensor leaves the others' draws alone.
    states_.emplace_back(models_.back(), reflectors, scene.sensor_cycle_time_s(i), options.seed, i);
  }
  culling_ = options.culling && !models_.empty();
  if (culling_) scene_culling_ = SceneCulling(scene, models_.front().culling.radius_m);
  p_WS_W_.resize(scene.sensors.size());
  snapshot_.visited_indices.reserve(scene.objects.size());
  snapshot_.visited.resize(scene.objects.size());
  snapshot_.objects.resize(scene.objects.size());
}

void Simulation::cull_within(double t0_s, double t1_s) {
  if (culling_) scene_culling_ = SceneCulling(scene_, models_.front().culling.radius_m, t0_s, t1_s);
}

void Simulation::run_cycle(int cycle) { run_at(scene_.cycle_time_at(cycle)); }

void Simulation::run_at(double t_s, int only_sensor) {
  snapshot_.t_s = t_s;
  snapshot_.ego = scene_.ego.state_at(t_s);
  // The scene's broad phase: only objects that are present and within some sensor's reach are
  // evaluated and visited (an absent one takes no part; a skipped state keeps its last value).
  for (std::size_t i = 0; i < models_.size(); ++i) {
    const Pose2& X_WV = snapshot_.ego.X_WB;  // the ego's body frame is the vehicle frame V
    p_WS_W_[i] = transform_point(X_WV, models_[i].mount.X_VS.translation());
  }
  for (const std::uint32_t i : snapshot_.visited_indices) snapshot_.visited[i] = 0;
  scene_culling_.select(t_s, p_WS_W_, scene_.objects, snapshot_.visited_indices);
  for (const std::uint32_t i : snapshot_.visited_indices) {
    snapshot_.visited[i] = 1;
    snapshot_.objects[i] = scene_.objects[i].trajectory.state_at(t_s);
  }
  for (std::size_t i = 0; i < models_.size(); ++i) {
    if (only_sensor < 0 || static_cast<std::size_t>(only_sensor) == i) run_sensor_cycle(models_[i], objects_, snapshot_, states_[i]);
  }
}

BodyState Simulation::object_state(std::size_t o) const {
  return snapshot_.visited.at(o) ? snapshot_.objects[o] : scene_.objects[o].trajectory.state_at(snapshot_.t_s);
}

}  // namespace rcsim
