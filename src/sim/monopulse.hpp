#pragma once
// Angle estimation by the monopulse principle (paper III-D, eqs. (7)-(8)).
#include "common/rng.hpp"
#include "sim/antenna.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {

// For each cell: complex Gaussian noise of constant variance (std. dev. pointer_noise_sigma, half
// the variance in each of real and imaginary part) added to the summed pointers, eq. (8); the
// angle from the noisy pointers by inverting eq. (7); the amplitude the magnitude of the noisy sum
// pointer. `rng` null means no noise. The truth of the cell is its strongest member's object.
void estimate_monopulse_angles(const MonopulseAntenna& antenna, double pointer_noise_sigma,
                               const ResolutionCells& cells, const IdealTargets& ideal, Rng* rng, Detections& out);

// Fidelity::no_monopulse: the same detections without eqs. (7)-(8): the angle is the ideal azimuth of
// the cell's strongest member plus Gaussian noise of std. dev. angle_sigma_rad (one draw per cell,
// none without `rng`); the amplitude the magnitude of the cell's noise-free sum pointer.
void estimate_ideal_angles(double angle_sigma_rad, const ResolutionCells& cells, const IdealTargets& ideal, Rng* rng,
                           Detections& out);

}  // namespace rcsim
