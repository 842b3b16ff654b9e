#include "sim/spectral_leakage.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "common/angles.hpp"
#include "common/decibel.hpp"

namespace rcsim {

double hann_response(double offset_bins) {
  const double x = std::abs(offset_bins);
  if (x < 1e-9) return 1.0;
  if (std::abs(x - 1.0) < 1e-9) return 0.5;  // the removable singularity: sinc'(1) / (-2) = 1/2
  const double sinc = std::sin(kPi * x) / (kPi * x);
  return std::abs(sinc / (1.0 - x * x));
}

void add_spectral_leakage(const ResolutionCell& cell, double threshold_db, Detections& detections) {
  if (cell.window == SpectralWindow::none) return;
  const std::size_t count = detections.size();
  for (std::size_t k = 0; k < count; ++k) {
    const Detection d = detections[k];  // a copy: the vector grows
    if (!(d.amplitude_db >= threshold_db)) continue;  // its neighbours are weaker still (and NaN leaks nothing)
    // The cells and the offsets from their centres, in cells (map_cell_index).
    const double range_cell_index = map_cell_index(d.range_m, cell.range_cell_m);
    const double rate_cell_index = map_cell_index(d.range_rate_mps, cell.range_rate_cell_mps);
    const double offset_range_cells = map_cell_offset(d.range_m, cell.range_cell_m);
    const double offset_rate_cells = map_cell_offset(d.range_rate_mps, cell.range_rate_cell_mps);
    std::array<double, 2 * kLeakageReachCells + 1> along_range{}, along_rate{};
    for (int i = -kLeakageReachCells; i <= kLeakageReachCells; ++i) {
      along_range[static_cast<std::size_t>(i + kLeakageReachCells)] = hann_response(i - offset_range_cells);
      along_rate[static_cast<std::size_t>(i + kLeakageReachCells)] = hann_response(i - offset_rate_cells);
    }
    const double peak = along_range[kLeakageReachCells] * along_rate[kLeakageReachCells];
    // A leak lies in its cell at the detection's offset, kept off the cell's edge so that rounding
    // cannot put it into the next (or back into the detection's own).
    constexpr double kOffEdge_cells = 1e-6;
    const double inside_range_cells = std::clamp(offset_range_cells, -0.5 + kOffEdge_cells, 0.5 - kOffEdge_cells);
    const double inside_rate_cells = std::clamp(offset_rate_cells, -0.5 + kOffEdge_cells, 0.5 - kOffEdge_cells);
    for (int i = -kLeakageReachCells; i <= kLeakageReachCells; ++i) {
      for (int j = -kLeakageReachCells; j <= kLeakageReachCells; ++j) {
        if (i == 0 && j == 0) continue;
        const double relative = along_range[static_cast<std::size_t>(i + kLeakageReachCells)] *
                                along_rate[static_cast<std::size_t>(j + kLeakageReachCells)] / peak;
        if (!(relative > 0.0)) continue;
        const double level_db = d.amplitude_db + amplitude_to_db(relative);
        if (level_db < threshold_db) continue;
        Detection leak = d;
        leak.range_m = (range_cell_index + i + inside_range_cells) * cell.range_cell_m;
        leak.range_rate_mps = (rate_cell_index + j + inside_rate_cells) * cell.range_rate_cell_mps;
        leak.amplitude_db = level_db;
        if (leak.range_m > 0.0) detections.push_back(leak);
      }
    }
  }
}

}  // namespace rcsim
