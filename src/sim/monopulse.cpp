#include "sim/monopulse.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "sim/amplitude.hpp"

namespace rcsim {

void estimate_monopulse_angles(const MonopulseAntenna& antenna, double pointer_noise_sigma,
                               const ResolutionCells& cells, const IdealTargets& ideal, Rng* rng, Detections& out) {
  out.clear();
  const double component_sigma = pointer_noise_sigma / std::sqrt(2.0);
  const bool noisy = rng != nullptr && component_sigma > 0.0;
  // A chunk of cells at a time: first the draws of all its cells (in the cells' order, so the
  // sequence is the same), then the angles. Apart, consecutive draws and consecutive angle
  // computations overlap instead of waiting on each other.
  constexpr std::size_t kChunk = 16;
  // Per cell: sum imaginary, sum real, delta imaginary, delta real. This is the order in which
  // the earlier code, std::complex(sigma * normal(), sigma * normal()), drew them under GCC (it
  // evaluates those arguments right to left); kept so that a seed gives the same noise as before.
  std::array<double, 4 * kChunk> normal;
  for (std::size_t first = 0; first < cells.size(); first += kChunk) {
    const std::size_t n = std::min(kChunk, cells.size() - first);
    for (std::size_t k = 0; k < 4 * n; ++k) normal[k] = noisy ? rng->normal() : 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const auto& c = cells[first + k];
      // eq. (8): + Noise (zero without noise).
      const AntennaPointers h{c.sum_pointer + component_sigma * std::complex<double>(normal[4 * k + 1], normal[4 * k]),
                              c.delta_pointer + component_sigma * std::complex<double>(normal[4 * k + 3], normal[4 * k + 2])};
      Detection& d = out.emplace_back();  // built in place, not copied from the stack
      d.range_m = c.range_m;
      d.range_rate_mps = c.range_rate_mps;
      d.azimuth_rad = antenna.estimate_azimuth(h);  // eq. (7) inverted, sign from the phase
      d.elevation_rad = c.elevation_rad;
      const double power = std::norm(h.sum);        // |A|^2 of the resulting amplitude
      d.amplitude_db = power > 0.0 ? power_to_db(power) : -300.0;
      d.object_index = ideal[static_cast<std::size_t>(c.strongest_ideal_index)].object_index;
    }
  }
}

void estimate_ideal_angles(double angle_sigma_rad, const ResolutionCells& cells, const IdealTargets& ideal, Rng* rng,
                           Detections& out) {
  out.clear();
  const bool noisy = rng != nullptr && angle_sigma_rad > 0.0;
  for (const auto& c : cells) {
    const IdealTarget& strongest = ideal[static_cast<std::size_t>(c.strongest_ideal_index)];
    Detection& d = out.emplace_back();
    d.range_m = c.range_m;
    d.range_rate_mps = c.range_rate_mps;
    d.azimuth_rad = strongest.azimuth_rad + (noisy ? angle_sigma_rad * rng->normal() : 0.0);
    d.elevation_rad = c.elevation_rad;
    const double power = std::norm(c.sum_pointer);  // |A|^2, eq. (3) summed over the cell
    d.amplitude_db = power > 0.0 ? power_to_db(power) : -300.0;
    d.object_index = strongest.object_index;
  }
}

}  // namespace rcsim
