#pragma once
// Set distances between the recorded targets X and the simulated targets Y of one sensor cycle,
// on positions in the sensor's Cartesian frame.
//
// GOSPA: A. S. Rahmathullah, Á. F. García-Fernández, L. Svensson, "Generalized optimal
// sub-pattern assignment metric", Proc. FUSION 2017, eq. (2) with α = 2:
//   d = ( min_γ Σ_{(i,j)∈γ} d(x_i, y_j)^p + c^p/2 (|X| + |Y| − 2|γ|) )^(1/p),
// over partial assignments γ of pairs closer than c. Solved as a linear assignment on
// min(d, c)^p (a pair at or beyond c costs the same as leaving both unassigned).
// Solved exactly on the pairs closer than c alone (found on a grid of cells of size c): each
// target paired at d^p or left unassigned at c^p/2, by the sparse shortest augmenting path
// method of metrics/sparse_assignment.hpp (Jonker & Volgenant 1987; docs/metrics.md, "GOSPA on
// the pairs closer than c").
// OSPA: D. Schuhmacher, B.-T. Vo, B.-N. Vo, "A consistent metric for performance evaluation of
// multi-object filters", IEEE Trans. Signal Processing 56(8), 2008, eq. (3).
#include <vector>

#include "common/pose2.hpp"

namespace rcsim::metrics {

struct GospaParameters {
  double cutoff_m = 2.0;  // c
  double order_p = 2.0;   // p >= 1
  // α is fixed at 2: the only value for which GOSPA splits into localisation, missed and false.
};

struct GospaResult {
  double gospa_m = 0.0;          // the metric, in metres
  // Its p-th power split: gospa_m^p = localisation + missed + false (units m^p).
  double localisation_mp = 0.0;  // Σ d^p over the assigned pairs
  double missed_mp = 0.0;        // c^p/2 per recorded target left unassigned
  double false_mp = 0.0;         // c^p/2 per simulated target left unassigned
  int assigned = 0, missed = 0, false_targets = 0;
  double ospa_m = 0.0;           // OSPA with the same c and p (0 when both sets are empty)
  // For each recorded target, the simulated target assigned to it (closer than c), or -1.
  std::vector<int> simulated_of_recorded;
};

GospaResult gospa(const std::vector<Vec2>& recorded_S, const std::vector<Vec2>& simulated_S,
                  const GospaParameters& parameters);

namespace detail {
// The same figures by the dense assignment (metrics/assignment.hpp) on each connected component
// of the pairs closer than c, O(n^2 m) per component: the way before issue 52, the reference of
// the tests and the benchmark.
GospaResult gospa_dense_components(const std::vector<Vec2>& recorded_S, const std::vector<Vec2>& simulated_S,
                                   const GospaParameters& parameters);
// The same figures by one assignment over all |X| x |Y| pairs, O(n^3): the reference of the
// tests and the benchmark, and the way taken when a coordinate is not finite.
GospaResult gospa_full_assignment(const std::vector<Vec2>& recorded_S, const std::vector<Vec2>& simulated_S,
                                  const GospaParameters& parameters);
}  // namespace detail

}  // namespace rcsim::metrics
