#include "metrics/merge_artefacts.hpp"

#include <cmath>

#include "metrics/gospa.hpp"

namespace rcsim::metrics {

namespace {

// Whether the point lies farther than margin_m from the box of `object` (true when it is absent).
bool off_box(const std::vector<BoxInSensor>& boxes, int object, const Vec2& p_ST_S, double margin_m) {
  for (const BoxInSensor& b : boxes) {
    if (b.object == object) return distance_to_box_m(b, p_ST_S) > margin_m;
  }
  return true;
}

}  // namespace

int merge_artefact_of(const std::vector<MergeCell>& cells, const std::vector<BoxInSensor>& boxes, double range_m,
                      double range_rate_mps, double azimuth_rad, const Vec2& p_ST_S, const MergeParameters& parameters) {
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const MergeCell& c = cells[i];
    // Sensor-frame azimuths lie within the view field, far from the +-pi seam: a plain interval.
    if (std::abs(range_m - c.range_m) <= parameters.range_cell_m &&
        std::abs(range_rate_mps - c.range_rate_mps) <= parameters.range_rate_cell_mps &&
        azimuth_rad >= c.azimuth_lo_rad && azimuth_rad <= c.azimuth_hi_rad &&
        off_box(boxes, c.object_a, p_ST_S, parameters.margin_m) && off_box(boxes, c.object_b, p_ST_S, parameters.margin_m)) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

int matched_artefacts(const std::vector<Vec2>& recorded_S, const std::vector<Vec2>& simulated_S,
                      double match_distance_m) {
  if (recorded_S.empty() || simulated_S.empty()) return 0;
  // GOSPA's assignment pairs exactly the targets closer than its cut-off, at least total cost.
  return gospa(recorded_S, simulated_S, {match_distance_m, 1.0}).assigned;
}

}  // namespace rcsim::metrics
