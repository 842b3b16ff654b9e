// The bounded compass search of calibrate --real-drive (replay/calibrate/bounded_search.hpp):
// cases whose optimum is known by hand.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include "replay/calibrate/bounded_search.hpp"

namespace rcsim::replay {
namespace {

// (x - 3)^2 + (y + 1)^2 from (0, 0), steps 1: the optimum lies on the grid the steps reach,
// inside the bounds, and nothing is said to lie on a bound.
TEST(CompassSearch, FindsAQuadraticsMinimumInsideTheBounds) {
  const auto f = [](const std::vector<double>& x) { return (x[0] - 3.0) * (x[0] - 3.0) + (x[1] + 1.0) * (x[1] + 1.0); };
  const SearchResult r = compass_search({{"x", 0.0, -10.0, 10.0, 1.0, 0.01}, {"y", 0.0, -10.0, 10.0, 1.0, 0.01}}, f, 500);
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.best[0], 3.0, 1e-9);
  EXPECT_NEAR(r.best[1], -1.0, 1e-9);
  EXPECT_NEAR(r.objective, 0.0, 1e-12);
  EXPECT_FALSE(r.on_bound[0]);
  EXPECT_FALSE(r.on_bound[1]);
}

// The minimum at x = 7 lies beyond the upper bound 5: the search ends on the bound and says so.
TEST(CompassSearch, SaysWhenTheOptimumLiesOnABound) {
  const auto f = [](const std::vector<double>& x) { return (x[0] - 7.0) * (x[0] - 7.0); };
  const SearchResult r = compass_search({{"x", 0.0, -5.0, 5.0, 2.0, 0.01}}, f, 500);
  EXPECT_DOUBLE_EQ(r.best[0], 5.0);
  EXPECT_TRUE(r.on_bound[0]);
  EXPECT_DOUBLE_EQ(r.objective, 4.0);
}

// A step of 0.3 from 0 reaches 0.3, 0.15 ...: the search refines below its first step, so the
// optimum 0.2 is found to the resolution, not to the first step's grid.
TEST(CompassSearch, RefinesBelowItsFirstStep) {
  const auto f = [](const std::vector<double>& x) { return std::abs(x[0] - 0.2); };
  const SearchResult r = compass_search({{"x", 0.0, 0.0, 1.0, 0.3, 0.001}}, f, 500);
  EXPECT_NEAR(r.best[0], 0.2, 0.002);
}

TEST(CompassSearch, KeepsTheBudgetAndStopsOnRequestWithTheBestSoFar) {
  int calls = 0;
  const auto f = [&](const std::vector<double>& x) {
    ++calls;
    return (x[0] - 100.0) * (x[0] - 100.0);
  };
  const SearchResult budget = compass_search({{"x", 0.0, -1000.0, 1000.0, 1.0, 0.01}}, f, 7);
  EXPECT_EQ(budget.evaluations, 7);
  EXPECT_EQ(calls, 7);
  EXPECT_FALSE(budget.converged);
  EXPECT_FALSE(budget.stopped);

  std::atomic<bool> stop{false};
  calls = 0;
  const SearchResult stopped = compass_search({{"x", 0.0, -1000.0, 1000.0, 1.0, 0.01}}, f, 1000, &stop,
                                              [&](const SearchProgress& p) { stop.store(p.evaluations == 3); });
  EXPECT_EQ(stopped.evaluations, 3);
  EXPECT_TRUE(stopped.stopped);
  EXPECT_DOUBLE_EQ(stopped.best[0], 2.0);  // 0 -> 1 -> 2: the best of three
}

// An objective that no parameter moves (issue 48: every simulated cell detected whatever the
// level) is said to be flat, not an optimum found; one that moves anywhere is not flat.
TEST(CompassSearch, SaysWhenTheObjectiveIsFlat) {
  const auto constant = [](const std::vector<double>&) { return 0.75; };
  const SearchResult flat = compass_search({{"x", 0.0, -5.0, 5.0, 1.0, 0.1}, {"y", 1.0, 0.0, 2.0, 0.5, 0.1}}, constant, 500);
  EXPECT_TRUE(flat.flat);
  EXPECT_GT(flat.evaluations, 2);
  EXPECT_DOUBLE_EQ(flat.best[0], 0.0);  // where it started
  EXPECT_DOUBLE_EQ(flat.best[1], 1.0);
  EXPECT_DOUBLE_EQ(flat.objective, 0.75);

  // Flat but for one corner the search visits: not flat.
  const auto almost = [](const std::vector<double>& x) { return x[0] <= -4.0 ? 0.5 : 0.75; };
  EXPECT_FALSE(compass_search({{"x", 0.0, -5.0, 5.0, 4.0, 0.1}}, almost, 500).flat);
  // One evaluation says nothing about the objective's shape.
  EXPECT_FALSE(compass_search({{"x", 0.0, -5.0, 5.0, 1.0, 0.1}}, constant, 1).flat);
}

}  // namespace
}  // namespace rcsim::replay
