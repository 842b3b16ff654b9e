#pragma once
// The detection decision (paper III-B) as a detection-probability curve: the threshold applies to
// the measured cell amplitude |H_cell,Sigma + noise| of eq. (8), and a target's RCS may fluctuate
// from cycle to cycle (Swerling). Without noise and fluctuation it is the paper's hard threshold.
#include <vector>

#include "common/rng.hpp"
#include "sensor/sensor_config.hpp"
#include "sim/stage_types.hpp"

namespace rcsim {

// A cell whose detection probability is below this is not formed (its echoes yield no entry).
inline constexpr double kNegligibleDetectionProbability = 1e-6;

// Probability that a cell of mean level `mean_level_db` (20 log10 of its mean sum-pointer
// amplitude |H_cell,Sigma|) is measured at or above `threshold_db`, with complex pointer noise of
// E|n|^2 = noise_sigma^2 (eq. (8)) and the given fluctuation of the cell's power S:
//   none (Swerling 0): Q1(sqrt(2 S / s2), sqrt(2 T / s2))  (Marcum Q; Rice)
//   swerling1:         exp(-T / (s2 + S))
//   swerling3:         exp(-T / (s2 + S/2)) (1 + (S/2) T / (s2 + S/2)^2)
// with S = 10^(mean_level_db/10), T = 10^(threshold_db/10), s2 = noise_sigma^2; s2 = 0 gives the
// noise-free limits (a hard threshold for none). docs/amplitude.md derives the formulas.
double detection_probability(Fluctuation fluctuation, double mean_level_db, double threshold_db, double noise_sigma);

// The mean cell level below which a cell is not formed: the threshold itself without fluctuation
// (the paper's III-C gate on A_cell^u), else where the detection probability falls below
// kNegligibleDetectionProbability.
double detection_floor_db(const SensorConfig& config);

// Swerling 1/3: each cell's power is multiplied by a fresh draw of unit mean (exponential, or
// chi-square with 4 degrees of freedom / 4), its pointers by the square root (the angle of eq.
// (7) does not change). One draw (Swerling 1) or two (Swerling 3) per cell, in the cells' order.
void apply_fluctuation(Fluctuation fluctuation, Rng& rng, ResolutionCells& cells);

// Keeps the detections whose amplitude is a local maximum of the range/range-rate map: none
// stronger in its own map cell or the eight around it (map_cell_index; ties: the earlier one
// stays), so two kept at one radial speed lie at least a range cell apart. Order
// kept. The buffers are the caller's (no allocation once they have grown).
struct LocalMaximaBuffers {
  std::vector<std::size_t> by_range;
  std::vector<unsigned char> peak;
};
void keep_local_maxima(const ResolutionCell& cell, Detections& detections, LocalMaximaBuffers& buffers);

}  // namespace rcsim
