// metrics::gospa by the sparse exact assignment against the dense assignment on each connected
// component (detail::gospa_dense_components, the way before issue 52): the GOSPA value, its parts
// and OSPA to 1e-9, and the very same pairs wherever the optimum is unique; where ties make it
// not unique, the same cost in every connected component of the pairs closer than c.
#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <numeric>
#include <set>

#include "common/rng.hpp"
#include "metrics/gospa.hpp"

namespace rcsim::metrics {
namespace {

struct Clouds {
  std::vector<Vec2> x, y;
};

// Each connected component's cost Σ d^p + c^p/2 per unassigned target, by the component's
// smallest node (recorded i is node i, simulated j node |X| + j).
std::vector<double> component_costs(const Clouds& k, const GospaParameters& g, const GospaResult& r) {
  const int n_x = static_cast<int>(k.x.size()), n = n_x + static_cast<int>(k.y.size());
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) v = parent[static_cast<std::size_t>(v)];
    return v;
  };
  for (int i = 0; i < n_x; ++i) {
    for (std::size_t j = 0; j < k.y.size(); ++j) {
      if ((k.x[static_cast<std::size_t>(i)] - k.y[j]).norm() < g.cutoff_m) {
        const int a = root(i), b = root(n_x + static_cast<int>(j));
        parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
      }
    }
  }
  const double half_c_p = 0.5 * std::pow(g.cutoff_m, g.order_p);
  std::vector<double> cost(static_cast<std::size_t>(n), 0.0);
  std::vector<char> assigned_y(k.y.size(), 0);
  for (int i = 0; i < n_x; ++i) {
    const int j = r.simulated_of_recorded[static_cast<std::size_t>(i)];
    if (j >= 0) assigned_y[static_cast<std::size_t>(j)] = 1;
    cost[static_cast<std::size_t>(root(i))] +=
        j >= 0 ? std::pow((k.x[static_cast<std::size_t>(i)] - k.y[static_cast<std::size_t>(j)]).norm(), g.order_p)
               : half_c_p;
  }
  for (std::size_t j = 0; j < k.y.size(); ++j) {
    if (!assigned_y[j]) cost[static_cast<std::size_t>(root(n_x + static_cast<int>(j)))] += half_c_p;
  }
  return cost;
}

// GOSPA and OSPA to 1e-9 always. The same pairs: the decomposition too, bit for bit. Other pairs
// (ties: equal-cost optima, possibly of different numbers of pairs, so of other parts): the same
// cost in every connected component. Returns whether the pairs are the very same.
bool expect_same_as_dense(const Clouds& k, const GospaParameters& g) {
  const GospaResult sparse = gospa(k.x, k.y, g);
  const GospaResult dense = detail::gospa_dense_components(k.x, k.y, g);
  EXPECT_NEAR(sparse.gospa_m, dense.gospa_m, 1e-9);
  EXPECT_NEAR(sparse.ospa_m, dense.ospa_m, 1e-9);
  // A valid assignment: distinct partners, each closer than c.
  std::set<int> partners;
  for (std::size_t i = 0; i < k.x.size(); ++i) {
    const int j = sparse.simulated_of_recorded[i];
    if (j < 0) continue;
    EXPECT_TRUE(partners.insert(j).second);
    EXPECT_LT((k.x[i] - k.y[static_cast<std::size_t>(j)]).norm(), g.cutoff_m);
  }
  EXPECT_EQ(static_cast<int>(partners.size()), sparse.assigned);
  if (sparse.simulated_of_recorded == dense.simulated_of_recorded) {
    EXPECT_EQ(sparse.assigned, dense.assigned);
    EXPECT_EQ(sparse.missed, dense.missed);
    EXPECT_EQ(sparse.false_targets, dense.false_targets);
    EXPECT_EQ(sparse.gospa_m, dense.gospa_m);
    EXPECT_EQ(sparse.localisation_mp, dense.localisation_mp);
    EXPECT_EQ(sparse.missed_mp, dense.missed_mp);
    EXPECT_EQ(sparse.false_mp, dense.false_mp);
    EXPECT_EQ(sparse.ospa_m, dense.ospa_m);
    return true;
  }
  const std::vector<double> a = component_costs(k, g, sparse), b = component_costs(k, g, dense);
  for (std::size_t v = 0; v < a.size(); ++v) EXPECT_NEAR(a[v], b[v], 1e-9) << "component of node " << v;
  return false;
}

std::vector<Vec2> uniform_cloud(Rng& rng, int n, double side_m) {
  std::vector<Vec2> points;
  for (int i = 0; i < n; ++i) points.emplace_back(rng.uniform(0, side_m), rng.uniform(0, side_m));
  return points;
}

// n points around n / 20 + 1 centres, 1 m spread (cars and walls of an imaging radar).
std::vector<Vec2> clustered_cloud(Rng& rng, int n, double side_m) {
  std::vector<Vec2> centres = uniform_cloud(rng, 1 + n / 20, side_m), points;
  for (int i = 0; i < n; ++i) {
    const Vec2& centre = centres[static_cast<std::size_t>(rng.uniform01() * static_cast<double>(centres.size()))];
    points.emplace_back(centre.x() + rng.normal(), centre.y() + rng.normal());
  }
  return points;
}

// A model against a recording: each recorded point kept with probability 0.85 and moved by noise
// of sigma_m, plus extra points.
std::vector<Vec2> perturbed(Rng& rng, const std::vector<Vec2>& x, double sigma_m, std::vector<Vec2> extra) {
  std::vector<Vec2> y;
  for (const Vec2& v : x) {
    if (rng.uniform01() < 0.85) y.emplace_back(v.x() + sigma_m * rng.normal(), v.y() + sigma_m * rng.normal());
  }
  y.insert(y.end(), extra.begin(), extra.end());
  return y;
}

TEST(GospaSparse, EqualsTheDenseComponentsOnRandomClouds) {
  Rng rng(5200, 0);
  int trials = 0, same_pairs = 0;
  for (const double c : {0.5, 2.0, 5.0}) {
    for (const double p : {1.0, 2.0, 3.0}) {
      for (int cloud = 0; cloud < 48; ++cloud) {
        const double side_m = std::array{3.0, 15.0, 60.0, 200.0}[static_cast<std::size_t>(cloud % 4)];
        const bool clustered = cloud % 8 >= 4;
        const int n_x = static_cast<int>(rng.uniform01() * 150), n_y = static_cast<int>(rng.uniform01() * 150);
        Clouds k;
        k.x = clustered ? clustered_cloud(rng, n_x, side_m) : uniform_cloud(rng, n_x, side_m);
        if (cloud % 3 == 0) {
          k.y = clustered ? clustered_cloud(rng, n_y, side_m) : uniform_cloud(rng, n_y, side_m);
        } else {
          k.y = perturbed(rng, k.x, 0.3 * c, uniform_cloud(rng, n_y / 4, side_m));
        }
        SCOPED_TRACE(::testing::Message() << "c " << c << " p " << p << " cloud " << cloud << ": " << k.x.size() << " x "
                                          << k.y.size());
        same_pairs += expect_same_as_dense(k, {c, p}) ? 1 : 0;
        ++trials;
      }
    }
  }
  EXPECT_EQ(trials, 432);
  EXPECT_EQ(same_pairs, trials);  // continuous coordinates: unique optima, the very same pairs
}

TEST(GospaSparse, ImagingRadarSizedFrames) {
  // 2,000 recorded targets in cars and walls, the model's 2,000 near them: components of
  // hundreds of targets, as on the Astyx frames.
  Rng rng(7, 0);
  for (int frame = 0; frame < 3; ++frame) {
    Clouds k;
    k.x = clustered_cloud(rng, 2000, 100.0);
    k.y = perturbed(rng, k.x, 0.4, clustered_cloud(rng, 300, 100.0));
    k.y.resize(std::min<std::size_t>(k.y.size(), 2000));
    SCOPED_TRACE(::testing::Message() << "frame " << frame);
    EXPECT_TRUE(expect_same_as_dense(k, {2.0, 2.0}));
  }
}

TEST(GospaSparse, AllWithinTheCutoff) {
  Rng rng(1, 0);
  for (int trial = 0; trial < 20; ++trial) {
    Clouds k{uniform_cloud(rng, 1 + trial * 3, 1.0), uniform_cloud(rng, 40 - trial, 1.0)};  // every pair < sqrt(2)
    SCOPED_TRACE(::testing::Message() << "trial " << trial);
    EXPECT_TRUE(expect_same_as_dense(k, {2.0, 2.0}));
    EXPECT_TRUE(expect_same_as_dense(k, {1.5, 1.0}));
  }
}

TEST(GospaSparse, NoneWithinTheCutoff) {
  // Two lattices 3 m apart, offset by 1.5 m: every pair at least 2.12 m, c = 2.
  Clouds k;
  for (int i = 0; i < 30; ++i) {
    for (int j = 0; j < 30; ++j) {
      k.x.emplace_back(3.0 * i, 3.0 * j);
      k.y.emplace_back(3.0 * i + 1.5, 3.0 * j + 1.5);
    }
  }
  const GospaResult r = gospa(k.x, k.y, {2.0, 2.0});
  EXPECT_EQ(r.assigned, 0);
  EXPECT_EQ(r.gospa_m, std::sqrt(2.0 * 1800));
  EXPECT_TRUE(expect_same_as_dense(k, {2.0, 2.0}));
}

TEST(GospaSparse, TiesOnALattice) {
  // Integer lattices: many pairs at equal distances, equal-cost optima. The same GOSPA and OSPA
  // and the same cost in each component; the pairs, and so the parts, may differ (at c = 2,
  // p = 1 a pair at 1 and one at 1 cost what a pair at 1 and two targets left cost).
  Rng rng(3, 0);
  for (int trial = 0; trial < 40; ++trial) {
    Clouds k;
    const int side = 4 + trial % 9;
    for (int i = 0; i < side * side; ++i) {
      if (rng.uniform01() < 0.7) k.x.emplace_back(i % side, i / side);
      if (rng.uniform01() < 0.7) k.y.emplace_back(i % side + (trial % 2 == 0 ? 0.5 : 0.0), i / side);
    }
    SCOPED_TRACE(::testing::Message() << "trial " << trial);
    for (const GospaParameters g : {GospaParameters{1.2, 2.0}, GospaParameters{2.0, 1.0}, GospaParameters{3.0, 2.0}}) {
      expect_same_as_dense(k, g);
    }
  }
}

TEST(GospaSparse, PairsAtExactlyTheCutoffAreNoPairs) {
  // c = 5: pairs at exactly c (integer 3-4-5 triangles, exact in binary) and, for every other
  // recorded target, one just inside.
  Clouds k;
  for (int i = 0; i < 40; ++i) {
    k.x.emplace_back(20.0 * i, 0.0);
    k.y.emplace_back(20.0 * i + 3.0, 4.0);                    // at c exactly
    k.y.emplace_back(20.0 * i - 5.0, 0.0);                    // at c exactly
    if (i % 2 == 0) k.y.emplace_back(20.0 * i, 5.0 - 1e-9);   // just inside
  }
  for (const double p : {1.0, 2.0}) {
    const GospaResult r = gospa(k.x, k.y, {5.0, p});
    EXPECT_EQ(r.assigned, 20);
    EXPECT_TRUE(expect_same_as_dense(k, {5.0, p}));
  }
}

TEST(GospaSparse, EmptySidesAndOneByOne) {
  const std::vector<Vec2> three{Vec2(0, 0), Vec2(0.1, 0), Vec2(50, 50)};
  EXPECT_TRUE(expect_same_as_dense({three, {}}, {2.0, 2.0}));
  EXPECT_TRUE(expect_same_as_dense({{}, three}, {2.0, 2.0}));
  EXPECT_TRUE(expect_same_as_dense({{}, {}}, {2.0, 2.0}));
  EXPECT_TRUE(expect_same_as_dense({{Vec2(0, 0)}, {Vec2(0.6, 0.8)}}, {2.0, 2.0}));
  EXPECT_TRUE(expect_same_as_dense({{Vec2(0, 0)}, {Vec2(3, 0)}}, {2.0, 2.0}));
  const GospaResult one = gospa({Vec2(0, 0)}, {Vec2(0.6, 0.8)}, {2.0, 2.0});
  EXPECT_EQ(one.simulated_of_recorded, (std::vector<int>{0}));
  EXPECT_NEAR(one.gospa_m, 1.0, 1e-15);
}

}  // namespace
}  // namespace rcsim::metrics
