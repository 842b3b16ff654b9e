#pragma once
// Angle-merge artefacts (paper III-C, Fig. 10): when two objects share a range–speed resolution
// cell, the sensor sees one pointer sum and its monopulse angle lands somewhere between them,
// often on neither. A target is counted as such an artefact of a pair of objects when
//   - the pair's nearest contour points lie in one resolution cell: |ΔR| < range cell and
//     |ΔṘ| < range-rate cell (both objects in the field of view),
//   - the target's azimuth lies strictly between the two nearest points' azimuths,
//   - its range is within one range cell of the pair's ranges, and
//   - it is farther than contour_margin_m from both boxes ("away from both contours").
#include <vector>

#include "metrics/sensor_view.hpp"

namespace rcsim::metrics {

struct MergeParameters {
  double range_cell_m = 0.30;         // the sensor's resolution (srr24: paper III-C)
  double range_rate_cell_mps = 0.5;
  double contour_margin_m = 0.5;
};

struct MergePair {
  int box_a = -1, box_b = -1;  // indices into the cycle's boxes (box_a < box_b)
};

// Pairs of boxes (all assumed in view) that share a resolution cell.
std::vector<MergePair> merge_pairs(const std::vector<BoxInSensor>& boxes, const MergeParameters& parameters);

// The pair (index into pairs) whose artefact the target at (range, azimuth, p_ST_S) is, or -1.
int merge_artefact_of(const std::vector<BoxInSensor>& boxes, const std::vector<MergePair>& pairs, double range_m,
                      double azimuth_rad, const Vec2& p_ST_S, const MergeParameters& parameters);

}  // namespace rcsim::metrics
