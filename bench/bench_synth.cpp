// Time per sensor cycle of the signal-level reference (`rcsim synth`) against the
// reflection-center model (`rcsim simulate`, tracks level, noise on) on the same scenes of
// recordings_synthetic/scenes, and the reference's stages on one frame. Each iteration runs the
// next cycle of the scene for all of its sensors (two); the "per_sensor_cycle" counter is the time
// per sensor and cycle.
#include <benchmark/benchmark.h>

#include "benchmark_main.hpp"

#include <memory>
#include <string>

#include "model/model_library.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"
#include "synth/reference_simulator.hpp"

namespace rcsim {
namespace {

const char* const kScenes[] = {"front_approach", "perpendicular_crossing", "parking_area", "city_drive_60s"};

const Scene& scene(int index) {
  static const ModelLibrary library = ModelLibrary::builtin();
  static std::vector<std::unique_ptr<Scene>> scenes;
  if (scenes.empty()) {
    for (const char* name : kScenes) {
      scenes.push_back(std::make_unique<Scene>(
          load_scene_file(std::string(RCSIM_SOURCE_DIR) + "/recordings_synthetic/scenes/" + name + ".json", library)));
    }
  }
  return *scenes[static_cast<std::size_t>(index)];
}

void per_sensor_cycle(benchmark::State& state, std::size_t sensors) {
  state.counters["per_sensor_cycle"] = benchmark::Counter(
      static_cast<double>(state.iterations() * static_cast<benchmark::IterationCount>(sensors)),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.SetLabel(kScenes[state.range(0)]);
}

void BM_Reference(benchmark::State& state) {
  const Scene& s = scene(static_cast<int>(state.range(0)));
  auto sim = std::make_unique<synth::ReferenceSimulator>(s, synth::SynthConfig{}, 1);
  int cycle = 0;
  for (auto _ : state) {
    if (cycle == sim->cycle_count()) {
      state.PauseTiming();
      sim = std::make_unique<synth::ReferenceSimulator>(s, synth::SynthConfig{}, 1);
      cycle = 0;
      state.ResumeTiming();
    }
    sim->run_cycle(cycle++);
    benchmark::DoNotOptimize(sim->sensor_cycle(0).targets.data());
  }
  per_sensor_cycle(state, s.sensors.size());
}

void BM_Model(benchmark::State& state) {
  const Scene& s = scene(static_cast<int>(state.range(0)));
  SimulationOptions options;
  options.seed = 1;
  auto sim = std::make_unique<Simulation>(s, options);
  int cycle = 0;
  for (auto _ : state) {
    if (cycle == sim->cycle_count()) {
      state.PauseTiming();
      sim = std::make_unique<Simulation>(s, options);
      cycle = 0;
      state.ResumeTiming();
    }
    sim->run_cycle(cycle++);
    benchmark::DoNotOptimize(&sim->sensor_state(0));
  }
  per_sensor_cycle(state, s.sensors.size());
}

// The reference's stages on one frame of the city drive at t = 12 s (right sensor).
void BM_ReferenceStages(benchmark::State& state) {
  const Scene& s = scene(3);
  const synth::SynthConfig config;
  const synth::ReferenceSimulator sim(s, config, 1);
  synth::SignalChain chain(config);
  Rng rng(1);
  const auto echoes = sim.echoes_at(1, 12.0);
  const int stage = static_cast<int>(state.range(0));
  for (auto _ : state) {
    switch (stage) {
      case 0: benchmark::DoNotOptimize(sim.echoes_at(1, 12.0).data()); break;  // scene => echoes
      case 1: chain.synthesize(echoes); break;                                  // echoes => I/Q samples
      case 2: chain.add_receiver_noise(rng); break;                             // + noise
      case 3: chain.transform(); break;                                         // => range-Doppler maps
      default: benchmark::DoNotOptimize(chain.detect().data()); break;          // => detections
    }
  }
  static const char* const names[] = {"echoes", "synthesize", "noise", "fft", "detect"};
  state.SetLabel(std::string(names[stage]) + ", " + std::to_string(echoes.size()) + " echoes");
}

BENCHMARK(BM_Reference)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Model)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ReferenceStages)->DenseRange(0, 4)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace rcsim

int main(int argc, char** argv) {
  return rcsim::bench_tools::run_benchmark_main(argc, argv, "rcsim_bench_synth",
                                                "Time per sensor cycle of the signal-level reference (rcsim synth) against the reflection-center\nmodel (rcsim simulate) on the scenes of recordings_synthetic/scenes, and the reference's stages.");
}
