#pragma once
// Writes a finished traffic run as an `rcsim-scene` (schemas/scene.md), atomically.
#include <string>

#include "traffic/traffic_sim.hpp"

namespace rcsim::traffic {

// The scene text (deterministic: fixed decimals, vehicles in order of appearance).
std::string scene_json(const TrafficSimulation& sim);
void write_scene(const std::string& path, const TrafficSimulation& sim);

}  // namespace rcsim::traffic
