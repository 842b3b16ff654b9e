#pragma once
// Exact partial assignment on a sparse set of candidate pairs: each row is either paired with one
// of its candidate columns, at that pair's cost, or left unassigned at a fixed cost, and so is
// each column. Minimises
//   Σ_{(i,j) paired} cost_ij + unassigned_row_cost · (rows left) + unassigned_column_cost · (columns left).
//
// Method: the shortest augmenting path method with dual potentials, one Dijkstra search per row
// over the candidate pairs alone (R. Jonker, A. Volgenant, "A shortest augmenting path algorithm
// for dense and sparse linear assignment problems", Computing 38, 1987; the rectangular form and
// its dual update as in D. F. Crouse, "On implementing 2D rectangular assignment algorithms",
// IEEE Trans. Aerospace and Electronic Systems 52(4), 2016, Algorithm 1), on the standard
// reduction of "leaving" to an assignment: every row i gets a private dummy column of cost
// unassigned_row_cost + unassigned_column_cost, and each pair's cost is kept as it is (the total
// then differs from the one above by unassigned_column_cost · columns, a constant). A dummy column
// is reachable only from its own row, so it takes no space: the search offers it as a sink where
// it reaches the row. Before the searches, Jonker & Volgenant's augmenting row reduction (a few
// bids a row) assigns most rows while keeping the duals feasible. Exact: every search is a
// shortest path on non-negative reduced costs; the result is optimal to the rounding of the
// costs' sums.
// Time O(Σ searches × k log k) for k pairs within each search's reach: the dummies bound a search
// to the pairs within unassigned_row_cost + unassigned_column_cost of reduced cost of its row.
#include <vector>

namespace rcsim::metrics {

// The candidate pairs by row (compressed sparse rows): row i's pairs are
// column[row_start[i] .. row_start[i + 1]) with costs cost[...]; a column at most once per row.
struct SparseCosts {
  int rows = 0, columns = 0;
  std::vector<int> row_start{0};  // rows + 1 entries
  std::vector<int> column;
  std::vector<double> cost;
};

struct SparseAssignment {
  std::vector<int> column_of_row;  // -1 for a row left unassigned
  double total_cost = 0.0;         // Σ over the pairs, plus the unassigned costs of both sides
};

// Costs (pairs and unassigned) must be finite and >= 0. A pair costing at least
// unassigned_row_cost + unassigned_column_cost gains nothing over leaving both.
SparseAssignment solve_sparse_assignment(const SparseCosts& costs, double unassigned_row_cost,
                                         double unassigned_column_cost);

}  // namespace rcsim::metrics
