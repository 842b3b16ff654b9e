#include "sim/spectral_leakage.hpp"

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
    // The offsets from the cell's centre, in cells, on the grid from 0.
    const double range_cells = d.range_m / cell.range_cell_m, rate_cells = d.range_rate_mps / cell.range_rate_cell_mps;
    const double offset_range = range_cells - std::floor(range_cells) - 0.5;
    const double offset_rate = rate_cells - std::floor(rate_cells) - 0.5;
    const double peak = hann_response(offset_range) * hann_response(offset_rate);
    const double margin_db = d.amplitude_db - threshold_db;
    if (margin_db < 0.0) continue;  // its neighbours are weaker still
    for (int i = -kLeakageReachCells; i <= kLeakageReachCells; ++i) {
      const double along_range = hann_response(i - offset_range);
      for (int j = -kLeakageReachCells; j <= kLeakageReachCells; ++j) {
        if (i == 0 && j == 0) continue;
        const double relative = along_range * hann_response(j - offset_rate) / peak;
        if (!(relative > 0.0)) continue;
        const double level_db = d.amplitude_db + amplitude_to_db(relative);
        if (level_db < threshold_db) continue;
        Detection leak = d;
        leak.range_m = d.range_m + i * cell.range_cell_m;
        leak.range_rate_mps = d.range_rate_mps + j * cell.range_rate_cell_mps;
        leak.amplitude_db = level_db;
        if (leak.range_m > 0.0) detections.push_back(leak);
      }
    }
  }
}

}  // namespace rcsim
