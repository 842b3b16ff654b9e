#include "metrics/assignment.hpp"

#include <algorithm>
#include <gtest/gtest.h>
#include <limits>
#include <numeric>

#include "common/rng.hpp"

namespace rcsim::metrics {
namespace {

// Minimum over all ways of assigning min(rows, cols) rows to distinct columns.
double brute_force_minimum(const Eigen::MatrixXd& cost) {
  const bool transpose = cost.rows() > cost.cols();
  const Eigen::MatrixXd c = transpose ? Eigen::MatrixXd(cost.transpose()) : cost;
  std::vector<int> columns(static_cast<std::size_t>(c.cols()));
  std::iota(columns.begin(), columns.end(), 0);
  double best = std::numeric_limits<double>::infinity();
  do {  // every permutation of columns; the first rows() of them are the assignment
    double total = 0.0;
    for (Eigen::Index i = 0; i < c.rows(); ++i) total += c(i, columns[static_cast<std::size_t>(i)]);
    best = std::min(best, total);
  } while (std::next_permutation(columns.begin(), columns.end()));
  return best;
}

TEST(Assignment, HandCaseTakesTheCheaperCrossing) {
  Eigen::MatrixXd cost(2, 2);
  cost << 4, 1,
          2, 8;
  const Assignment a = solve_assignment(cost);
  EXPECT_EQ(a.column_of_row, (std::vector<int>{1, 0}));
  EXPECT_DOUBLE_EQ(a.total_cost, 3.0);
}

TEST(Assignment, EmptyMatricesAssignNothing) {
  EXPECT_TRUE(solve_assignment(Eigen::MatrixXd(0, 3)).column_of_row.empty());
  const Assignment a = solve_assignment(Eigen::MatrixXd(2, 0));
  EXPECT_EQ(a.column_of_row, (std::vector<int>{-1, -1}));
  EXPECT_EQ(a.total_cost, 0.0);
}

TEST(Assignment, MoreRowsThanColumnsLeavesTheDearestRowOut) {
  Eigen::MatrixXd cost(3, 1);
  cost << 5, 1, 3;
  const Assignment a = solve_assignment(cost);
  EXPECT_EQ(a.column_of_row, (std::vector<int>{-1, 0, -1}));
}

TEST(Assignment, MatchesBruteForceOnRandomRectangularCases) {
  Rng rng(42, 0);
  for (int trial = 0; trial < 400; ++trial) {
    const auto rows = static_cast<Eigen::Index>(1 + rng.uniform01() * 6);
    const auto cols = static_cast<Eigen::Index>(1 + rng.uniform01() * 6);
    Eigen::MatrixXd cost(rows, cols);
    for (Eigen::Index i = 0; i < rows; ++i) {
      for (Eigen::Index j = 0; j < cols; ++j) {
        // Some trials with few distinct values to provoke ties.
        cost(i, j) = trial % 3 == 0 ? std::floor(rng.uniform01() * 3.0) : rng.uniform01() * 10.0;
      }
    }
    const Assignment a = solve_assignment(cost);
    ASSERT_NEAR(a.total_cost, brute_force_minimum(cost), 1e-9) << "trial " << trial;
    std::vector<int> used;
    int assigned = 0;
    for (const int j : a.column_of_row) {
      if (j < 0) continue;
      ++assigned;
      ASSERT_EQ(std::count(used.begin(), used.end(), j), 0) << "column used twice";
      used.push_back(j);
    }
    ASSERT_EQ(assigned, std::min(rows, cols));
  }
}

TEST(Assignment, RefusesNonFiniteCosts) {
  Eigen::MatrixXd cost(1, 1);
  cost << std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(solve_assignment(cost), std::invalid_argument);
}

}  // namespace
}  // namespace rcsim::metrics
