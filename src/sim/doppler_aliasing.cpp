#include "sim/doppler_aliasing.hpp"

#include <cmath>

namespace rcsim {

double wrap_range_rate_mps(double range_rate_mps, double min_mps, double max_mps) {
  if (range_rate_mps >= min_mps && range_rate_mps < max_mps) return range_rate_mps;
  const double width_mps = max_mps - min_mps;
  double wrapped = min_mps + std::fmod(range_rate_mps - min_mps, width_mps);
  if (wrapped < min_mps) wrapped += width_mps;
  if (wrapped >= max_mps) wrapped = min_mps;  // rounding at the upper end
  return wrapped;
}

void alias_range_rates(const ResolutionCell& cell, Detections& detections) {
  if (!cell.aliases_range_rate()) return;
  for (Detection& d : detections) {
    d.range_rate_mps = wrap_range_rate_mps(d.range_rate_mps, cell.unambiguous_min_mps, cell.unambiguous_max_mps);
  }
}

}  // namespace rcsim
