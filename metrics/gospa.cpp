#include "metrics/gospa.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "metrics/assignment.hpp"

namespace rcsim::metrics {

GospaResult gospa(const std::vector<Vec2>& recorded_S, const std::vector<Vec2>& simulated_S,
                  const GospaParameters& parameters) {
  const double c = parameters.cutoff_m, p = parameters.order_p;
  if (!(c > 0.0) || !(p >= 1.0) || !std::isfinite(c) || !std::isfinite(p)) {
    throw std::invalid_argument("gospa: needs cutoff_m > 0 and order_p >= 1");
  }
  const auto n_x = static_cast<Eigen::Index>(recorded_S.size());
  const auto n_y = static_cast<Eigen::Index>(simulated_S.size());
  const double c_p = std::pow(c, p);
  GospaResult result;
  result.simulated_of_recorded.assign(recorded_S.size(), -1);

  Eigen::MatrixXd cost(n_x, n_y);
  Eigen::MatrixXd distance(n_x, n_y);
  for (Eigen::Index i = 0; i < n_x; ++i) {
    for (Eigen::Index j = 0; j < n_y; ++j) {
      distance(i, j) = (recorded_S[i] - simulated_S[j]).norm();
      cost(i, j) = std::pow(std::min(distance(i, j), c), p);  // min(d, c)^p
    }
  }
  const Assignment assignment = solve_assignment(cost);
  double ospa_sum = 0.0;  // Σ min(d, c)^p over the optimal (cut-off) assignment
  for (Eigen::Index i = 0; i < n_x; ++i) {
    const int j = assignment.column_of_row[i];
    if (j < 0) continue;
    ospa_sum += cost(i, j);
    if (distance(i, j) < c) {
      result.simulated_of_recorded[i] = j;
      result.localisation_mp += std::pow(distance(i, j), p);
      ++result.assigned;
    }
  }
  result.missed = static_cast<int>(n_x) - result.assigned;
  result.false_targets = static_cast<int>(n_y) - result.assigned;
  result.missed_mp = 0.5 * c_p * result.missed;
  result.false_mp = 0.5 * c_p * result.false_targets;
  result.gospa_m = std::pow(result.localisation_mp + result.missed_mp + result.false_mp, 1.0 / p);

  // OSPA: (1/n (Σ min(d,c)^p + c^p (n − m)))^(1/p), m = min(|X|,|Y|), n = max(|X|,|Y|).
  const auto n = std::max(n_x, n_y), m = std::min(n_x, n_y);
  if (n > 0) result.ospa_m = std::pow((ospa_sum + c_p * static_cast<double>(n - m)) / static_cast<double>(n), 1.0 / p);
  return result;
}

}  // namespace rcsim::metrics
