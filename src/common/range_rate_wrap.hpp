#pragma once
// Doppler aliasing's one formula: a radial speed wrapped into a radar's unambiguous interval
// [min, max) (docs/imaging-radar.md). Used by the sensor model (sim/doppler_aliasing.hpp) and by
// the importers that read aliased speeds (replay/import/doppler_ego_motion.hpp).
#include <cmath>

namespace rcsim {

// v wrapped into [min_mps, max_mps) (max > min): v - k (max - min) for the integer k that puts it there.
inline double wrap_range_rate_mps(double range_rate_mps, double min_mps, double max_mps) {
  if (range_rate_mps >= min_mps && range_rate_mps < max_mps) return range_rate_mps;
  const double width_mps = max_mps - min_mps;
  double wrapped = min_mps + std::fmod(range_rate_mps - min_mps, width_mps);
  if (wrapped < min_mps) wrapped += width_mps;
  if (wrapped >= max_mps) wrapped = min_mps;  // rounding at the upper end
  return wrapped;
}

}  // namespace rcsim
