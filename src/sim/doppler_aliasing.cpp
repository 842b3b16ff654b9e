#include "sim/doppler_aliasing.hpp"

#include <cmath>

namespace rcsim {

void alias_range_rates(const ResolutionCell& cell, Detections& detections) {
  if (!cell.aliases_range_rate()) return;
  for (Detection& d : detections) {
    d.range_rate_mps = wrap_range_rate_mps(d.range_rate_mps, cell.unambiguous_min_mps, cell.unambiguous_max_mps);
  }
}

}  // namespace rcsim
