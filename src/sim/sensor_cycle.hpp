#pragma once
// One sensor cycle, the paper's Fig. 13 in one function. The sensor model is built once and read
// as const; what changes from cycle to cycle (stage buffers, tracker, generator) lives in
// SensorCycleState.
#include <span>

#include "common/list_level.hpp"
#include "common/rng.hpp"
#include "scene/scene.hpp"
#include "sim/antenna.hpp"
#include "sim/culling.hpp"
#include "sim/detection.hpp"
#include "sim/fidelity.hpp"
#include "sim/ideal_targets.hpp"
#include "sim/resolution_cells.hpp"
#include "sim/stage_types.hpp"
#include "sim/tracking.hpp"

namespace rcsim {

struct SimulationOptions {
  ListLevel level = ListLevel::tracks;
  std::uint64_t seed = 0;
  bool noise = true;  // false: every random draw off (no noise, no clutter)
  Fidelity fidelity = Fidelity::full;  // docs/fidelity.md
  double angle_noise_sigma_rad = kNoMonopulseAngleSigmaRad;  // Fidelity::no_monopulse only
  bool culling = true;  // broad phase (culling.hpp); the output is byte-identical either way
};

// The immutable model of one mounted sensor.
struct SensorModel {
  // `objects`: the scene's objects, for the culling bounds (empty: no culling).
  SensorModel(const MountedSensor& mount, const Effects& effects, const SimulationOptions& options,
              std::span<const SceneObject> objects = {});

  MountedSensor mount;
  MonopulseAntenna antenna;
  double cell_gate_amplitude;  // cells below it are not formed: detection_floor_db (detection.hpp)
  Effects effects;
  SimulationOptions options;
  CullingBounds culling;
};

// Everything of one sensor that changes per cycle; buffers keep their capacity between cycles.
struct SensorCycleState {
  SensorCycleState(const SensorModel& model, std::size_t reflector_capacity, double cycle_time_s, std::uint64_t seed, std::uint64_t stream);

  SensorKinematics kinematics;
  IdealTargets ideal;
  std::vector<unsigned char> may_occlude;  // per object, from the broad phase (culling)
  Echoes echoes;
  ResolutionCellBuffers cell_buffers;
  ResolutionCells cells;
  Detections detections;
  LocalMaximaBuffers local_maxima;
  std::vector<std::size_t> beam_order;  // keep_strongest_beam_per_cell
  ReportedTargets reported;
  Tracker tracker;
  Rng rng;
};

// The scene at one instant: computed once per cycle, shared by all sensors.
struct SceneSnapshot {
  double t_s = 0.0;
  BodyState ego;
  // The objects the sensors visit, ascending: every object present at this time
  // (SceneObject::presence), with culling only those within some sensor's reach (SceneCulling).
  std::vector<std::uint32_t> visited_indices;
  std::vector<unsigned char> visited;  // per object: 1 where listed in visited_indices
  std::vector<BodyState> objects;      // valid where visited[i]
};

// The scene's objects as the sensor cycle reads them.
struct SceneObjects {
  explicit SceneObjects(std::span<const SceneObject> objects_in) : objects(objects_in) {}
  std::span<const SceneObject> objects;
};

// Whether the cycle reports its detections as they are (the sensor reports detections, or
// Fidelity::no_tracking) rather than the tracker's confirmed tracks.
bool reports_detections(const SensorModel& model);

void run_sensor_cycle(const SensorModel& model, const SceneObjects& objects, const SceneSnapshot& snapshot,
                      SensorCycleState& state);

}  // namespace rcsim
