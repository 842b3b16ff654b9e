#pragma once
// rcsim calibrate (docs/calibration.md). The paper assigns ERCS 1 to its reference reflector and
// derives the equivalent radar cross sections of all other reflection centers "by inspection of
// real radar measurements" (III-B, eq. (3)). This does that inspection by search: it varies the
// ERCS of every reflector of every model the recordings use (and, if asked, the sensor's
// amplitude law, eq. (1), and its multibounce loss) so that the model at level `full`, replayed
// against the recordings as rcsim replay does, comes closest to them in GOSPA.
//
// Objective: the mean over recordings of GOSPA / GOSPA with the starting parameters, so that every
// recording weighs the same, plus how much further (in |ln|) the count of simulated targets has
// moved from the recorded count than at the start (GOSPA alone would reward reporting nothing
// where the model misplaces targets). Search: coordinate pattern search, each parameter moved by +-step in
// turn and kept where the objective falls; the step halves from initial_step_db to final_step_db.
// Every random draw comes from one seed (common random numbers), so the objective is a
// deterministic function of the parameters.
#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/recording.hpp"
#include "replay/run/replay_run.hpp"

namespace rcsim::replay {

// The calibration's JSON documents keep their keys in the order they were written.
using Json = nlohmann::ordered_json;

// What may be varied. Reflectors that mirror each other about the model's x axis (a left and a
// right corner) share their parameters, mirrored, so a fitted model stays symmetric.
enum class ParameterGroup {
  ercs,         // each reflector's ERCS (point: its maximum; plane: its value), in dB steps
  position,     // point reflectors' x and y; plane reflectors moved along their outward normal
  visibility,   // point reflectors' visibility function: centre, full half-width, fall-off
  level,        // the sensor's reference level L0, eq. (1)
  slope,        // the sensor's reference slope, eq. (1)
  multibounce,  // the sensor's loss per back-and-forth bounce
  antenna,      // the sensor's amplitude pattern exponent n, A^phi = |H_sum|^n in eq. (2)
};
inline constexpr std::string_view kParameterGroupNames = "ercs | position | visibility | level | slope | multibounce | antenna";
std::optional<ParameterGroup> parse_parameter_group(std::string_view name);
std::string_view parameter_group_name(ParameterGroup group);

struct CalibrationOptions {
  std::vector<ParameterGroup> groups{ParameterGroup::ercs, ParameterGroup::slope};
  std::uint64_t seed = 1;
  // First step: ERCS, level and loss in dB; slope: step / 20 m; positions: step / 60 dB/m (6 dB:
  // 0.1 m); angles: 2.5 deg per dB.
  double initial_step_db = 6.0;
  double final_step_db = 0.5;    // the search ends after the sweeps at the first step below this
  int max_sweeps_per_step = 3;
  // A calibration directory (rcsim-calibration) to start from instead of the built-ins: an earlier
  // fit, or hand-edited documents (e.g. a model with reflectors added); "" = the built-ins.
  std::string start_dir;
  ReplayOptions replay;  // import and metric parameters; its seed and fidelity are set here
};

struct CalibrationParameter {
  // e.g. passenger_car.corner_front_left+corner_front_right.ercs, srr24.amplitude.reference_slope_db_per_m
  std::string name;
  std::string document;               // "sensor:srr24" or "model:passenger_car"
  std::vector<std::string> pointers;  // JSON pointers of the values it sets, e.g. /plane_reflectors/0/ercs
  ParameterGroup group = ParameterGroup::ercs;
  std::string unit;  // of initial and value: the first pointer's value, or an offset ("offset_m")
  double initial = 0.0, value = 0.0, lower = 0.0, upper = 0.0;
};

struct RecordingFit {
  std::string recording;
  double gospa_before_m = 0.0;  // with the starting parameters
  double gospa_after_m = 0.0;   // with the fitted ones
};

struct CalibrationResult {
  std::vector<CalibrationParameter> parameters;
  std::vector<RecordingFit> recordings;
  double objective_before = 1.0, objective_after = 1.0;  // mean GOSPA ratio plus count penalty
  int evaluations = 0;  // objective evaluations (each replays the recordings a parameter touches)
  // Every evaluation (at least two) gave the start's objective: no parameter moved it, nothing fitted.
  bool flat = false;
  // options.replay.stop was set (Ctrl-C): the search ended early, at once (a replay under way
  // stops at its next cycle and its trial is dropped); the parameters are the best so far.
  bool partial = false;
  // The fitted rcsim-sensor and rcsim-object-model documents, keyed as CalibrationParameter::document.
  std::map<std::string, nlohmann::ordered_json> documents;
};

// The fewest cycles a recording to fit on may have where tracks are compared or simulated: a track
// confirms after 4 hits (paper III-E). Raw detections with no tracker simulated need one cycle
// (single frames are first-class).
inline constexpr int kMinCalibrationCycles = 4;

// The fewest recorded targets a recording to fit on may hold (issue 51: one target gave a
// "fitted" calibration): one per value the real-drive fit moves (a level offset, the diffuse
// return, the occlusion loss, the range exponent). A single frame of 4 detections on a car is
// still fitted (issue 48).
inline constexpr std::size_t kMinCalibrationTargets = 4;

// Whether some sensor of the recording reports tracks (then tracks are compared), not detections.
bool compares_tracks(const Recording& recording);

// Refuses, naming the recording (InputError), one that cannot inform a fit: fewer than
// kMinCalibrationTargets recorded targets, no annotated object, every recorded target the same point, or fewer than kMinCalibrationCycles
// cycles where a track must confirm: some sensor reports tracks, or, at `fidelity` (not
// no_tracking), some sensor's profile simulates a tracker.
void check_fittable(const Recording& recording, Fidelity fidelity);

// Progress: the step just finished, the objective and the evaluations so far; first with step 0
// once the starting parameters are evaluated.
using CalibrationProgress = std::function<void(double step_db, double objective, int evaluations)>;

CalibrationResult calibrate(const std::vector<Recording>& recordings, const CalibrationOptions& options,
                            const CalibrationProgress& progress = {});

// Leave-one-out: each recording's GOSPA with the parameters fitted on all the others (before:
// the starting parameters), an estimate of the error on a recording the fit has not seen.
std::vector<RecordingFit> cross_validate(const std::vector<Recording>& recordings, const CalibrationOptions& options,
                                         const std::function<void(const RecordingFit&)>& done = {});

// The rcsim-sensor document a calibration directory holds (its first sensor), to start a
// --real-drive search from (calibrate --start DIR, e.g. an interrupted fit); InputError naming the
// file for a directory that is no calibration or holds no sensor.
nlohmann::ordered_json start_sensor_document(const std::string& dir);

// Refuses (InputError naming it) an output directory a calibration cannot be written into (not a
// directory, read-only, no permission; its index a link or a device): called before the first
// evaluation, so that an hour's fit never ends unable to write.
void check_calibration_output(const std::string& dir);

// Writes the fitted documents (DIR/<name>.json) and the index DIR/calibration.json
// (rcsim-calibration v1) that rcsim replay or rcsim bench --calibration DIR read; each file atomically,
// the index last.
// The rcsim-sensor document a recording's sensor type names: built-in or a file relative to
// `base_dir` (the recording's directory).
nlohmann::ordered_json sensor_document(const std::string& type, const std::string& base_dir);

void write_calibration(const std::string& dir, const CalibrationResult& result, const CalibrationOptions& options,
                       const std::vector<Recording>& recordings, const std::vector<RecordingFit>* held_out);

}  // namespace rcsim::replay
