#include "replay/run/simulated_source.hpp"

#include <cmath>

namespace rcsim::replay {

SimulationOptions model_options(std::uint64_t seed, Fidelity fidelity) {
  SimulationOptions options;
  options.level = ListLevel::tracks;
  options.seed = seed;
  options.fidelity = fidelity;
  return options;
}

void ModelSource::append_targets(std::size_t sensor, std::vector<ComparedTarget>& out) const {
  // A radar that measures elevation gives its targets' elevations (a planar one none: NaN).
  const bool elevation = simulation_.scene().sensors[sensor].config.fov.measures_elevation();
  for (const ReportedTarget& r : simulation_.sensor_state(sensor).reported) {
    out.push_back(compared_target(r));
    if (elevation) out.back().elevation_rad = r.elevation_rad;
  }
}

void ReferenceSource::append_targets(std::size_t sensor, std::vector<ComparedTarget>& out) const {
  for (const synth::ReportedTarget& r : reference_.sensor_cycle(sensor).targets) out.push_back(compared_target(r));
}

}  // namespace rcsim::replay
