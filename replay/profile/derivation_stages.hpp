#pragma once
// The stages of `rcsim profile derive` (docs/profile-derive.md), each reading one part of a sensor
// profile off the pooled detections, as docs/sensor-profiles.md did by hand for aimotive_lrr, and
// adds to `figures` what it read them from (for --report).
#include <nlohmann/json.hpp>
#include <vector>

#include "replay/profile/derivation_figures.hpp"
#include "replay/profile/derived_value.hpp"
#include "replay/profile/detection_pool.hpp"
#include "replay/profile/frame_matching.hpp"

namespace rcsim::replay::profile {

// x rounded to the nearest multiple of step.
double round_to(double x, double step);

// View field: the nearer of azimuth's 0.1 % and 99.9 % quantiles, the 99.9 % quantile of range; the minimum range where detections
// come near the sensor (else the base's, not observable).
std::vector<DerivedValue> derive_view_field(const DetectionPool& pool, std::vector<DerivationFigure>& figures);

// The reporting threshold (the amplitude histogram's abrupt start: its 0.1 % quantile, to 0.5 dB
// below) and, for an SNR with the radar's RCS beside it, the radar equation's constant and range
// exponent with the antenna pattern (least squares of SNR - RCS against log10 R and eq. (6)).
std::vector<DerivedValue> derive_amplitude(const DetectionPool& pool, const nlohmann::json& base, double azimuth_half_deg,
                                           std::vector<DerivationFigure>& figures);

// The cells, from the gaps between pairs of one sensor cycle: no two detections share a range-
// Doppler cell, so pairs at one radial speed lie a range cell apart and pairs at one range a
// range-rate cell apart. A cell the pairs do not show (no emptier within it than beside it, as
// from continuous values) is the base's, said why; `cells` then holds the base's (found: the
// range cell was derived).
struct Cells {
  double range_m = 0.0, range_rate_mps = 0.0;
  bool found = false;
  double range_low_m = 0.0, range_high_m = 0.0;  // the range cell's interval (found)
};
std::vector<DerivedValue> derive_resolution(const DetectionPool& pool, const nlohmann::json& base, Cells& cells,
                                           std::vector<DerivationFigure>& figures);

// Measurement noise: a quantised quantity's step / sqrt(12); else the radial speed's residual
// about the stationary fit by SNR margin, and the range's from stationary detections matched
// frame to frame (drives only). Also the cycle time, from the same matching.
std::vector<DerivedValue> derive_noise(const DetectionPool& pool, const Cells& cells, double threshold_db,
                                       const std::vector<FramePair>& frame_pairs, std::vector<DerivationFigure>& figures);

// The fluctuation (Swerling 0, 1 or 3): which model's re-detection probability, given the SNR
// margin a stationary detection was seen at, the matched cycles follow best.
std::vector<DerivedValue> derive_fluctuation(const std::vector<FramePair>& frame_pairs, bool snapshots,
                                             std::vector<DerivationFigure>& figures);

}  // namespace rcsim::replay::profile
