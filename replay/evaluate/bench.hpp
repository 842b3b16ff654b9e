#pragma once
// rcsim bench: speed against error (docs/bench.md). Every fidelity level of the model, the
// signal-level reference and the noise floor, each replayed against a recording:
//   reference   : the reference (src/synth) on the imported scene, seed A, against the recording
//   noise_floor : the reference with seed B against the reference with seed A as if it were the
//                 recording -- the error no model can beat
//   full, ...   : the model at that fidelity level against the recording
// Speed is sensor cycles per CPU second of the simulation alone (thread CPU time, comparison and
// I/O excluded); error is what rcsim replay measures.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "io/recording.hpp"
#include "replay/run/replay_run.hpp"

namespace rcsim::replay {

inline constexpr std::string_view kReferenceLevel = "reference";
inline constexpr std::string_view kNoiseFloorLevel = "noise_floor";

struct BenchOptions {
  std::uint64_t seed = 1;  // the model's seed; the reference's are derived (reference_seeds)
  std::vector<Fidelity> levels{Fidelity::full, Fidelity::no_monopulse, Fidelity::points_only, Fidelity::no_tracking};
  bool reference = true;           // the reference and noise_floor rows (the slow part)
  double min_timing_cpu_s = 0.25;  // model levels: timing passes over the recording repeat until this much CPU
  ReplayOptions replay;            // metric and import parameters (its seed and fidelity are set per row)
};

// Seeds A and B of the reference runs: seed + 1 and seed + 2, skipping the seed the recording was
// made with (recording.json source.seed, if any), so that no run repeats the recording's noise.
std::pair<std::uint64_t, std::uint64_t> reference_seeds(std::uint64_t seed, const Recording& recording);

struct BenchRow {
  int recording = 0;  // position in the bench
  std::string recording_name;
  std::uint64_t recording_checksum = 0;
  std::string level;
  long long sensor_cycles = 0;             // cycles x sensors
  double cpu_s = -1.0;                     // CPU time of one pass over the recording; -1: not timed (noise_floor)
  double sensor_cycles_per_cpu_s = -1.0;   // -1: not timed
  double gospa_mean_m = 0.0;
  long long targets_recorded = 0, targets_simulated = 0;
  double targets_per_cycle_ratio = -1.0;   // simulated / recorded; -1: nothing recorded
  long long merge_recorded = 0, merge_found = 0, merge_missed = 0, merge_spurious = 0;
  bool has_latency = false;
  double latency_difference_s = 0.0;       // mean simulated - recorded over paired episodes
  int latency_pairs = 0;
};

// The rows of one recording, in the order reference, noise_floor, then options.levels; each row
// is handed to `done` as soon as it is measured (progress), and what the import noticed (bridged
// or split annotation gaps, ImportedScene::warnings) to `warn` before any row.
std::vector<BenchRow> bench_recording(const Recording& recording, int index, const BenchOptions& options,
                                      const std::function<void(const BenchRow&)>& done = {},
                                      const std::function<void(const std::string&)>& warn = {});

// One level over all recordings: cycles per CPU second of the sum, means of the errors. The one
// summary of a bench: rcsim bench prints it, rcsim report plots and tabulates it.
struct BenchLevelSummary {
  std::string level;
  int recordings = 0;
  long long sensor_cycles = 0;
  double cpu_s = -1.0;                    // sum over the timed rows; -1: none timed
  double sensor_cycles_per_cpu_s = -1.0;  // their sensor cycles / their CPU time
  double gospa_mean_m = 0.0;              // mean over recordings
  // Mean GOSPA / mean noise floor, both over the recordings that have a noise floor (the plot's
  // point against its dashed line); -1: no such recording.
  double gospa_over_noise_floor = -1.0;
  double targets_per_cycle_ratio = -1.0;  // mean over recordings that recorded targets
  long long merge_recorded = 0, merge_found = 0, merge_missed = 0, merge_spurious = 0;
  bool has_latency = false;
  double latency_difference_s = 0.0;      // mean over recordings with paired episodes
  long long latency_pairs = 0;
};
// In the order the levels first appear in `rows`.
std::vector<BenchLevelSummary> summarise_levels(const std::vector<BenchRow>& rows);

// The goals of docs/bench.md (speed, error, noise floor), evaluated on a bench.
struct BenchGoals {
  bool evaluable = false;           // full, the reference and the noise floor all present
  double best_error_m = 0.0;        // lowest mean GOSPA of any level (reference included)
  std::string best_level;
  double default_error_m = 0.0;     // level full
  bool within_10_percent = false;   // default_error <= 1.1 best_error
  double speedup = 0.0;             // full's cycles per CPU second / the reference's
  bool at_least_100x = false;
  struct PerRecording {
    std::string recording;
    double ratio = 0.0;             // full's GOSPA / noise floor
    bool within_1_5 = false;
    // The same for the reference on the imported scene: what a perfect model of the reference,
    // fed the same annotations, would get (the floor leaves the annotation errors out).
    double reference_ratio = 0.0;
    // The goal (docs/bench.md): full's GOSPA over the reference's on the imported scene, <= 1.1.
    double over_reference = 0.0;
    bool within_1_1_reference = false;
  };
  std::vector<PerRecording> per_recording;
  bool all_within_1_5 = false;  // the noise floor: information, no longer the goal
  bool all_within_1_1_reference = false;
};
BenchGoals evaluate_goals(const std::vector<BenchRow>& rows);

// CPU model and logical core count of this machine (for the stored figures).
std::string machine_description();

}  // namespace rcsim::replay
