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
  for (const ReportedTarget& r : simulation_.sensor_state(sensor).reported) out.push_back(compared_target(r));
}

void ReferenceSource::append_targets(std::size_t sensor, std::vector<ComparedTarget>& out) const {
  for (const synth::ReportedTarget& r : reference_.sensor_cycle(sensor).targets) out.push_back(compared_target(r));
}

}  // namespace rcsim::replay
