#pragma once
// Angles of an array that resolves azimuth (an imaging radar, docs/imaging-radar.md): the paper's
// step III-D for a sensor whose cells are range x range rate x azimuth. Where the paper's sensor
// measures one monopulse angle per range/range-rate cell (eqs. (7)-(8)), merging every reflector
// in it, a MIMO array forms beams: two reflectors a beam width apart are resolved, and each beam
// cell has its own angle.
#include <vector>

#include "common/rng.hpp"
#include "sensor/sensor_config.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {

// For each beam cell: the angle is its amplitude-weighted azimuth (eq. (4) applied to the
// azimuth) plus Gaussian noise of std. dev. azimuth_sigma_rad; the amplitude is the magnitude of
// its sum pointer plus complex noise of std. dev. pointer_noise_sigma (eq. (8)). Draws per cell,
// in the cells' order: the noise's imaginary and real part, then the angle; none without `rng`.
void estimate_beam_angles(double azimuth_sigma_rad, double pointer_noise_sigma, const ResolutionCells& cells,
                          const IdealTargets& ideal, Rng* rng, Detections& out);

// One detection per range-Doppler cell (a radar that reports the strongest beam of each cell of
// its range/range-rate map): the detections fall into the map's cells (map_cell_index: centred
// on whole multiples of range_cell_m and range_rate_cell_mps); in each, only the strongest stays
// (ties: the earlier one).
// Order kept. `order` is the caller's buffer.
void keep_strongest_beam_per_cell(const ResolutionCell& cell, Detections& detections, std::vector<std::size_t>& order);

}  // namespace rcsim
