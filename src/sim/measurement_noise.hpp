#pragma once
// Measurement errors in range and range rate (paper III-A): white Gaussian noise whose variance
// falls as the amplitude rises.
#include "common/rng.hpp"
#include "sensor/sensor_config.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {

// Standard deviation for a detection of the given amplitude: sigma_at_threshold * A_th / A,
// never below sigma_min (the amplitude ratio is linear, so 6 dB above threshold halves sigma).
double noise_sigma(double sigma_at_threshold, double sigma_min, double threshold_db, double amplitude_db);

void add_measurement_noise(const MeasurementNoise& noise, double threshold_db, Rng& rng, Detections& detections);

}  // namespace rcsim
