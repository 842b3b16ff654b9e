#include "metrics/assignment.hpp"

#include <limits>
#include <stdexcept>

namespace rcsim::metrics {

namespace {

// rows <= cols. Dual potentials u (rows), v (cols); for each row in turn, a Dijkstra-like search
// over reduced costs finds the cheapest augmenting path from it to a free column.
std::vector<int> assign_rows(const Eigen::MatrixXd& cost) {
  const int n = static_cast<int>(cost.rows());
  const int m = static_cast<int>(cost.cols());
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // 1-based with column 0 as the virtual start, as in the classic formulation.
  std::vector<double> u(n + 1, 0.0), v(m + 1, 0.0), min_reduced(m + 1);
  std::vector<int> row_of_col(m + 1, 0), previous_col(m + 1, 0);
  std::vector<char> used(m + 1);
  for (int row = 1; row <= n; ++row) {
    row_of_col[0] = row;
    int col0 = 0;
    std::fill(min_reduced.begin(), min_reduced.end(), kInf);
    std::fill(used.begin(), used.end(), 0);
    do {
      used[col0] = 1;
      const int i0 = row_of_col[col0];
      double delta = kInf;
      int col1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double reduced = cost(i0 - 1, j - 1) - u[i0] - v[j];
        if (reduced < min_reduced[j]) {
          min_reduced[j] = reduced;
          previous_col[j] = col0;
        }
        if (min_reduced[j] < delta) {
          delta = min_reduced[j];
          col1 = j;
        }
      }
      for (int j = 0; j <= m; ++j) {
        if (used[j]) {
          u[row_of_col[j]] += delta;
          v[j] -= delta;
        } else {
          min_reduced[j] -= delta;
        }
      }
      col0 = col1;
    } while (row_of_col[col0] != 0);
    do {  // augment along the path back to the start
      const int col1 = previous_col[col0];
      row_of_col[col0] = row_of_col[col1];
      col0 = col1;
    } while (col0 != 0);
  }
  std::vector<int> column_of_row(n, -1);
  for (int j = 1; j <= m; ++j) {
    if (row_of_col[j] != 0) column_of_row[row_of_col[j] - 1] = j - 1;
  }
  return column_of_row;
}

}  // namespace

Assignment solve_assignment(const Eigen::MatrixXd& cost) {
  if (!cost.allFinite()) throw std::invalid_argument("solve_assignment: costs must be finite");
  Assignment result;
  const auto rows = cost.rows(), cols = cost.cols();
  result.column_of_row.assign(static_cast<std::size_t>(rows), -1);
  if (rows == 0 || cols == 0) return result;
  if (rows <= cols) {
    result.column_of_row = assign_rows(cost);
  } else {
    const std::vector<int> row_of_col = assign_rows(cost.transpose());
    for (int j = 0; j < static_cast<int>(cols); ++j) result.column_of_row[row_of_col[j]] = j;
  }
  for (int i = 0; i < static_cast<int>(rows); ++i) {
    if (result.column_of_row[i] >= 0) result.total_cost += cost(i, result.column_of_row[i]);
  }
  return result;
}

}  // namespace rcsim::metrics
