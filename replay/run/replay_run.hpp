#pragma once
// rcsim replay: import a recording, re-simulate it at exactly the recorded cycle times, and
// compare the simulated target lists with the recorded ones cycle by cycle and sensor by sensor.
// Results stream into a ReplaySink (the SQLite report store) so that an hour-long recording
// never has to be held in memory twice.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <utility>
#include <limits>
#include <string>
#include <vector>

#include "io/recording.hpp"
#include "metrics/distribution_distance.hpp"
#include "metrics/gospa.hpp"
#include "metrics/merge_artefacts.hpp"
#include "metrics/sensor_view.hpp"
#include "metrics/target_class.hpp"
#include "replay/import/importer.hpp"
#include "sim/fidelity.hpp"

namespace rcsim::replay {

struct ReplayOptions {
  std::uint64_t seed = 0;
  Fidelity fidelity = Fidelity::full;  // docs/fidelity.md
  ImportOptions import;
  metrics::GospaParameters gospa{2.0, 2.0};
  double association_gate_m = 1.0;  // a target belongs to the nearest box within this distance
  double merge_match_distance_m = 1.0;  // a recorded and a simulated artefact of one pair match within this
  double merge_margin_m = 0.5;          // an artefact lies farther than this from both boxes
  // Stationary background: ego-motion-compensated radial speed within this (docs/metrics.md).
  double stationary_gate_mps = 0.5;
  double object_range_bin_m = 10.0;  // bins of the detection probability against range
  // false: no GOSPA and no pairs (the summary's GOSPA figures are then 0, no target has a match),
  // for a search that needs only counts and detection rates (calibrate --real-drive's objective:
  // the assignment is 70 % of an imaging radar's replay).
  bool match_targets = true;
  // Set (by SIGINT: rcsim replay, calibrate): the replay stops at the next cycle boundary and
  // throws ReplayStopped; null: never. Not part of a run's identity.
  const std::atomic<bool>* stop = nullptr;
};

// A replay stopped by ReplayOptions::stop before its cycle `cycles_done` (of `cycles`): its sink
// saw begin_run and those cycles, never end_run.
class ReplayStopped : public std::runtime_error {
 public:
  ReplayStopped(int done, int of) : std::runtime_error("replay stopped"), cycles_done(done), cycles(of) {}
  int cycles_done, cycles;
};

// One target of one cycle and sensor, recorded or simulated.
struct ComparedTarget {
  int track_id = -1;
  double range_m = 0.0, azimuth_rad = 0.0, range_rate_mps = 0.0, amplitude_db = 0.0;
  Vec2 p_ST_S = Vec2::Zero();  // Cartesian, sensor frame
  int object = -1;          // recording object index it belongs to, or -1
  int match = -1;           // index of the GOSPA-assigned partner in the other list, or -1
  int merge_pair = -1;      // index into CycleComparison::merge_pairs if a merge artefact (then object = -1)
  metrics::TargetClass target_class = metrics::TargetClass::other;
  Vec2 p_OT_O = Vec2::Zero();  // offset from the box centre in the object's frame (object >= 0)
  // What real radars report besides (recording format v2's optional columns); NaN where absent.
  double rcs_dbsm = kNoValue, snr_db = kNoValue, elevation_rad = kNoValue;
  static constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();
};

struct ObjectInCycle {
  int object = -1;
  double x_m = 0.0, y_m = 0.0, yaw_rad = 0.0;  // annotated (smoothed) box in the world
  bool detectable = false;  // the scene geometry (SceneGeometry) says a sensor can detect it; not "in view" (object_figures: the box in the field of view)
};

struct CycleComparison {
  int cycle = 0;
  int sensor = 0;
  double t_s = 0.0;  // recording time
  Pose2 X_WS;        // sensor pose in the world
  std::vector<ComparedTarget> recorded, simulated;
  metrics::GospaResult gospa;
  metrics::GospaResult gospa_object;             // on the targets of annotated objects only
  std::vector<std::pair<int, int>> merge_pairs;  // object indices sharing a resolution cell (scene geometry)
  int merge_matched = 0;  // recorded artefacts with a simulated one of the same pair within the match distance
  std::vector<ObjectInCycle> objects;            // present objects near the sensor (stored for sensor 0)
};

// One episode in which an object is detectable by a sensor by the scene's geometry, and when each
// side confirmed it (replay/run/latency_episodes.hpp); an object that leaves and comes back (a
// parked car passed lap after lap) has several episodes.
struct LatencyRow {
  int sensor = 0, object = 0, episode = 0;
  double detectable_from_s = 0.0;
  double first_recorded_s = -1.0, first_simulated_s = -1.0;  // confirmation times; -1: never confirmed
};

// Per annotated object and sensor, over the cycles it was in the sensor's field of view.
struct ObjectFigureRow {
  int sensor = 0, object = 0;
  int cycles_in_view = 0, cycles_detected_recorded = 0, cycles_detected_simulated = 0;
  long long targets_recorded = 0, targets_simulated = 0;
};

// The same in one bin of the range of the box's nearest point: detection probability vs range,
// and targets per object-cycle; a (sensor, object)'s bins add up to its ObjectFigureRow.
struct ObjectRangeRow {
  int sensor = 0, object = 0;
  double range_from_m = 0.0, range_to_m = 0.0;
  int cycles_in_view = 0, cycles_detected_recorded = 0, cycles_detected_simulated = 0;
  long long targets_recorded = 0, targets_simulated = 0;
};

// Targets of each class (metrics/target_class.hpp), [0] recorded, [1] simulated.
struct ClassCounts {
  long long object[2] = {0, 0}, background[2] = {0, 0}, other[2] = {0, 0};
};

struct QuantityDistance {
  std::string quantity, unit;
  metrics::DistributionDistance distance;
};

struct ReplaySummary {
  int cycles = 0;
  // The sensors' cycles compared: cycles × sensors on a shared clock, the cycles themselves with
  // sensors on their own clocks (recording v4, where each cycle is one sensor's).
  long long sensor_cycles = 0;
  long long targets_recorded = 0, targets_simulated = 0, targets_matched = 0;
  double gospa_mean_m = 0.0, ospa_mean_m = 0.0;
  double gospa_localisation_mean_mp = 0.0, gospa_missed_mean_mp = 0.0, gospa_false_mean_mp = 0.0;
  double gospa_object_mean_m = 0.0, ospa_object_mean_m = 0.0;  // on the object targets only
  ClassCounts classes;
  long long merge_artefacts_recorded = 0, merge_artefacts_simulated = 0, merge_artefacts_matched = 0;
  // Confirmation latency (latency_episodes.hpp): each side's mean over the episodes it confirmed
  // (-1: none); the mean difference simulated - recorded over the episodes both confirmed (the
  // pairs); the episodes, and those each side never confirmed (censored, kept in `latencies`).
  double latency_recorded_s = -1.0, latency_simulated_s = -1.0, latency_difference_mean_s = 0.0;
  int latency_pairs = 0, latency_episodes = 0, latency_unconfirmed_recorded = 0, latency_unconfirmed_simulated = 0;
  double residual_range_rms_m = 0.0, residual_azimuth_rms_rad = 0.0, residual_range_rate_rms_mps = 0.0,
         residual_amplitude_mean_db = 0.0;
  // The same over the matched pairs whose both targets belong to one annotated object.
  long long object_pairs_matched = 0;
  double residual_object_range_rms_m = 0.0, residual_object_azimuth_rms_rad = 0.0;
  double simulate_cpu_s = 0.0, total_wall_s = 0.0;
  std::vector<LatencyRow> latencies;
  std::vector<QuantityDistance> distances;  // all targets, then the background's (background_*)
  std::vector<ObjectFigureRow> objects;
  std::vector<ObjectRangeRow> object_ranges;
};

// What a replay hands to storage, in order: begin, every cycle, end.
class ReplaySink {
 public:
  virtual ~ReplaySink() = default;
  virtual void begin_run(const Recording& recording, const ImportedScene& scene, const Scene& simulated_scene,
                         const ReplayOptions& options) = 0;
  virtual void add_cycle(const CycleComparison& cycle) = 0;
  virtual void end_run(const ReplaySummary& summary) = 0;
};

// A sink that keeps nothing: where only the summary counts (bench rows, calibration).
class DiscardingSink final : public ReplaySink {
 public:
  void begin_run(const Recording&, const ImportedScene&, const Scene&, const ReplayOptions&) override {}
  void add_cycle(const CycleComparison&) override {}
  void end_run(const ReplaySummary&) override {}
};

// What is compared against the recording: the reflection-center model at a fidelity level
// (replay/run/simulated_source.hpp: ModelSource) or the signal-level reference (ReferenceSource).
class SimulatedSource {
 public:
  virtual ~SimulatedSource() = default;
  // Runs every sensor (only_sensor < 0) or that sensor alone at scene time t (times increasing).
  virtual void run_at(double t_scene_s, int only_sensor) = 0;
  // The scene's trajectories now hold scene times [t0_s, t1_s] in full (a streaming replay).
  virtual void cull_within(double /*t0_s*/, double /*t1_s*/) {}
  // The target list one sensor reported in the last run_at, appended to `out`.
  virtual void append_targets(std::size_t sensor, std::vector<ComparedTarget>& out) const = 0;
};

// The recorded side of a replay, cycle by cycle: a recording in memory, or one read as the replay
// goes (streaming_import.hpp), whose scene's trajectories then cover a moving window.
class RecordedCycles {
 public:
  virtual ~RecordedCycles() = default;
  // The next cycle's index, recording time, sensor (-1: every sensor's cycle, a shared clock) and
  // targets (replacing `targets`); false at the end.
  virtual bool next(int& cycle, double& t_rec_s, int& sensor, std::vector<RecordedTarget>& targets) = 0;
  // The scene-time window the trajectories now hold in full, when it has moved.
  virtual std::optional<std::pair<double, double>> take_moved_window() { return std::nullopt; }
};

// The level a recording is compared at unless the user says otherwise: what its sensors report
// (schemas/recording.md): raw detections are compared without the tracker (no_tracking), tracks
// with it (full).
inline Fidelity default_fidelity_for(const Recording& recording) {
  return recording.all_sensors_report(ListLevel::detections) ? Fidelity::no_tracking : Fidelity::full;
}

// rcsim replay: the reflection-center model (options.fidelity) against the recording in
// directory `dir`, read, smoothed, simulated, compared and stored cycle by cycle in bounded
// memory: the stored figures are those of replay_recording on the recording read whole.
ReplaySummary replay_recording_dir(const std::filesystem::path& dir, const ReplayOptions& options, ReplaySink& sink);

// The same on a recording in memory (calibration, tests: recordings cut by sensor or cycles).
ReplaySummary replay_recording(const Recording& recording, const ReplayOptions& options, ReplaySink& sink);

// The comparison itself, for any source; `scene` is build_scene(imported); summary.simulate_cpu_s
// is the CPU time spent in source.run_at.
ReplaySummary compare_with_recording(const Recording& recording, const ImportedScene& imported, const Scene& scene,
                                     SimulatedSource& source, const ReplayOptions& options, ReplaySink& sink);

// The comparison over any recorded side: `recording` is the header (name, sensors, checksum,
// cycle count), `cycles` gives the rows.
ReplaySummary compare_cycles(const Recording& recording, const ImportedScene& imported, const Scene& scene,
                             RecordedCycles& cycles, SimulatedSource& source, const ReplayOptions& options,
                             ReplaySink& sink);

}  // namespace rcsim::replay
