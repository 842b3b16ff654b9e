#include "metrics/sparse_assignment.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

namespace rcsim::metrics {

namespace {

constexpr int kFree = -1;   // a row or column not (yet) assigned
constexpr int kDummy = -2;  // a row on its own dummy column: left unassigned

bool finite_non_negative(double x) { return std::isfinite(x) && x >= 0.0; }

void check_sparse_costs(const SparseCosts& costs, double unassigned_row_cost, double unassigned_column_cost) {
  const auto fail = [](const char* what) { throw std::invalid_argument(std::string("solve_sparse_assignment: ") + what); };
  if (costs.rows < 0 || costs.columns < 0) fail("negative size");
  if (costs.row_start.size() != static_cast<std::size_t>(costs.rows) + 1 || costs.row_start.front() != 0) {
    fail("row_start needs rows + 1 entries from 0");
  }
  if (static_cast<std::size_t>(costs.row_start.back()) != costs.column.size() || costs.column.size() != costs.cost.size()) {
    fail("row_start, column and cost disagree");
  }
  if (!finite_non_negative(unassigned_row_cost) || !finite_non_negative(unassigned_column_cost)) {
    fail("unassigned costs must be finite and >= 0");
  }
  std::vector<int> seen_in_row(static_cast<std::size_t>(costs.columns), -1);
  for (int i = 0; i < costs.rows; ++i) {
    if (costs.row_start[i + 1] < costs.row_start[i]) fail("row_start decreases");
    for (int e = costs.row_start[i]; e < costs.row_start[i + 1]; ++e) {
      const int j = costs.column[static_cast<std::size_t>(e)];
      if (j < 0 || j >= costs.columns) fail("column out of range");
      if (seen_in_row[static_cast<std::size_t>(j)] == i) fail("a column twice in one row");
      seen_in_row[static_cast<std::size_t>(j)] = i;
      if (!finite_non_negative(costs.cost[static_cast<std::size_t>(e)])) fail("costs must be finite and >= 0");
    }
  }
}

// The solver's state: the assignment both ways and the duals u (rows), v (columns; every dummy
// column's stays 0). Invariants (Crouse 2016, sec. III): reduced costs cost − u_i − v_j >= 0 on
// every pair and every row's dummy, = 0 on the assigned ones, v <= 0 and v = 0 on free columns.
class SparseSolver {
 public:
  SparseSolver(const SparseCosts& costs, double dummy_cost)
      : c_(costs), dummy_cost_(dummy_cost), u_(static_cast<std::size_t>(costs.rows), 0.0),
        v_(static_cast<std::size_t>(costs.columns), 0.0), column_of_row_(static_cast<std::size_t>(costs.rows), kFree),
        row_of_column_(static_cast<std::size_t>(costs.columns), kFree), distance_(v_.size()), previous_row_(v_.size()),
        labelled_by_(v_.size(), -1), scanned_by_(v_.size(), -1) {}

  // Augmenting row reduction (Jonker & Volgenant 1987, sec. 4; with ε = 0, an auction's bid):
  // row k takes its cheapest option j1 (reduced by v) and lowers v_j1 by the gap to its second
  // cheapest, so that both cost it alike; j1's former row is free and bids next, up to
  // kBidsPerRow bids a chain (price wars between near-equal rows are left to the searches). On a
  // tie the row takes the second option instead of displacing. Keeps the invariants, with
  // u_k = the second cheapest; a row whose cheapest option is its dummy is left for good.
  void reduce_rows() {
    constexpr int kBidsPerRow = 3;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    for (int i = 0; i < c_.rows; ++i) {
      int k = i;
      for (int bid = 0; bid < kBidsPerRow && k >= 0; ++bid) {
        double u1 = dummy_cost_, u2 = kInf;
        int j1 = kDummy, j2 = kDummy;
        for (int e = c_.row_start[k]; e < c_.row_start[k + 1]; ++e) {
          const int j = c_.column[static_cast<std::size_t>(e)];
          const double h = c_.cost[static_cast<std::size_t>(e)] - v_[static_cast<std::size_t>(j)];
          if (h < u1) {
            u2 = u1;
            j2 = j1;
            u1 = h;
            j1 = j;
          } else if (h < u2) {
            u2 = h;
            j2 = j;
          }
        }
        const auto sk = static_cast<std::size_t>(k);
        if (j1 == kDummy) {  // no pair beats leaving
          column_of_row_[sk] = kDummy;
          u_[sk] = u1;
          break;
        }
        int displaced = row_of_column_[static_cast<std::size_t>(j1)];
        if (u1 < u2) {
          v_[static_cast<std::size_t>(j1)] -= u2 - u1;
        } else if (displaced >= 0) {
          j1 = j2;
          displaced = j1 == kDummy ? kFree : row_of_column_[static_cast<std::size_t>(j1)];
        }
        u_[sk] = u2;
        column_of_row_[sk] = j1;
        if (j1 == kDummy) break;
        row_of_column_[static_cast<std::size_t>(j1)] = k;
        if (displaced >= 0) column_of_row_[static_cast<std::size_t>(displaced)] = kFree;
        k = displaced;
      }
    }
  }

  // One shortest augmenting path from the free row `start` (Dijkstra on reduced costs, lazy
  // deletion heap), then the dual update and the augmentation.
  void augment_from(int start) {
    frontier_.clear();
    frontier_is_heap_ = false;
    scanned_.clear();
    // The sink found so far: a free column, or the dummy of sink_row (at first start's own).
    double sink_distance = dummy_cost_ - u_[static_cast<std::size_t>(start)];
    int sink_column = kDummy, sink_row = start;
    relax(start, 0.0, start, sink_distance);
    while (!frontier_.empty()) {
      const auto [d, j] = pop_nearest();
      const auto sj = static_cast<std::size_t>(j);
      if (scanned_by_[sj] == start || d > distance_[sj]) continue;  // scanned, or a stale entry
      if (!(d < sink_distance)) break;  // nothing left nearer than the sink
      scanned_by_[sj] = start;
      scanned_.push_back(j);
      const int k = row_of_column_[sj];
      if (k == kFree) {
        sink_distance = d;
        sink_column = j;
        break;
      }
      // Row k is reached at d through its tight pair with j; its own dummy is free.
      const double via_dummy = d + dummy_cost_ - u_[static_cast<std::size_t>(k)];
      if (via_dummy < sink_distance) {
        sink_distance = via_dummy;
        sink_row = k;
      }
      relax(k, d, start, sink_distance);
    }
    // Dual update (Crouse 2016, Algorithm 1, steps 20-22), before the assignment changes.
    u_[static_cast<std::size_t>(start)] += sink_distance;
    for (const int j : scanned_) {
      const auto sj = static_cast<std::size_t>(j);
      const double delta = sink_distance - distance_[sj];
      v_[sj] -= delta;
      if (row_of_column_[sj] >= 0) u_[static_cast<std::size_t>(row_of_column_[sj])] += delta;
    }
    // Augment back along the path to start.
    int row = sink_column >= 0 ? previous_row_[static_cast<std::size_t>(sink_column)] : sink_row;
    int column = sink_column;
    for (;;) {
      const int before = column_of_row_[static_cast<std::size_t>(row)];
      column_of_row_[static_cast<std::size_t>(row)] = column;
      if (column >= 0) row_of_column_[static_cast<std::size_t>(column)] = row;
      if (row == start) break;
      column = before;  // a column: row was reached through its pair
      row = previous_row_[static_cast<std::size_t>(column)];
    }
  }

  void solve() {
    reduce_rows();
    for (int i = 0; i < c_.rows; ++i) {
      if (column_of_row_[static_cast<std::size_t>(i)] == kFree) augment_from(i);
    }
  }

  SparseAssignment result(double unassigned_row_cost, double unassigned_column_cost) const {
    SparseAssignment out;
    out.column_of_row.assign(static_cast<std::size_t>(c_.rows), -1);
    int pairs = 0, rows_left = 0;
    for (int i = 0; i < c_.rows; ++i) {
      const int j = column_of_row_[static_cast<std::size_t>(i)];
      if (j < 0) {
        ++rows_left;
        continue;
      }
      out.column_of_row[static_cast<std::size_t>(i)] = j;
      ++pairs;
      for (int e = c_.row_start[i]; e < c_.row_start[i + 1]; ++e) {
        if (c_.column[static_cast<std::size_t>(e)] == j) out.total_cost += c_.cost[static_cast<std::size_t>(e)];
      }
    }
    out.total_cost += unassigned_row_cost * rows_left + unassigned_column_cost * (c_.columns - pairs);
    return out;
  }

 private:
  // Labels the columns of row's pairs not yet scanned in this search, row reached at
  // row_distance; a column no nearer than the sink found is never popped, so not labelled.
  void relax(int row, double row_distance, int search, double sink_distance) {
    const double u_row = u_[static_cast<std::size_t>(row)];
    for (int e = c_.row_start[row]; e < c_.row_start[row + 1]; ++e) {
      const auto j = static_cast<std::size_t>(c_.column[static_cast<std::size_t>(e)]);
      if (scanned_by_[j] == search) continue;
      const double d = row_distance + c_.cost[static_cast<std::size_t>(e)] - u_row - v_[j];
      if (!(d < sink_distance)) continue;
      const bool labelled = labelled_by_[j] == search;
      if (labelled && !(d < distance_[j])) continue;
      labelled_by_[j] = search;
      distance_[j] = d;
      previous_row_[j] = row;
      if (!labelled || frontier_is_heap_) push(d, static_cast<int>(j));
    }
  }

  // The frontier: while short (most searches end within a few columns), a list of the labelled
  // columns searched linearly for the nearest by distance_; beyond, a binary heap of (distance,
  // column) with lazy deletion (an improved column is pushed again, its older entry skipped).
  void push(double d, int j) {
    frontier_.emplace_back(d, j);
    if (frontier_is_heap_) {
      std::push_heap(frontier_.begin(), frontier_.end(), std::greater<>());
    } else if (frontier_.size() > kLinearFrontier) {
      for (auto& entry : frontier_) entry.first = distance_[static_cast<std::size_t>(entry.second)];
      std::make_heap(frontier_.begin(), frontier_.end(), std::greater<>());
      frontier_is_heap_ = true;
    }
  }
  std::pair<double, int> pop_nearest() {
    if (frontier_is_heap_) {
      std::pop_heap(frontier_.begin(), frontier_.end(), std::greater<>());
      const auto entry = frontier_.back();
      frontier_.pop_back();
      return entry;
    }
    std::size_t nearest = 0;
    double d = distance_[static_cast<std::size_t>(frontier_[0].second)];
    for (std::size_t t = 1; t < frontier_.size(); ++t) {
      const double dt = distance_[static_cast<std::size_t>(frontier_[t].second)];
      if (dt < d) {
        d = dt;
        nearest = t;
      }
    }
    const int j = frontier_[nearest].second;
    frontier_[nearest] = frontier_.back();
    frontier_.pop_back();
    return {d, j};
  }

  static constexpr std::size_t kLinearFrontier = 256;
  const SparseCosts& c_;
  const double dummy_cost_;
  std::vector<double> u_, v_;
  std::vector<int> column_of_row_, row_of_column_;
  // Per search (marked by its start row, so nothing is cleared between searches).
  std::vector<double> distance_;
  std::vector<int> previous_row_, labelled_by_, scanned_by_;
  std::vector<int> scanned_;
  std::vector<std::pair<double, int>> frontier_;
  bool frontier_is_heap_ = false;
};

}  // namespace

SparseAssignment solve_sparse_assignment(const SparseCosts& costs, double unassigned_row_cost,
                                         double unassigned_column_cost) {
  check_sparse_costs(costs, unassigned_row_cost, unassigned_column_cost);
  SparseSolver solver(costs, unassigned_row_cost + unassigned_column_cost);
  solver.solve();
  return solver.result(unassigned_row_cost, unassigned_column_cost);
}

}  // namespace rcsim::metrics
