// GOSPA per call (c = 2 m, p = 2) between a recorded and a simulated cloud of N targets each: by
// the sparse exact assignment on the pairs closer than c (metrics::gospa, since issue 52), by the
// dense assignment on each connected component of those pairs (detail::gospa_dense_components,
// the way before) and by one assignment over all pairs (detail::gospa_full_assignment, the way
// before that). Clouds:
//   uniform  - N points per side, each side uniform over 100 m x 100 m, independently;
//   cars     - cars of 100 points (N < 100: one car of N) spread over 100 m x 100 m, each side's
//              points drawn independently over each car's 4.5 m x 1.8 m;
//   wall     - N points per side along a 100-m line within 1 m (a guard rail of background).
// Counters: the largest connected component (targets of both sides) and the number of
// components with a pair.
#include <benchmark/benchmark.h>

#include "benchmark_main.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

#include "common/rng.hpp"
#include "metrics/gospa.hpp"

namespace {

using rcsim::Vec2;

enum class Cloud { uniform = 0, cars = 1, wall = 2 };

constexpr double kBenchCutoffM = 2.0;

struct CloudPair {
  std::vector<Vec2> recorded, simulated;
};

CloudPair make_clouds(Cloud kind, int n, std::uint64_t seed) {
  rcsim::Rng rng(seed, 0);
  CloudPair clouds;
  if (kind == Cloud::cars) {
    const int cars = std::max(1, n / 100);
    std::vector<Vec2> centres;
    std::vector<double> yaws;
    for (int k = 0; k < cars; ++k) {
      centres.emplace_back(rng.uniform(0, 100), rng.uniform(0, 100));
      yaws.push_back(rng.uniform(-std::numbers::pi, std::numbers::pi));
    }
    for (auto* side : {&clouds.recorded, &clouds.simulated}) {
      for (int i = 0; i < n; ++i) {
        const auto k = static_cast<std::size_t>(i % cars);
        const Vec2 local(rng.uniform(-2.25, 2.25), rng.uniform(-0.9, 0.9));
        side->push_back(centres[k] + rcsim::rotate(yaws[k], local));
      }
    }
    return clouds;
  }
  for (auto* side : {&clouds.recorded, &clouds.simulated}) {
    for (int i = 0; i < n; ++i) {
      side->push_back(kind == Cloud::uniform ? Vec2(rng.uniform(0, 100), rng.uniform(0, 100))
                                             : Vec2(rng.uniform(0, 100), rng.uniform(0, 1)));
    }
  }
  return clouds;
}

// The largest connected component of the pairs closer than c (all pairs tested: setup, untimed),
// and how many components hold a pair.
std::pair<int, int> bench_components(const CloudPair& clouds, double c) {
  const int n_x = static_cast<int>(clouds.recorded.size()), n = n_x + static_cast<int>(clouds.simulated.size());
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (int i = 0; i < n_x; ++i) {
    for (std::size_t j = 0; j < clouds.simulated.size(); ++j) {
      if ((clouds.recorded[i] - clouds.simulated[j]).norm() < c) parent[root(i)] = root(n_x + static_cast<int>(j));
    }
  }
  std::vector<int> size(static_cast<std::size_t>(n), 0);
  for (int v = 0; v < n; ++v) ++size[root(v)];
  const int largest = n == 0 ? 0 : *std::max_element(size.begin(), size.end());
  const auto with_pair = static_cast<int>(std::count_if(size.begin(), size.end(), [](int s) { return s >= 2; }));
  return {largest, with_pair};
}

enum class Way { sparse, dense_components, full };

template <Way kWay>
void BM_Gospa(benchmark::State& state) {
  const auto kind = static_cast<Cloud>(state.range(0));
  const auto n = static_cast<int>(state.range(1));
  const CloudPair clouds = make_clouds(kind, n, 1);
  const rcsim::metrics::GospaParameters parameters{kBenchCutoffM, 2.0};
  double gospa_m = 0.0;
  for (auto _ : state) {
    const auto r = kWay == Way::full ? rcsim::metrics::detail::gospa_full_assignment(clouds.recorded, clouds.simulated, parameters)
                   : kWay == Way::dense_components
                       ? rcsim::metrics::detail::gospa_dense_components(clouds.recorded, clouds.simulated, parameters)
                       : rcsim::metrics::gospa(clouds.recorded, clouds.simulated, parameters);
    gospa_m = r.gospa_m;
    // Not DoNotOptimize(gospa_m): Google Benchmark 1.7's "+m,r" on a double breaks it under GCC.
    benchmark::DoNotOptimize(r.simulated_of_recorded.data());
    benchmark::ClobberMemory();
  }
  const auto [largest, components] = bench_components(clouds, kBenchCutoffM);
  state.counters["gospa_m"] = gospa_m;
  state.counters["largest_component"] = largest;
  state.counters["components"] = components;
  state.SetLabel(kind == Cloud::uniform ? "uniform" : kind == Cloud::cars ? "cars" : "wall");
}

void gospa_cases(benchmark::internal::Benchmark* b) {
  for (const int kind : {0, 1, 2}) {
    for (const int n : {5, 20, 200, 2000}) b->Args({kind, n});
  }
}

BENCHMARK(BM_Gospa<Way::sparse>)->Name("BM_GospaSparse")->Apply(gospa_cases)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Gospa<Way::dense_components>)->Name("BM_GospaByComponents")->Apply(gospa_cases)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Gospa<Way::full>)->Name("BM_GospaFullAssignment")->Apply(gospa_cases)->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  return rcsim::bench_tools::run_benchmark_main(
      argc, argv, "rcsim_bench_gospa",
      "GOSPA per call (c = 2 m, p = 2) between two clouds of N targets each (arguments: cloud, N; cloud 0 uniform "
      "over 100 m x 100 m, 1 cars of 100 points, 2 a 100-m wall 1 m wide): the sparse exact assignment (BM_GospaSparse), "
      "the dense one per connected component (BM_GospaByComponents) and one over all pairs (BM_GospaFullAssignment).");
}
