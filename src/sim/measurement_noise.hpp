#pragma once
// Measurement errors in range and range rate (paper III-A): white Gaussian noise whose variance
// falls as the amplitude rises.
#include "common/rng.hpp"
#include "sensor/sensor_config.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {

// Standard deviation for a detection whose amplitude is A = A_th / threshold_ratio:
// sigma_at_threshold * A_th / A, never below sigma_min (6 dB above threshold halves sigma).
inline double noise_sigma(double sigma_at_threshold, double sigma_min, double threshold_ratio) {
  return sigma_at_threshold * threshold_ratio > sigma_min ? sigma_at_threshold * threshold_ratio : sigma_min;
}

void add_measurement_noise(const MeasurementNoise& noise, double threshold_db, Rng& rng, Detections& detections);

}  // namespace rcsim
