#pragma once
// The two kinds of simulated target lists a recording is compared with: the reflection-center
// model at a fidelity level (rcsim replay, rcsim bench) and the signal-level reference (rcsim
// bench's reference and noise-floor rows, docs/bench.md).
#include <memory>

#include "replay/run/replay_run.hpp"
#include "sim/simulation.hpp"
#include "synth/reference_simulator.hpp"

namespace rcsim::replay {

// The fields every target kind shares (RecordedTarget, ReportedTarget of the model and of the
// reference), and a recorded target's optional columns.
template <typename Target>
ComparedTarget compared_target(const Target& target) {
  ComparedTarget t;
  t.track_id = target.id;
  t.range_m = target.range_m;
  t.azimuth_rad = target.azimuth_rad;
  t.range_rate_mps = target.range_rate_mps;
  t.amplitude_db = target.amplitude_db;
  if constexpr (requires { target.rcs_dbsm; }) {  // a recorded target: the optional columns
    t.rcs_dbsm = target.rcs_dbsm;
    t.snr_db = target.snr_db;
    t.elevation_rad = target.elevation_rad;
  }
  return t;
}

// Tracked target lists of the model at a fidelity level, with every random draw from `seed`.
SimulationOptions model_options(std::uint64_t seed, Fidelity fidelity);

class ModelSource final : public SimulatedSource {
 public:
  ModelSource(const Scene& scene, const SimulationOptions& options) : simulation_(scene, options) {}
  void run_at(double t_scene_s, int only_sensor) override { simulation_.run_at(t_scene_s, only_sensor); }
  void cull_within(double t0_s, double t1_s) override { simulation_.cull_within(t0_s, t1_s); }
  void append_targets(std::size_t sensor, std::vector<ComparedTarget>& out) const override;

 private:
  Simulation simulation_;
};

// The signal-level reference (src/synth) run on the imported scene: its objects are built from
// their class and annotated size, as the model's are.
class ReferenceSource final : public SimulatedSource {
 public:
  ReferenceSource(const Scene& scene, std::uint64_t seed) : reference_(scene, synth::SynthConfig{}, seed) {}
  void run_at(double t_scene_s, int only_sensor) override { reference_.run_at(t_scene_s, only_sensor); }
  void append_targets(std::size_t sensor, std::vector<ComparedTarget>& out) const override;

 private:
  synth::ReferenceSimulator reference_;
};

}  // namespace rcsim::replay
