#pragma once
// Angle-merge artefacts (paper III-C, Fig. 10), by the sensor's own resolution rule. When echoes
// of two objects fall in one range x range-rate resolution cell (the sensor model's merging rule:
// within half a cell of the cell's strongest echo, eqs. (4)-(5)), the sensor measures one pointer
// sum and its monopulse angle lands somewhere between them, often on neither object. The cells
// come from the scene geometry (replay/run/scene_geometry.hpp), not from either target list.
//
// A target is an artefact of such a cell when
//   - its range and range rate lie in the cell: within one cell of the cell's range and range
//     rate (the model's half-cell window, widened by half a cell for measurement noise);
//   - its azimuth lies within the span of the two objects' echoes that formed the cell;
//   - it lies on neither object: farther than margin_m from both boxes.
// An artefact then belongs to no object (the replay takes it from the association), so it never
// counts as a detection of either car. The margin is smaller than the association gate on
// purpose: cars in adjacent 3.5 m lanes leave a gap of 1.7 m, every point of which lies within
// 0.85 m of a box, so a 1 m gate would leave no room for the artefact of paper Fig. 10
// (docs/metrics.md).
// A recorded and a simulated artefact match when they are artefacts of the same pair of objects
// in the same cycle and lie within match_distance_m of each other (optimal assignment).
#include <vector>

#include "common/pose2.hpp"
#include "metrics/sensor_view.hpp"

namespace rcsim::metrics {

struct MergeParameters {
  double range_cell_m = 0.30;  // the sensor's resolution (srr24: paper III-C)
  double range_rate_cell_mps = 0.5;
  double match_distance_m = 1.0;
  double margin_m = 0.5;  // an artefact lies farther than this from both boxes
};

// One resolution cell holding echoes of two objects, as one sensor sees it in one cycle.
struct MergeCell {
  int object_a = -1, object_b = -1;  // object indices, object_a < object_b
  double range_m = 0.0, range_rate_mps = 0.0;  // the cell's, eqs. (4)-(5)
  double azimuth_lo_rad = 0.0, azimuth_hi_rad = 0.0;  // span of the two objects' echoes in the cell
};

// The cell (index into cells) whose artefact the target is, or -1. boxes: the present objects as
// the sensor sees them (those of each cell's pair are looked up by object index).
int merge_artefact_of(const std::vector<MergeCell>& cells, const std::vector<BoxInSensor>& boxes, double range_m,
                      double range_rate_mps, double azimuth_rad, const Vec2& p_ST_S, const MergeParameters& parameters);

// How many of one pair's recorded artefacts are matched by simulated ones of that pair closer
// than match_distance_m (positions in the sensor frame; optimal assignment, each used once).
int matched_artefacts(const std::vector<Vec2>& recorded_S, const std::vector<Vec2>& simulated_S,
                      double match_distance_m);

}  // namespace rcsim::metrics
