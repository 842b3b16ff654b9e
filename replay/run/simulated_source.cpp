#include "replay/run/simulated_source.hpp"

#include <cmath>

namespace rcsim::replay {

SimulationOptions model_options(std::uint64_t seed, Fidelity fidelity) {
  SimulationOptions options;
  options.level = OutputLevel::tracks;
  options.seed = seed;
  options.fidelity = fidelity;
  return options;
}

void ModelSource::append_targets(std::size_t sensor, std::vector<ComparedTarget>& out) const {
  for (const ReportedTarget& r : simulation_.sensor_state(sensor).reported) out.push_back(compared_target(r));
}

void ModelSource::mark_detected_objects(std::size_t sensor, const std::vector<metrics::BoxInSensor>& /*boxes*/,
                                        double /*gate_m*/, std::vector<char>& detected) const {
  for (const Detection& d : simulation_.sensor_state(sensor).detections) {
    if (d.object_index >= 0) detected[static_cast<std::size_t>(d.object_index)] = 1;
  }
}

void ReferenceSource::append_targets(std::size_t sensor, std::vector<ComparedTarget>& out) const {
  for (const synth::ReportedTarget& r : reference_.sensor_cycle(sensor).targets) out.push_back(compared_target(r));
}

void ReferenceSource::mark_detected_objects(std::size_t sensor, const std::vector<metrics::BoxInSensor>& boxes,
                                            double gate_m, std::vector<char>& detected) const {
  for (const synth::Detection& d : reference_.sensor_cycle(sensor).detections) {
    const Vec2 p_ST_S(d.range_m * std::cos(d.azimuth_rad), d.range_m * std::sin(d.azimuth_rad));
    const int box = metrics::nearest_box(boxes, p_ST_S, gate_m);
    if (box >= 0) detected[static_cast<std::size_t>(boxes[static_cast<std::size_t>(box)].object)] = 1;
  }
}

}  // namespace rcsim::replay
