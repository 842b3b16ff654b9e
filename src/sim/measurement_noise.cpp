#include "sim/measurement_noise.hpp"

#include <algorithm>
#include <cmath>

namespace rcsim {

double noise_sigma(double sigma_at_threshold, double sigma_min, double threshold_db, double amplitude_db) {
  const double ratio = std::pow(10.0, (threshold_db - amplitude_db) / 20.0);  // A_th / A
  return std::max(sigma_min, sigma_at_threshold * ratio);
}

void add_measurement_noise(const MeasurementNoise& noise, double threshold_db, Rng& rng, Detections& detections) {
  for (auto& d : detections) {
    const double ratio = std::pow(10.0, (threshold_db - d.amplitude_db) / 20.0);  // A_th / A
    d.range_m += std::max(noise.range_sigma_min_m, noise.range_sigma_at_threshold_m * ratio) * rng.normal();
    d.range_rate_mps +=
        std::max(noise.range_rate_sigma_min_mps, noise.range_rate_sigma_at_threshold_mps * ratio) * rng.normal();
    d.range_m = std::max(d.range_m, 0.0);
  }
}

}  // namespace rcsim
