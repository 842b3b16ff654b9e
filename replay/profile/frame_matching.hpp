#pragma once
// Stationary detections of one sensor matched from a cycle to its next after the ego's motion
// (docs/sensor-profiles.md: "stationary targets matched frame to frame after ego motion"): the
// time between the cycles, the range noise and the re-detection rate that `profile derive` reads.
#include <optional>
#include <vector>

#include "replay/profile/detection_pool.hpp"

namespace rcsim::replay::profile {

// A stationary detection of the earlier cycle whose place the later one still sees.
struct Redetection {
  double margin_db = 0.0;  // its SNR margin over the threshold in the earlier cycle
  bool seen = false;       // a stationary detection of the later cycle within the gate
};

// A stationary detection seen again in the later cycle: how its measurement moved against where the
// ego's motion puts it, and its SNR margins in both cycles (the noise law's two ends).
struct MatchedDetection {
  double range_m = 0.0;         // later range - predicted range
  double range_rate_mps = 0.0;  // the difference of the two radial speeds' stationary residuals, both along the earlier azimuth
  double margin_earlier_db = 0.0, margin_later_db = 0.0;
};

// Two consecutive cycles of one sensor, matched.
struct FramePair {
  double dt_s = 0.0;  // the time the static world's shift shows
  int recording = 0, sensor = 0, cycle = 0, next_cycle = 0;  // whose cycles, in the pool's numbering
  std::vector<MatchedDetection> matches;
  std::vector<Redetection> redetections;
};

struct ViewLimits {
  double azimuth_half_rad = 0.0, max_range_m = 0.0;
};

// Every pair of consecutive cycles of one sensor with at least 5 matches; none for single frames.
std::vector<FramePair> match_consecutive_cycles(const DetectionPool& pool, double threshold_db, const ViewLimits& view);

// The largest cycle time of which every measured step is a whole multiple (within 10 % of it), as
// the least-squares period of the steps that fit it; none where no period fits 90 % of them.
std::optional<double> fundamental_period(const std::vector<double>& dt_s);

}  // namespace rcsim::replay::profile
