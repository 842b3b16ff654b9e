#include "metrics/sparse_assignment.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <set>

#include "common/rng.hpp"
#include "metrics/assignment.hpp"

namespace rcsim::metrics {
namespace {

struct Pair {
  int row, column;
  double cost;
};

SparseCosts sparse_costs(int rows, int columns, const std::vector<Pair>& pairs) {
  SparseCosts costs;
  costs.rows = rows;
  costs.columns = columns;
  costs.row_start.assign(static_cast<std::size_t>(rows) + 1, 0);
  std::vector<Pair> sorted = pairs;
  std::stable_sort(sorted.begin(), sorted.end(), [](const Pair& a, const Pair& b) { return a.row < b.row; });
  for (const Pair& p : sorted) {
    costs.column.push_back(p.column);
    costs.cost.push_back(p.cost);
    ++costs.row_start[static_cast<std::size_t>(p.row) + 1];
  }
  for (int i = 0; i < rows; ++i) costs.row_start[static_cast<std::size_t>(i) + 1] += costs.row_start[static_cast<std::size_t>(i)];
  return costs;
}

// The same problem as one dense assignment of (rows + columns) x (columns + rows) (the standard
// reduction): pairs top left, each row's own "leave" column top right, each column's own "leave"
// row bottom left, zeros bottom right; a forbidden cell costs more than every way around it.
double dense_minimum(const SparseCosts& costs, double row_leave, double column_leave) {
  const int n = costs.rows, m = costs.columns;
  double forbidden = 1.0 + (row_leave + column_leave) * (n + m);
  for (const double c : costs.cost) forbidden += c;
  Eigen::MatrixXd dense = Eigen::MatrixXd::Constant(n + m, m + n, forbidden);
  for (int i = 0; i < n; ++i) {
    for (int e = costs.row_start[static_cast<std::size_t>(i)]; e < costs.row_start[static_cast<std::size_t>(i) + 1]; ++e) {
      dense(i, costs.column[static_cast<std::size_t>(e)]) = costs.cost[static_cast<std::size_t>(e)];
    }
    dense(i, m + i) = row_leave;
  }
  for (int j = 0; j < m; ++j) dense(n + j, j) = column_leave;
  dense.bottomRightCorner(m, n).setZero();
  return solve_assignment(dense).total_cost;
}

// A valid result: distinct columns, each a candidate of its row; its total as it claims.
void expect_valid(const SparseCosts& costs, double row_leave, double column_leave, const SparseAssignment& a) {
  ASSERT_EQ(a.column_of_row.size(), static_cast<std::size_t>(costs.rows));
  std::set<int> used;
  double total = 0.0;
  for (int i = 0; i < costs.rows; ++i) {
    const int j = a.column_of_row[static_cast<std::size_t>(i)];
    if (j < 0) {
      total += row_leave;
      continue;
    }
    ASSERT_TRUE(used.insert(j).second) << "column " << j << " twice";
    bool candidate = false;
    for (int e = costs.row_start[static_cast<std::size_t>(i)]; e < costs.row_start[static_cast<std::size_t>(i) + 1]; ++e) {
      if (costs.column[static_cast<std::size_t>(e)] == j) {
        candidate = true;
        total += costs.cost[static_cast<std::size_t>(e)];
      }
    }
    ASSERT_TRUE(candidate) << "row " << i << " on column " << j << ", not one of its pairs";
  }
  total += column_leave * static_cast<double>(costs.columns - static_cast<int>(used.size()));
  ASSERT_NEAR(a.total_cost, total, 1e-12 * (1.0 + total));
}

TEST(SparseAssignment, HandCaseTakesThePairsWorthTaking) {
  // Leaving costs 1 a side. Row 0: column 0 at 0.5 or column 1 at 1.5; row 1: column 0 at 0.2.
  // Best: row 1 on column 0 (0.2), row 0 on column 1 (1.5 < 2, leaving both): 1.7.
  const SparseCosts costs = sparse_costs(2, 2, {{0, 0, 0.5}, {0, 1, 1.5}, {1, 0, 0.2}});
  const SparseAssignment a = solve_sparse_assignment(costs, 1.0, 1.0);
  EXPECT_EQ(a.column_of_row, (std::vector<int>{1, 0}));
  EXPECT_DOUBLE_EQ(a.total_cost, 1.7);
  // A pair dearer than leaving both is left: row 0 alone, its pair at 2.5 > 2.
  const SparseAssignment left = solve_sparse_assignment(sparse_costs(1, 1, {{0, 0, 2.5}}), 1.0, 1.0);
  EXPECT_EQ(left.column_of_row, (std::vector<int>{-1}));
  EXPECT_DOUBLE_EQ(left.total_cost, 2.0);
}

TEST(SparseAssignment, UnequalLeavingCosts) {
  // Rows leave at 3, columns at 0: a pair is taken when cheaper than 3.
  const SparseCosts costs = sparse_costs(2, 1, {{0, 0, 2.0}, {1, 0, 1.0}});
  const SparseAssignment a = solve_sparse_assignment(costs, 3.0, 0.0);
  EXPECT_EQ(a.column_of_row, (std::vector<int>{-1, 0}));
  EXPECT_DOUBLE_EQ(a.total_cost, 4.0);
}

TEST(SparseAssignment, EmptyAndPairlessProblems) {
  EXPECT_TRUE(solve_sparse_assignment(sparse_costs(0, 0, {}), 1.0, 1.0).column_of_row.empty());
  const SparseAssignment none = solve_sparse_assignment(sparse_costs(3, 2, {}), 1.0, 0.5);
  EXPECT_EQ(none.column_of_row, (std::vector<int>{-1, -1, -1}));
  EXPECT_DOUBLE_EQ(none.total_cost, 4.0);
  EXPECT_DOUBLE_EQ(solve_sparse_assignment(sparse_costs(0, 4, {}), 1.0, 0.5).total_cost, 2.0);
}

TEST(SparseAssignment, EqualsTheDenseReductionOnRandomProblems) {
  Rng rng(52, 0);
  for (int trial = 0; trial < 600; ++trial) {
    const int rows = static_cast<int>(rng.uniform01() * 13), columns = static_cast<int>(rng.uniform01() * 13);
    const double density = std::array{0.1, 0.3, 0.7, 1.0}[static_cast<std::size_t>(trial % 4)];
    // Every third trial with costs of few distinct values, to provoke ties.
    const bool ties = trial % 3 == 0;
    std::vector<Pair> pairs;
    for (int i = 0; i < rows; ++i) {
      for (int j = 0; j < columns; ++j) {
        if (rng.uniform01() >= density) continue;
        pairs.push_back({i, j, ties ? std::floor(rng.uniform01() * 4.0) : rng.uniform01() * 4.0});
      }
    }
    const double row_leave = ties ? 1.0 : rng.uniform01() * 2.0, column_leave = ties ? 1.0 : rng.uniform01() * 2.0;
    const SparseCosts costs = sparse_costs(rows, columns, pairs);
    const SparseAssignment a = solve_sparse_assignment(costs, row_leave, column_leave);
    SCOPED_TRACE(::testing::Message() << "trial " << trial << ": " << rows << " x " << columns << ", "
                                      << pairs.size() << " pairs");
    expect_valid(costs, row_leave, column_leave, a);
    ASSERT_NEAR(a.total_cost, dense_minimum(costs, row_leave, column_leave), 1e-9);
  }
}

TEST(SparseAssignment, LongChainsOfCompetingRows) {
  // Row i may take column i at 1 or column i + 1 at 0.9: every row prefers its right neighbour,
  // and the searches run along the chain. Leaving costs 1 a side.
  const int n = 300;
  std::vector<Pair> pairs;
  for (int i = 0; i < n; ++i) {
    pairs.push_back({i, i, 1.0});
    if (i + 1 < n) pairs.push_back({i, i + 1, 0.9});
  }
  const SparseCosts costs = sparse_costs(n, n, pairs);
  const SparseAssignment a = solve_sparse_assignment(costs, 1.0, 1.0);
  expect_valid(costs, 1.0, 1.0, a);
  // n − 1 rows on their right neighbour (0.9 each), the last row left (1) and column 0 left (1):
  // 0.9 (n − 1) + 2, against n for every row on its own column.
  EXPECT_NEAR(a.total_cost, 0.9 * (n - 1) + 2.0, 1e-9);
  EXPECT_NEAR(a.total_cost, dense_minimum(costs, 1.0, 1.0), 1e-9);
}

TEST(SparseAssignment, RefusesMalformedInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(solve_sparse_assignment(sparse_costs(1, 1, {{0, 0, nan}}), 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(solve_sparse_assignment(sparse_costs(1, 1, {{0, 0, -1.0}}), 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(solve_sparse_assignment(sparse_costs(1, 1, {{0, 0, 1.0}}), -1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(solve_sparse_assignment(sparse_costs(1, 2, {{0, 1, 1.0}, {0, 1, 2.0}}), 1.0, 1.0), std::invalid_argument);
  SparseCosts out_of_range = sparse_costs(1, 1, {{0, 0, 1.0}});
  out_of_range.column[0] = 1;
  EXPECT_THROW(solve_sparse_assignment(out_of_range, 1.0, 1.0), std::invalid_argument);
  SparseCosts short_starts = sparse_costs(2, 1, {});
  short_starts.row_start.pop_back();
  EXPECT_THROW(solve_sparse_assignment(short_starts, 1.0, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace rcsim::metrics
