#include "metrics/gospa.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <gtest/gtest.h>
#include <limits>
#include <set>

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

// The decomposition by components against one assignment over all pairs
// (detail::gospa_full_assignment, the former computation).

// n points: uniform over a square of side_m, or around clusters of 1 m spread.
std::vector<Vec2> gospa_test_cloud(Rng& rng, int n, double side_m, bool clustered) {
  std::vector<Vec2> points;
  std::vector<Vec2> centres;
  for (int k = 0; k < 1 + n / 10; ++k) centres.emplace_back(rng.uniform(0, side_m), rng.uniform(0, side_m));
  for (int i = 0; i < n; ++i) {
    if (clustered) {
      const Vec2& centre = centres[static_cast<std::size_t>(rng.uniform01() * static_cast<double>(centres.size()))];
      points.emplace_back(centre.x() + rng.normal(), centre.y() + rng.normal());
    } else {
      points.emplace_back(rng.uniform(0, side_m), rng.uniform(0, side_m));
    }
  }
  return points;
}

// A valid assignment: distinct partners, each closer than c; its parts add up to what it claims.
void expect_valid_gospa_assignment(const std::vector<Vec2>& x, const std::vector<Vec2>& y, const GospaParameters& g,
                                   const GospaResult& r) {
  ASSERT_EQ(r.simulated_of_recorded.size(), x.size());
  std::set<int> partners;
  double localisation_mp = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const int j = r.simulated_of_recorded[i];
    if (j < 0) continue;
    ASSERT_LT(j, static_cast<int>(y.size()));
    ASSERT_TRUE(partners.insert(j).second) << "simulated " << j << " assigned twice";
    const double d = (x[i] - y[static_cast<std::size_t>(j)]).norm();
    ASSERT_LT(d, g.cutoff_m);
    localisation_mp += std::pow(d, g.order_p);
  }
  ASSERT_EQ(static_cast<int>(partners.size()), r.assigned);
  ASSERT_NEAR(r.localisation_mp, localisation_mp, 1e-12 * (1.0 + localisation_mp));
  ASSERT_EQ(r.missed, static_cast<int>(x.size()) - r.assigned);
  ASSERT_EQ(r.false_targets, static_cast<int>(y.size()) - r.assigned);
}

// Both results: the same counts, the same total cost (gospa_m^p) and parts, the same OSPA, up to
// the rounding of sums taken over another equal-cost assignment; bit for bit when the
// assignments agree (and OSPA's sum then too when |X| <= |Y|, the order of its terms being known).
void expect_same_gospa(const GospaResult& by_components, const GospaResult& full, std::size_t n_x, std::size_t n_y,
                       double p) {
  const auto near = [](double a, double b) { return std::abs(a - b) <= 1e-12 * (1.0 + std::abs(b)); };
  ASSERT_EQ(by_components.assigned, full.assigned);
  ASSERT_EQ(by_components.missed, full.missed);
  ASSERT_EQ(by_components.false_targets, full.false_targets);
  ASSERT_TRUE(near(std::pow(by_components.gospa_m, p), std::pow(full.gospa_m, p)));
  ASSERT_TRUE(near(by_components.gospa_m, full.gospa_m)) << by_components.gospa_m << " " << full.gospa_m;
  ASSERT_TRUE(near(by_components.localisation_mp, full.localisation_mp));
  ASSERT_EQ(by_components.missed_mp, full.missed_mp);
  ASSERT_EQ(by_components.false_mp, full.false_mp);
  ASSERT_TRUE(near(by_components.ospa_m, full.ospa_m)) << by_components.ospa_m << " " << full.ospa_m;
  if (by_components.simulated_of_recorded == full.simulated_of_recorded) {
    ASSERT_EQ(by_components.gospa_m, full.gospa_m);
    ASSERT_EQ(by_components.localisation_mp, full.localisation_mp);
    if (n_x <= n_y) {
      ASSERT_EQ(by_components.ospa_m, full.ospa_m);
    }
  }
}

TEST(GospaByComponents, EqualsTheFullAssignmentOnRandomClouds) {
  Rng rng(2024, 0);
  int trials = 0, same_assignment = 0, grid_sized = 0;
  for (const double c : {0.5, 2.0, 5.0}) {
    for (const double p : {1.0, 2.0}) {
      for (int cloud = 0; cloud < 60; ++cloud) {
        // Densities from a few points in 150 m x 150 m to 60 in 2 m x 2 m, uniform or clustered;
        // the simulated cloud either independent or the recorded one moved by noise, some
        // dropped and some added (as a model against a recording).
        const double side_m = std::array{2.0, 8.0, 30.0, 150.0}[static_cast<std::size_t>(cloud % 4)];
        const bool clustered = cloud % 8 >= 4;
        const int n_x = static_cast<int>(rng.uniform01() * 61), n_y = static_cast<int>(rng.uniform01() * 61);
        const std::vector<Vec2> x = gospa_test_cloud(rng, n_x, side_m, clustered);
        std::vector<Vec2> y;
        if (cloud % 3 == 0) {
          y = gospa_test_cloud(rng, n_y, side_m, clustered);
        } else {
          for (const Vec2& v : x) {
            if (rng.uniform01() < 0.8) y.emplace_back(v.x() + 0.3 * c * rng.normal(), v.y() + 0.3 * c * rng.normal());
          }
          for (const Vec2& v : gospa_test_cloud(rng, n_y / 4, side_m, clustered)) y.push_back(v);
        }
        const GospaParameters g{c, p};
        const GospaResult r = gospa(x, y, g);
        const GospaResult full = detail::gospa_full_assignment(x, y, g);
        SCOPED_TRACE(::testing::Message() << "c " << c << " p " << p << " cloud " << cloud << ": " << x.size()
                                          << " x " << y.size());
        expect_valid_gospa_assignment(x, y, g, r);
        expect_same_gospa(r, full, x.size(), y.size(), p);
        ++trials;
        same_assignment += r.simulated_of_recorded == full.simulated_of_recorded ? 1 : 0;
        grid_sized += x.size() * y.size() > 400 ? 1 : 0;
      }
    }
  }
  EXPECT_EQ(trials, 360);
  EXPECT_GT(grid_sized, 100);  // the grid's path (more than 20 x 20 pairs) taken often
  // Random clouds have no equal-cost optima: the very same assignment nearly always.
  EXPECT_GE(same_assignment, trials - 3);
}

TEST(GospaByComponents, LargeDenseCloudsEqualTheFullAssignment) {
  Rng rng(11, 0);
  for (const bool clustered : {false, true}) {
    const std::vector<Vec2> x = gospa_test_cloud(rng, 400, 60.0, clustered);
    std::vector<Vec2> y;
    for (const Vec2& v : x) {
      if (rng.uniform01() < 0.9) y.emplace_back(v.x() + 0.5 * rng.normal(), v.y() + 0.5 * rng.normal());
    }
    for (const GospaParameters g : {GospaParameters{2.0, 2.0}, GospaParameters{0.5, 1.0}}) {
      const GospaResult r = gospa(x, y, g);
      expect_valid_gospa_assignment(x, y, g, r);
      expect_same_gospa(r, detail::gospa_full_assignment(x, y, g), x.size(), y.size(), g.order_p);
    }
  }
}

TEST(GospaByComponents, TwoFarApartGroupsByHand) {
  // c = 2, p = 2. Near the origin: x0 = (0, 0), x1 = (1, 0) against (0.5, 0), (1.2, 0): straight
  // 0.25 + 0.04 = 0.29 beats crossed 1.44 + 0.25. 100 m away: x2 = (100, 0) takes (100, 1) at
  // 1; (103, 0) lies 3 m away: false, c^2/2 = 2. GOSPA^2 = 0.29 + 1 + 2 = 3.29.
  // OSPA: (0.29 + 1 + c^2 (4 - 3)) / 4 = 5.29 / 4, OSPA = 2.3 / 2 = 1.15.
  const std::vector<Vec2> x{Vec2(0, 0), Vec2(1, 0), Vec2(100, 0)};
  const std::vector<Vec2> y{Vec2(0.5, 0), Vec2(1.2, 0), Vec2(100, 1), Vec2(103, 0)};
  const GospaResult r = gospa(x, y, kC2P2);
  EXPECT_NEAR(r.gospa_m, std::sqrt(3.29), 1e-12);
  EXPECT_NEAR(r.localisation_mp, 1.29, 1e-12);
  EXPECT_EQ(r.simulated_of_recorded, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(r.assigned, 3);
  EXPECT_EQ(r.missed, 0);
  EXPECT_EQ(r.false_targets, 1);
  EXPECT_DOUBLE_EQ(r.false_mp, 2.0);
  EXPECT_NEAR(r.ospa_m, 1.15, 1e-12);
  // And with the sides swapped: more recorded than simulated.
  const GospaResult swapped = gospa(y, x, kC2P2);
  EXPECT_NEAR(swapped.gospa_m, std::sqrt(3.29), 1e-12);
  EXPECT_EQ(swapped.simulated_of_recorded, (std::vector<int>{0, 1, 2, -1}));
  EXPECT_NEAR(swapped.ospa_m, 1.15, 1e-12);
}

TEST(GospaByComponents, AllPairsAtOrBeyondTheCutoff) {
  // 30 recorded at (3i, 0), 20 simulated at (3i, 2): each pair's distance is c = 2 exactly or
  // more, and a pair at c is no pair. 600 pairs: the grid finds the candidates.
  // GOSPA^2 = c^2/2 (30 + 20) = 100; OSPA^2 = (20 c^2 + c^2 (30 - 20)) / 30 = c^2.
  std::vector<Vec2> x, y;
  for (int i = 0; i < 30; ++i) x.emplace_back(3.0 * i, 0.0);
  for (int i = 0; i < 20; ++i) y.emplace_back(3.0 * i, 2.0);
  for (const bool swap : {false, true}) {
    const GospaResult r = swap ? gospa(y, x, kC2P2) : gospa(x, y, kC2P2);
    EXPECT_EQ(r.gospa_m, 10.0);
    EXPECT_EQ(r.ospa_m, 2.0);
    EXPECT_EQ(r.assigned, 0);
    EXPECT_EQ(r.missed + r.false_targets, 50);
    EXPECT_EQ(r.localisation_mp, 0.0);
    EXPECT_EQ(r.simulated_of_recorded, std::vector<int>(swap ? 20 : 30, -1));
  }
}

TEST(GospaByComponents, EmptySides) {
  // c = 2, p = 1: three targets on one side only: GOSPA = 3 c/2 = 3, OSPA = c.
  const std::vector<Vec2> three{Vec2(0, 0), Vec2(0.1, 0), Vec2(50, 50)};
  const GospaParameters g{2.0, 1.0};
  const GospaResult missed = gospa(three, {}, g);
  EXPECT_EQ(missed.gospa_m, 3.0);
  EXPECT_EQ(missed.missed, 3);
  EXPECT_EQ(missed.ospa_m, 2.0);
  EXPECT_EQ(missed.simulated_of_recorded, (std::vector<int>{-1, -1, -1}));
  const GospaResult false_only = gospa({}, three, g);
  EXPECT_EQ(false_only.gospa_m, 3.0);
  EXPECT_EQ(false_only.false_targets, 3);
  EXPECT_EQ(false_only.ospa_m, 2.0);
  EXPECT_TRUE(false_only.simulated_of_recorded.empty());
}

TEST(GospaByComponents, CoordinatesNotFiniteAsBefore) {
  // A NaN is refused as the full assignment refuses it; an infinite coordinate is far from all.
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(gospa({Vec2(nan, 0)}, {Vec2(0, 0)}, kC2P2), std::invalid_argument);
  const std::vector<Vec2> x{Vec2(inf, 0), Vec2(0, 0)}, y{Vec2(0.5, 0)};
  const GospaResult r = gospa(x, y, kC2P2), full = detail::gospa_full_assignment(x, y, kC2P2);
  EXPECT_EQ(r.gospa_m, full.gospa_m);
  EXPECT_EQ(r.simulated_of_recorded, (std::vector<int>{-1, 0}));
}

TEST(Gospa, RefusesBadParameters) {
  EXPECT_THROW(gospa({}, {}, {0.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(gospa({}, {}, {1.0, 0.5}), std::invalid_argument);
}

}  // namespace
}  // namespace rcsim::metrics
