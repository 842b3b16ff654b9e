#pragma once
// Runs a scene cycle by cycle for every mounted sensor.
#include <vector>

#include "scene/scene.hpp"
#include "sim/scene_culling.hpp"
#include "sim/sensor_cycle.hpp"

namespace rcsim {

class Simulation {
 public:
  Simulation(const Scene& scene, const SimulationOptions& options);
  // Rebuilds the scene's broad phase over scene times [t0_s, t1_s] (a streaming replay, whose
  // trajectories hold a window of the drive, calls it as the window moves); output unchanged.
  void cull_within(double t0_s, double t1_s);

  const Scene& scene() const { return scene_; }
  int cycle_count() const { return scene_.cycle_count(); }
  // Computes the scene at cycle k and runs every sensor's cycle; cycles must be run in order.
  void run_cycle(int cycle);
  // The same at an arbitrary time (replays use the recorded cycle times); only_sensor >= 0 runs
  // that sensor's cycle alone (sensors on their own clocks), the others keep their last one.
  void run_at(double t_s, int only_sensor = -1);

  // The last cycle's scene; object states only of the visited objects (object_state has all).
  const SceneSnapshot& snapshot() const { return snapshot_; }
  // Object o's state at the last cycle's time, evaluated now if the broad phase skipped it.
  BodyState object_state(std::size_t o) const;
  std::size_t sensor_count() const { return models_.size(); }
  const SensorModel& sensor_model(std::size_t i) const { return models_[i]; }
  const SensorCycleState& sensor_state(std::size_t i) const { return states_[i]; }
  const SceneObjects& objects() const { return objects_; }

 private:
  const Scene& scene_;
  SceneObjects objects_;
  std::vector<SensorModel> models_;
  std::vector<SensorCycleState> states_;
  SceneCulling scene_culling_;
  bool culling_ = false;
  std::vector<Vec2> p_WS_W_;  // per sensor, this cycle
  SceneSnapshot snapshot_;
};

}  // namespace rcsim
