// One hour of a three-lane road with about 200 vehicles (a 5 km ring at 13.4 vehicles per km and
// lane, every vehicle driven by IDM + MOBIL), and the scene text it makes.
#include <benchmark/benchmark.h>

#include "benchmark_main.hpp"

#include "common/rng.hpp"
#include "traffic/scene_writer.hpp"
#include "traffic/traffic_sim.hpp"

namespace {

rcsim::traffic::TrafficConfig hour_of_three_lanes() {
  rcsim::traffic::TrafficConfig c;
  c.layout = rcsim::traffic::Layout::Ring;
  c.lanes = 3;
  c.length_m = 5000.0;
  c.density_vpkm = 13.4;  // 201 vehicles
  c.duration_s = 3600.0;
  c.warmup_s = 30.0;
  c.sample_interval_s = 0.5;
  return rcsim::traffic::resolve_traffic_config(c, ".");
}

void BM_TrafficHourThreeLanes(benchmark::State& state) {
  const auto config = hour_of_three_lanes();
  std::size_t bytes = 0;
  std::size_t vehicles = 0;
  for (auto _ : state) {
    rcsim::Rng rng(config.seed);
    rcsim::traffic::TrafficSimulation sim(config, rng);
    sim.run(rng);
    const std::string text = rcsim::traffic::scene_json(sim);
    bytes = text.size();
    vehicles = sim.vehicles().size();
    benchmark::DoNotOptimize(text.data());
  }
  state.counters["vehicles"] = static_cast<double>(vehicles);
  state.counters["scene_MB"] = static_cast<double>(bytes) / 1e6;
}
BENCHMARK(BM_TrafficHourThreeLanes)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

int main(int argc, char** argv) {
  return rcsim::bench_tools::run_benchmark_main(argc, argv, "rcsim_bench_traffic",
                                                "One hour of a three-lane road with about 200 vehicles (IDM + MOBIL), and the scene text it makes.");
}
