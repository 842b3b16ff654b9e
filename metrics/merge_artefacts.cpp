#include "metrics/merge_artefacts.hpp"

#include <algorithm>
#include <cmath>

#include "common/angles.hpp"

namespace rcsim::metrics {

std::vector<MergePair> merge_pairs(const std::vector<BoxInSensor>& boxes, const MergeParameters& parameters) {
  std::vector<MergePair> pairs;
  for (std::size_t a = 0; a < boxes.size(); ++a) {
    for (std::size_t b = a + 1; b < boxes.size(); ++b) {
      if (std::abs(boxes[a].range_m - boxes[b].range_m) < parameters.range_cell_m &&
          std::abs(boxes[a].range_rate_mps - boxes[b].range_rate_mps) < parameters.range_rate_cell_mps) {
        pairs.push_back({static_cast<int>(a), static_cast<int>(b)});
      }
    }
  }
  return pairs;
}

int merge_artefact_of(const std::vector<BoxInSensor>& boxes, const std::vector<MergePair>& pairs, double range_m,
                      double azimuth_rad, const Vec2& p_ST_S, const MergeParameters& parameters) {
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const BoxInSensor& a = boxes[pairs[i].box_a];
    const BoxInSensor& b = boxes[pairs[i].box_b];
    // Between in angle: on opposite sides of the two nearest points' azimuths.
    const double from_a = angle_difference_rad(azimuth_rad, a.azimuth_rad);
    const double from_b = angle_difference_rad(azimuth_rad, b.azimuth_rad);
    const bool between = from_a * from_b < 0.0;
    const double near_m = std::min(a.range_m, b.range_m) - parameters.range_cell_m;
    const double far_m = std::max(a.range_m, b.range_m) + parameters.range_cell_m;
    if (between && range_m >= near_m && range_m <= far_m && distance_to_box_m(a, p_ST_S) > parameters.contour_margin_m &&
        distance_to_box_m(b, p_ST_S) > parameters.contour_margin_m) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

}  // namespace rcsim::metrics
