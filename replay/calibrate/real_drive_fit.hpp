#pragma once
// Fitting a sensor profile to a real drive and measuring it on data it was not fitted on
// (docs/sensor-profiles.md, issue 18's goals): the profile's free values (the RCS an ERCS of 1
// stands for, the diffuse face return, the occlusion loss, a relative level's range exponent) by a
// bounded search on the real-drive figures (object target counts and detection rates, not GOSPA),
// the stationary background by its density; then the goal figures in sample and held out: fitted
// on the front radar and measured on the rear one, the reverse, and fitted on the first half of
// the drive (or the frames) and measured on the second, or, for a few single frames, each frame
// held out in turn.
#include <atomic>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/recording.hpp"
#include "replay/run/replay_run.hpp"
#include "replay/calibrate/bounded_search.hpp"
#include "sensor/stationary_background.hpp"

namespace rcsim::replay {

// The recording with one sensor's targets only (the other sensors gone).
Recording restrict_to_sensor(const Recording& recording, int sensor);
// The recording's cycles [first, end) (ego rows, boxes and targets of those cycles; cycle
// numbers from 0 again).
Recording restrict_to_cycles(const Recording& recording, int first, int end);
// The recording without cycle `held` (a frame left out of single frames): its targets, ego row and
// boxes (those nearest its time) gone, the later cycles numbered one lower. Both cuts drop the
// objects left without a box (snapshot data boxes each object in one frame only).
Recording without_cycle(const Recording& recording, int held);

// A replay of `recording` with `config` in place of the sensor type of the same name, the
// detection probability in 20-m bins (for real_drive_figures).
ReplaySummary replay_with_sensor(const Recording& recording, const ReplayOptions& options, const SensorConfig& config);
ReplaySummary replay_with_sensor(const Recording& recording, const ReplayOptions& options, const SensorConfig& config,
                                 ReplaySink& sink);

// Issue 18's goal figures of one replay (docs/sensor-profiles.md).
struct RealDriveFigures {
  long long object_targets_recorded = 0, object_targets_simulated = 0;
  double object_count_ratio = 0.0;  // simulated / recorded, objects in view
  // Per object with at least 30 recorded targets: simulated / recorded; the one farthest from 1.
  double worst_object_ratio = 1.0;
  std::string worst_object;
  int objects_counted = 0, objects_within_ratio_goal = 0;  // within [0.67, 1.5]
  double max_detection_rate_difference = 0.0;  // per object and sensor, simulated - recorded, largest |.|
  std::string max_detection_rate_object;
  double max_pd_bin_difference = 0.0;  // detection probability in 20-m bins (>= 10 cycles in view)
  double residual_range_rms_m = 0.0, residual_azimuth_rms_rad = 0.0;  // object pairs
  long long object_pairs = 0;
  double background_per_cycle_recorded = 0.0, background_per_cycle_simulated = 0.0;
  double background_range_ks = 0.0;
};

// The figures of a replay of `recording` (its summary must come from options.object_range_bin_m
// = 20).
RealDriveFigures real_drive_figures(const Recording& recording, const ReplaySummary& summary);
nlohmann::ordered_json figures_to_json(const RealDriveFigures& figures);

// The stationary background of the recordings' sensors (recorded targets of class stationary
// background, docs/metrics.md): targets per sensor cycle, density over 10-m range bins and 12
// azimuth bins over the view field, amplitude deciles per range bin. The recordings are replayed with
// `config` as their sensors' profile (config.name must be the profile their `type` names).
StationaryBackground fit_stationary_background(const std::vector<const Recording*>& recordings,
                                               const ReplayOptions& options, const SensorConfig& config);

// One value the fit searched: where it started, where it ended, and whether that is a bound of the
// search (then the optimum may lie beyond it).
struct FittedValue {
  std::string field;  // the rcsim-sensor field, dotted
  double start = 0.0, value = 0.0, lower = 0.0, upper = 0.0;
  bool on_bound = false;
};

struct RealDriveSearch {
  int max_evaluations = 60;
  const std::atomic<bool>* stop = nullptr;  // set (e.g. by SIGINT): the fit ends with the best so far, partial
  std::function<void(const SearchProgress&)> progress;
  // The rcsim-sensor document to start from (an earlier fit, e.g. a partial one: calibrate
  // --start DIR); null: the recordings' own profile.
  nlohmann::ordered_json start;
};

struct RealDriveFit {
  nlohmann::ordered_json sensor_document;  // the recordings' rcsim-sensor document with the fitted values
  std::vector<FittedValue> values;
  double reference_rcs_dbsm = 0.0, diffuse_relative_ercs_per_sqrt_m = 0.0, occlusion_loss_db = 0.0;
  double objective = 0.0;
  int evaluations = 0;
  bool converged = false;
  bool partial = false;  // stopped before it converged or spent its budget: the best so far
  bool flat = false;     // every evaluation gave the same objective: the values are the start's, not fitted
};

// Fits the profile the recordings' sensors share (their one sensor type) to them: the stationary
// background first, then by a bounded compass search (bounded_search.hpp) from the profile's own
// values the reference RCS (a level offset, +-24 dB), the diffuse face return, the occlusion loss
// and, for an amplitude on the radar's own scale (relative_db), the range exponent (0-4). The
// profile with the background, and with each value at its bounds, is checked against the
// profile's limits before the search (std::invalid_argument naming the field).
RealDriveFit fit_real_drive(const std::vector<const Recording*>& recordings, const ReplayOptions& options,
                            const RealDriveSearch& search = {});

// One hold-out: fitted on `train`, figures in sample (on train) and held out (on `test`).
struct HoldOut {
  std::string name;  // "front -> rear", ...
  RealDriveFit fit;
  RealDriveFigures in_sample, held_out;
};

// Single frames (timeline snapshots) up to this many are held out one by one (leave one frame
// out); more are split in halves, as a drive is.
inline constexpr int kMaxFramesLeftOut = 20;

// The hold-outs of one recording: with two sensors, first -> second and second -> first; then, for
// up to kMaxFramesLeftOut single frames, each frame held out in turn (fitted on the others), else
// the first half of the cycles (frames) -> the second. Refused (InputError naming the recording)
// with fewer cycles than a split needs: 2 for detections, kMinCalibrationCycles for tracks
// (compares_tracks, calibration_fit.hpp).
void check_hold_out(const Recording& recording);
std::vector<HoldOut> hold_outs(const Recording& recording, const ReplayOptions& options, const RealDriveSearch& search = {});

}  // namespace rcsim::replay
