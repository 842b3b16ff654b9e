#include "metrics/gospa.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <gtest/gtest.h>
#include <limits>

#include "common/rng.hpp"

namespace rcsim::metrics {
namespace {

const GospaParameters kC2P2{2.0, 2.0};

TEST(Gospa, BothEmptyIsZero) {
  const GospaResult r = gospa({}, {}, kC2P2);
  EXPECT_EQ(r.gospa_m, 0.0);
  EXPECT_EQ(r.ospa_m, 0.0);
}

TEST(Gospa, OneMissedTargetCostsHalfTheCutoffPower) {
  // (c^p / 2)^(1/p) = (4/2)^(1/2) = sqrt(2); OSPA penalises the cardinality error with c.
  const GospaResult r = gospa({Vec2(1, 2)}, {}, kC2P2);
  EXPECT_DOUBLE_EQ(r.gospa_m, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(r.missed_mp, 2.0);
  EXPECT_EQ(r.missed, 1);
  EXPECT_EQ(r.false_targets, 0);
  EXPECT_DOUBLE_EQ(r.ospa_m, 2.0);
}

TEST(Gospa, OneFalseTargetIsSymmetric) {
  const GospaResult r = gospa({}, {Vec2(1, 2)}, kC2P2);
  EXPECT_DOUBLE_EQ(r.gospa_m, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(r.false_mp, 2.0);
  EXPECT_EQ(r.false_targets, 1);
}

TEST(Gospa, CloseAssignedPairCostsItsDistance) {
  const GospaResult r = gospa({Vec2(0, 0)}, {Vec2(0.6, 0.8)}, kC2P2);
  EXPECT_NEAR(r.gospa_m, 1.0, 1e-12);
  EXPECT_NEAR(r.localisation_mp, 1.0, 1e-12);
  EXPECT_EQ(r.simulated_of_recorded, (std::vector<int>{0}));
  EXPECT_NEAR(r.ospa_m, 1.0, 1e-12);
}

TEST(Gospa, PairBeyondTheCutoffCountsAsMissedPlusFalse) {
  // d = 3 >= c = 2: sqrt(2 + 2) = 2; OSPA min(3, 2) = 2.
  const GospaResult r = gospa({Vec2(0, 0)}, {Vec2(3, 0)}, kC2P2);
  EXPECT_DOUBLE_EQ(r.gospa_m, 2.0);
  EXPECT_EQ(r.assigned, 0);
  EXPECT_EQ(r.missed, 1);
  EXPECT_EQ(r.false_targets, 1);
  EXPECT_EQ(r.simulated_of_recorded, (std::vector<int>{-1}));
  EXPECT_DOUBLE_EQ(r.ospa_m, 2.0);
}

TEST(Gospa, OrderOneHandCase) {
  // p = 1, c = 2: one pair at 0.5 and one missed target: 0.5 + 2/2 = 1.5.
  // OSPA: (0.5 + 2 * (2 - 1)) / 2 = 1.25.
  const GospaResult r = gospa({Vec2(0, 0), Vec2(10, 0)}, {Vec2(0.5, 0)}, {2.0, 1.0});
  EXPECT_DOUBLE_EQ(r.gospa_m, 1.5);
  EXPECT_DOUBLE_EQ(r.localisation_mp, 0.5);
  EXPECT_DOUBLE_EQ(r.missed_mp, 1.0);
  EXPECT_DOUBLE_EQ(r.ospa_m, 1.25);
}

// GOSPA by its definition: the minimum over every partial assignment of pairs closer than c.
double brute_force_gospa(const std::vector<Vec2>& x, const std::vector<Vec2>& y, double c, double p) {
  double best = std::numeric_limits<double>::infinity();
  std::vector<char> y_used(y.size(), 0);
  std::function<void(std::size_t, double, int)> visit = [&](std::size_t i, double sum, int pairs) {
    if (i == x.size()) {
      const double unassigned = static_cast<double>(x.size() + y.size()) - 2.0 * pairs;
      best = std::min(best, sum + std::pow(c, p) / 2.0 * unassigned);
      return;
    }
    visit(i + 1, sum, pairs);  // x_i unassigned
    for (std::size_t j = 0; j < y.size(); ++j) {
      const double d = (x[i] - y[j]).norm();
      if (y_used[j] || d >= c) continue;
      y_used[j] = 1;
      visit(i + 1, sum + std::pow(d, p), pairs + 1);
      y_used[j] = 0;
    }
  };
  visit(0, 0.0, 0);
  return std::pow(best, 1.0 / p);
}

TEST(Gospa, EqualsItsDefinitionOnRandomSetsAndPartsAddUp) {
  Rng rng(7, 0);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<Vec2> x, y;
    const int n_x = static_cast<int>(rng.uniform01() * 5), n_y = static_cast<int>(rng.uniform01() * 5);
    for (int i = 0; i < n_x; ++i) x.emplace_back(rng.uniform01() * 4, rng.uniform01() * 4);
    for (int i = 0; i < n_y; ++i) y.emplace_back(rng.uniform01() * 4, rng.uniform01() * 4);
    const double p = trial % 3 == 0 ? 1.0 : trial % 3 == 1 ? 2.0 : 3.0;
    const GospaParameters parameters{1.5, p};
    const GospaResult r = gospa(x, y, parameters);
    ASSERT_NEAR(r.gospa_m, brute_force_gospa(x, y, 1.5, p), 1e-9) << "trial " << trial;
    ASSERT_NEAR(std::pow(r.gospa_m, p), r.localisation_mp + r.missed_mp + r.false_mp, 1e-9);
    ASSERT_EQ(r.assigned + r.missed, n_x);
    ASSERT_EQ(r.assigned + r.false_targets, n_y);
    ASSERT_LE(r.ospa_m, 1.5 + 1e-12);
  }
}

TEST(Gospa, RefusesBadParameters) {
  EXPECT_THROW(gospa({}, {}, {0.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(gospa({}, {}, {1.0, 0.5}), std::invalid_argument);
}

}  // namespace
}  // namespace rcsim::metrics
