#include "sim/resolution_cells.hpp"

#include <algorithm>
#include <cmath>

namespace rcsim {

void form_resolution_cells(const ResolutionCell& cell, double threshold_amplitude, Echoes& echoes,
                           ResolutionCells& out) {
  out.clear();
  std::sort(echoes.begin(), echoes.end(), [](const Echo& a, const Echo& b) {
    if (a.amplitude != b.amplitude) return a.amplitude > b.amplitude;
    return a.ideal_index < b.ideal_index;  // a total order: same input, same cells
  });
  const double half_range_m = 0.5 * cell.range_cell_m;
  const double half_rate_mps = 0.5 * cell.range_rate_cell_mps;
  // Taken echoes are marked by a negative ideal index, restored at the end.
  for (std::size_t i = 0; i < echoes.size(); ++i) {
    if (echoes[i].ideal_index < 0) continue;
    const Echo& centre = echoes[i];
    ResolutionCellSum c;
    c.strongest_ideal_index = centre.ideal_index;
    double weighted_range = 0.0, weighted_rate = 0.0;
    for (std::size_t j = i; j < echoes.size(); ++j) {
      Echo& e = echoes[j];
      if (e.ideal_index < 0) continue;
      if (std::abs(e.range_m - centre.range_m) > half_range_m ||
          std::abs(e.range_rate_mps - centre.range_rate_mps) > half_rate_mps) {
        continue;
      }
      c.amplitude_upper += e.amplitude;
      weighted_range += e.amplitude * e.range_m;
      weighted_rate += e.amplitude * e.range_rate_mps;
      c.sum_pointer += e.sum_pointer;
      c.delta_pointer += e.delta_pointer;
      ++c.member_count;
      e.ideal_index = -1 - e.ideal_index;
    }
    if (c.amplitude_upper < threshold_amplitude) continue;  // paper III-C: no entry for this cell
    c.range_m = weighted_range / c.amplitude_upper;         // eqs. (4)-(5)
    c.range_rate_mps = weighted_rate / c.amplitude_upper;
    out.push_back(c);
  }
  for (auto& e : echoes) e.ideal_index = -1 - e.ideal_index;
}

}  // namespace rcsim
