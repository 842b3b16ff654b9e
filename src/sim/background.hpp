#pragma once
// The stationary background (paper VI: the misdetections of a real environment, added
// randomly): targets drawn each cycle from the sensor's fitted density over range and azimuth,
// each with the range rate of a stationary reflector and an amplitude from the fitted deciles.
#include "common/rng.hpp"
#include "sensor/stationary_background.hpp"
#include "sim/ideal_targets.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {

// Appends Poisson(targets_per_cycle) detections (object_index -1): a cell by its weight, range
// and azimuth uniform within it, range rate -v_S . u (u the line of sight, a stationary point),
// amplitude interpolated in the range bin's deciles at a uniform draw. Nothing when empty.
void add_stationary_background(const StationaryBackground& background, const SensorKinematics& sensor, Rng& rng,
                               Detections& detections);

}  // namespace rcsim
