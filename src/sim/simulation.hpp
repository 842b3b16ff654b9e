#pragma once
// Runs a scene cycle by cycle for every mounted sensor.
#include <vector>

#include "scene/scene.hpp"
#include "sim/sensor_cycle.hpp"

namespace rcsim {

class Simulation {
 public:
  Simulation(const Scene& scene, const SimulationOptions& options);

  const Scene& scene() const { return scene_; }
  int cycle_count() const { return scene_.cycle_count(); }
  // Computes the scene at cycle k and runs every sensor's cycle; cycles must be run in order.
  void run_cycle(int cycle);
  // The same at an arbitrary time (replays use the recorded cycle times).
  void run_at(double t_s);

  const SceneSnapshot& snapshot() const { return snapshot_; }
  std::size_t sensor_count() const { return models_.size(); }
  const SensorModel& sensor_model(std::size_t i) const { return models_[i]; }
  const SensorCycleState& sensor_state(std::size_t i) const { return states_[i]; }
  const SceneObjects& objects() const { return objects_; }

 private:
  const Scene& scene_;
  SceneObjects objects_;
  std::vector<SensorModel> models_;
  std::vector<SensorCycleState> states_;
  SceneSnapshot snapshot_;
};

}  // namespace rcsim
