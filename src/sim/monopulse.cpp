#include "sim/monopulse.hpp"

#include <algorithm>
#include <cmath>

#include "sim/amplitude.hpp"

namespace rcsim {

void estimate_monopulse_angles(const MonopulseAntenna& antenna, double pointer_noise_sigma,
                               const ResolutionCells& cells, const IdealTargets& ideal, Rng* rng, Detections& out) {
  out.clear();
  const double component_sigma = pointer_noise_sigma / std::sqrt(2.0);
  for (const auto& c : cells) {
    AntennaPointers h{c.sum_pointer, c.delta_pointer};
    if (rng != nullptr && component_sigma > 0.0) {  // eq. (8): + Noise
      h.sum += std::complex<double>(component_sigma * rng->normal(), component_sigma * rng->normal());
      h.delta += std::complex<double>(component_sigma * rng->normal(), component_sigma * rng->normal());
    }
    Detection d;
    d.range_m = c.range_m;
    d.range_rate_mps = c.range_rate_mps;
    d.azimuth_rad = antenna.estimate_azimuth(h);  // eq. (7) inverted, sign from the phase
    const double amplitude = magnitude(h.sum);
    d.amplitude_db = amplitude > 0.0 ? amplitude_to_db(amplitude) : -300.0;
    d.object_index = ideal[static_cast<std::size_t>(c.strongest_ideal_index)].object_index;
    out.push_back(d);
  }
}

void apply_detection_threshold(double threshold_db, Detections& detections) {
  std::erase_if(detections, [&](const Detection& d) { return d.amplitude_db < threshold_db; });
}

}  // namespace rcsim
