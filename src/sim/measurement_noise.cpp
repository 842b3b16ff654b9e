#include "sim/measurement_noise.hpp"

#include <algorithm>
#include <cmath>

#include "common/angles.hpp"
#include "sim/amplitude.hpp"

namespace rcsim {

void add_measurement_noise(const MeasurementNoise& noise, double threshold_db, Rng& rng, Detections& detections) {
  for (auto& d : detections) {
    const double ratio = db_to_amplitude(threshold_db - d.amplitude_db);  // A_th / A
    d.range_m += noise_sigma(noise.range_sigma_at_threshold_m, noise.range_sigma_min_m, ratio) * rng.normal();
    d.range_rate_mps +=
        noise_sigma(noise.range_rate_sigma_at_threshold_mps, noise.range_rate_sigma_min_mps, ratio) * rng.normal();
    d.range_m = std::max(d.range_m, 0.0);
    // A radar that measures elevation: its elevation's noise, of one deviation at every amplitude.
    if (noise.elevation_sigma_rad > 0.0) {
      d.elevation_rad = std::clamp(d.elevation_rad + noise.elevation_sigma_rad * rng.normal(), -0.5 * kPi, 0.5 * kPi);
    }
  }
}

}  // namespace rcsim
