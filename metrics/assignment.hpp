#pragma once
// Optimal assignment (linear sum assignment) for rectangular cost matrices: the shortest
// augmenting path method with potentials (Jonker & Volgenant 1987; the O(n^2 m) form of Kuhn's
// Hungarian method). Every row is assigned when rows <= columns, every column otherwise.
#include <Eigen/Core>
#include <vector>

namespace rcsim::metrics {

struct Assignment {
  std::vector<int> column_of_row;  // -1 for a row left unassigned (only when rows > columns)
  double total_cost = 0.0;
};

// Minimises the sum of cost(i, column_of_row[i]); costs must be finite.
Assignment solve_assignment(const Eigen::MatrixXd& cost);

}  // namespace rcsim::metrics
