// One sensor cycle for 1, 10 and 100 vehicles in view (paper Fig. 13, all stages, noise on),
// with the heap allocations per cycle counted.
#include <benchmark/benchmark.h>

#include "benchmark_main.hpp"

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <new>

#include "common/angles.hpp"
#include "io/recording.hpp"
#include "model/model_library.hpp"
#include "replay/import/importer.hpp"
#include "sim/simulation.hpp"
#include "traffic/scene_writer.hpp"
#include "traffic/traffic_sim.hpp"

namespace {
std::atomic<long long> g_allocations{0};
}  // namespace

#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace rcsim {
namespace {

// Cars spread over the sensor's view field between 6 and 26 m at various headings, standing still
// (speed_mps = 0) or driving slowly at 0.5..2.5 m/s.
Scene scene_with_cars(int cars, bool effects, bool moving) {
  static const ModelLibrary library = ModelLibrary::builtin();
  Scene scene;
  scene.duration_s = 1e6;
  TrajectorySample ego;
  ego.speed_mps = 0.0;
  scene.ego = Trajectory({ego});
  MountedSensor sensor;
  sensor.id = "front";
  sensor.config = builtin_sensor_config("srr24");
  scene.sensors.push_back(sensor);
  scene.cycle_time_s = sensor.config.cycle_time_s;
  scene.effects = {effects, effects, effects};
  for (int i = 0; i < cars; ++i) {
    const double range_m = 6.0 + 20.0 * (i + 0.5) / cars;
    const double azimuth_rad = deg_to_rad(-30.0 + 60.0 * std::fmod(i * 0.618034, 1.0));
    TrajectorySample s;
    s.x_m = range_m * std::cos(azimuth_rad);
    s.y_m = range_m * std::sin(azimuth_rad);
    s.yaw_rad = kPi + 1.2 * std::sin(i);
    s.speed_mps = moving ? 0.5 + 0.5 * (i % 5) : 0.0;
    SceneObject object;
    object.id = "car" + std::to_string(i);
    object.model_name = "passenger_car";
    object.model = library.at("passenger_car");
    object.trajectory = Trajectory({s});
    scene.objects.push_back(object);
  }
  return scene;
}

void run_cycles(benchmark::State& state, bool effects) {
  // Sensor stages only, on a fixed snapshot of parked cars: the tracker reaches its steady state.
  const Scene scene = scene_with_cars(static_cast<int>(state.range(0)), effects, false);
  SimulationOptions options;
  options.seed = 1;
  Simulation sim(scene, options);
  SceneSnapshot snapshot;
  snapshot.ego = scene.ego.state_at(0.0);
  for (const auto& o : scene.objects) snapshot.objects.push_back(o.trajectory.state_at(0.0));
  snapshot.visited.assign(scene.objects.size(), 1);
  for (std::uint32_t i = 0; i < scene.objects.size(); ++i) snapshot.visited_indices.push_back(i);
  SensorCycleState cycle_state(sim.sensor_model(0), 13 * scene.objects.size(), scene.cycle_time_s, 1, 0);
  for (int k = 0; k < 50; ++k) run_sensor_cycle(sim.sensor_model(0), sim.objects(), snapshot, cycle_state);
  const long long before = g_allocations.load();
  for (auto _ : state) {
    run_sensor_cycle(sim.sensor_model(0), sim.objects(), snapshot, cycle_state);
    benchmark::DoNotOptimize(cycle_state.reported.data());
  }
  state.counters["allocs_per_cycle"] =
      benchmark::Counter(static_cast<double>(g_allocations.load() - before) / static_cast<double>(state.iterations()));
  state.counters["ideal_targets"] = static_cast<double>(cycle_state.ideal.size());
  state.counters["detections"] = static_cast<double>(cycle_state.detections.size());
  state.counters["reported"] = static_cast<double>(cycle_state.reported.size());
}

void BM_SensorCycle(benchmark::State& state) { run_cycles(state, false); }
void BM_SensorCycleAllEffects(benchmark::State& state) { run_cycles(state, true); }

// A whole scene cycle with moving cars: trajectories evaluated for every object, then the sensor
// cycle. Time loops over the first 2 s so that the cars stay in view (the tracker re-initiates
// once per loop, as after a dropout).
void BM_SceneCycle(benchmark::State& state) {
  const Scene scene = scene_with_cars(static_cast<int>(state.range(0)), false, true);
  SimulationOptions options;
  options.seed = 1;
  Simulation sim(scene, options);
  const int loop_cycles = 50;
  for (int k = 0; k < loop_cycles; ++k) sim.run_cycle(k);
  const long long before = g_allocations.load();
  long long k = 0, reported = 0, ideal = 0;
  for (auto _ : state) {
    sim.run_cycle(static_cast<int>(k++ % loop_cycles));
    reported += static_cast<long long>(sim.sensor_state(0).reported.size());
    ideal += static_cast<long long>(sim.sensor_state(0).ideal.size());
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["allocs_per_cycle"] = benchmark::Counter(static_cast<double>(g_allocations.load() - before) / n);
  state.counters["ideal_targets"] = static_cast<double>(ideal) / n;
  state.counters["reported"] = static_cast<double>(reported) / n;
}

// The broad phase (sim/culling.hpp) on the 60-second city recording (every sensor, every effect,
// all its objects): Arg(1) culling on, Arg(0) off. Cycles loop over the whole drive; the
// output is byte-identical either way (tests/sim/culling_test.cpp).
void BM_CityDriveCulling(benchmark::State& state) {
  static const ModelLibrary library = ModelLibrary::builtin();
  const Recording recording = read_recording(std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/city_drive_60s");
  const replay::ImportedScene imported = import_recording(recording, library, replay::ImportOptions{});
  const Scene scene = replay::build_scene(imported, library, recording.dir.string());
  SimulationOptions options;
  options.seed = 1;
  options.culling = state.range(0) != 0;
  Simulation timed(scene, options);
  const int cycles = timed.cycle_count();
  for (int k = 0; k < cycles; ++k) timed.run_cycle(k);  // every buffer at its largest
  const long long before = g_allocations.load();
  long long k = 0, ideal = 0;
  for (auto _ : state) {
    // Loops over the drive; the tracker sees a jump back once per loop (like a dropout).
    timed.run_cycle(static_cast<int>(k++ % cycles));
    for (std::size_t s = 0; s < timed.sensor_count(); ++s) ideal += static_cast<long long>(timed.sensor_state(s).ideal.size());
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["allocs_per_cycle"] = benchmark::Counter(static_cast<double>(g_allocations.load() - before) / n);
  state.counters["ideal_targets"] = static_cast<double>(ideal) / n;
  state.counters["objects"] = static_cast<double>(scene.objects.size());
  state.counters["sensors"] = static_cast<double>(scene.sensors.size());
}

// Dense traffic all round the sensor: 200 parked cars on a 6 m grid within 40 m of the ego in
// every direction (only those in the +-35 deg wedge can be seen). range(0): culling off (0) / on (1);
// range(1): effects (clutter, multibounce, occlusion) off (0) / on (1).
void BM_CarsAllAroundCulling(benchmark::State& state) {
  static const ModelLibrary library = ModelLibrary::builtin();
  Scene scene = scene_with_cars(0, state.range(1) != 0, false);
  int placed = 0;
  for (int i = -7; i <= 7 && placed < 200; ++i) {
    for (int j = -7; j <= 7 && placed < 200; ++j) {
      const double x_m = 6.0 * i, y_m = 5.0 * j;
      if ((i == 0 && j == 0) || std::hypot(x_m, y_m) > 40.0) continue;
      TrajectorySample s;
      s.x_m = x_m;
      s.y_m = y_m;
      s.yaw_rad = 0.7 * (i + 2 * j);
      SceneObject object;
      object.id = "car" + std::to_string(placed++);
      object.model_name = "passenger_car";
      object.model = library.at("passenger_car");
      object.trajectory = Trajectory({s});
      scene.objects.push_back(object);
    }
  }
  SimulationOptions options;
  options.seed = 1;
  options.culling = state.range(0) != 0;
  Simulation sim(scene, options);
  for (int k = 0; k < 50; ++k) sim.run_cycle(k);
  const long long before = g_allocations.load();
  long long k = 50;
  for (auto _ : state) {
    sim.run_cycle(static_cast<int>(k++ % 1000));
    benchmark::DoNotOptimize(sim.sensor_state(0).reported.data());
  }
  state.counters["allocs_per_cycle"] =
      benchmark::Counter(static_cast<double>(g_allocations.load() - before) / static_cast<double>(state.iterations()));
  state.counters["objects"] = static_cast<double>(scene.objects.size());
  state.counters["ideal_targets"] = static_cast<double>(sim.sensor_state(0).ideal.size());
}

// A 60-second scene of `rcsim traffic` (its defaults: a 4.1 km three-lane highway, 291 vehicles
// around the ego, two srr24 sensors), simulated directly rather than through a recording (which
// annotates only what is near the ego): Arg(1) culling on, Arg(0) off; the output is
// byte-identical either way (tests/sim/culling_test.cpp).
void BM_TrafficSceneCulling(benchmark::State& state) {
  static const Scene scene = [] {
    traffic::TrafficConfig config;
    config.duration_s = 60.0;
    config = traffic::resolve_traffic_config(config, ".");
    Rng rng(config.seed);
    traffic::TrafficSimulation traffic_sim(config, rng);
    traffic_sim.run(rng);
    const auto path = std::filesystem::temp_directory_path() / ("rcsim_bench_traffic_" + std::to_string(::getpid()) + ".json");
    std::ofstream(path) << traffic::scene_json(traffic_sim);
    Scene loaded = load_scene_file(path.string(), ModelLibrary::builtin());
    std::filesystem::remove(path);
    return loaded;
  }();
  SimulationOptions options;
  options.seed = 1;
  options.culling = state.range(0) != 0;
  Simulation sim(scene, options);
  const int cycles = sim.cycle_count();
  for (int k = 0; k < cycles; ++k) sim.run_cycle(k);
  long long k = 0;
  for (auto _ : state) {
    sim.run_cycle(static_cast<int>(k++ % cycles));
    benchmark::DoNotOptimize(sim.sensor_state(0).reported.data());
  }
  state.counters["objects"] = static_cast<double>(scene.objects.size());
  state.counters["sensors"] = static_cast<double>(scene.sensors.size());
}

BENCHMARK(BM_SensorCycle)->Arg(1)->Arg(10)->Arg(100);
BENCHMARK(BM_TrafficSceneCulling)->Arg(0)->Arg(1);
BENCHMARK(BM_CarsAllAroundCulling)->Args({0, 0})->Args({1, 0})->Args({0, 1})->Args({1, 1});
BENCHMARK(BM_CityDriveCulling)->Arg(0)->Arg(1);
BENCHMARK(BM_SensorCycleAllEffects)->Arg(10);
BENCHMARK(BM_SceneCycle)->Arg(1)->Arg(10)->Arg(100);

}  // namespace
}  // namespace rcsim

int main(int argc, char** argv) {
  return rcsim::bench_tools::run_benchmark_main(argc, argv, "rcsim_bench_sensor_cycle",
                                                "One sensor cycle (paper Fig. 13, all stages, noise on) for 1, 10 and 100 vehicles in view, with the\nheap allocations per cycle counted; the culling stage on a traffic scene and an imported recording.");
}
