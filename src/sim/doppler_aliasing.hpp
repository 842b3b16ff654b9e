#pragma once
// Doppler aliasing: a radar whose chirps repeat slowly measures radial speeds only within an
// unambiguous interval [min, max) of width lambda / (2 T_chirp); a faster one reads as
// v - k (max - min), wrapped into the interval (docs/imaging-radar.md). The Astyx HiRes: 128
// steps of 0.0812 m/s, about +-5.2 m/s.
#include "common/range_rate_wrap.hpp"
#include "sensor/sensor_config.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {

// Every detection's range rate wrapped into the cell's unambiguous interval; nothing when the
// sensor does not alias.
void alias_range_rates(const ResolutionCell& cell, Detections& detections);

}  // namespace rcsim
