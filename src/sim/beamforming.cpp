#include "sim/beamforming.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <tuple>

#include "common/angles.hpp"
#include "common/decibel.hpp"

namespace rcsim {

void estimate_beam_angles(double azimuth_sigma_rad, double pointer_noise_sigma, const ResolutionCells& cells,
                          const IdealTargets& ideal, Rng* rng, Detections& out) {
  out.clear();
  const double component_sigma = pointer_noise_sigma / std::sqrt(2.0);
  const bool noisy = rng != nullptr;
  for (const auto& c : cells) {
    std::complex<double> sum = c.sum_pointer;
    double azimuth_rad = c.azimuth_rad;
    if (noisy) {
      const double imaginary = rng->normal(), real = rng->normal();
      sum += component_sigma * std::complex<double>(real, imaginary);  // eq. (8): + Noise
      azimuth_rad = wrap_angle_rad(azimuth_rad + azimuth_sigma_rad * rng->normal());
    }
    Detection& d = out.emplace_back();
    d.range_m = c.range_m;
    d.range_rate_mps = c.range_rate_mps;
    d.azimuth_rad = azimuth_rad;
    d.elevation_rad = c.elevation_rad;
    const double power = std::norm(sum);
    d.amplitude_db = power > 0.0 ? power_to_db(power) : -300.0;
    d.object_index = ideal[static_cast<std::size_t>(c.strongest_ideal_index)].object_index;
  }
}

void keep_strongest_beam_per_cell(const ResolutionCell& cell, Detections& detections, std::vector<std::size_t>& order) {
  // With cells in elevation, the strongest beam of each range-Doppler cell at each elevation: a
  // radar of beams in elevation reports one per elevation cell.
  const auto grid_cell = [&](const Detection& d) {
    return std::tuple(map_cell_index(d.range_m, cell.range_cell_m), map_cell_index(d.range_rate_mps, cell.range_rate_cell_mps),
                      cell.resolves_elevation() ? map_cell_index(d.elevation_rad, cell.elevation_cell_rad) : 0.0);
  };
  order.resize(detections.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  // By grid cell, then strongest first, then earlier first: each cell's first entry stays.
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const auto ca = grid_cell(detections[a]), cb = grid_cell(detections[b]);
    if (ca != cb) return ca < cb;
    if (detections[a].amplitude_db != detections[b].amplitude_db) return detections[a].amplitude_db > detections[b].amplitude_db;
    return a < b;
  });
  std::vector<unsigned char> keep(detections.size(), 0);
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k == 0 || grid_cell(detections[order[k]]) != grid_cell(detections[order[k - 1]])) keep[order[k]] = 1;
  }
  std::size_t kept = 0;
  for (std::size_t i = 0; i < detections.size(); ++i) {
    if (keep[i]) detections[kept++] = detections[i];
  }
  detections.resize(kept);
}

}  // namespace rcsim
