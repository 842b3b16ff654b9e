// rcsim calibrate [RECORDING_DIR ...] -o DIR: fit the reflectors' ERCS (and, if asked, the
// amplitude law and the multibounce loss) to recordings, as the paper derives them by inspection
// of measurements (docs/calibration.md); rcsim replay or rcsim bench --calibration DIR use the result.
#include <cmath>
#include <fmt/format.h>
#include <iostream>

#include "cli/commands.hpp"
#include "cli/fit_progress.hpp"
#include "cli/recording_dirs.hpp"
#include "sensor/sensor_config.hpp"
#include "cli/seed_option.hpp"
#include "common/decibel.hpp"
#include "common/input_error.hpp"
#include "common/atomic_file.hpp"
#include "replay/calibrate/calibration_fit.hpp"
#include "replay/calibrate/real_drive_fit.hpp"

namespace rcsim::cli {

namespace {

struct CalibrateArgs {
  std::vector<std::string> recordings;
  std::string output_dir;
  std::string fit = "ercs,slope";
  std::uint64_t seed = kDefaultSeed;
  double initial_step_db = replay::CalibrationOptions{}.initial_step_db;
  double final_step_db = replay::CalibrationOptions{}.final_step_db;
  bool cross_validate = false;
  std::string start_dir;
  bool real_drive = false;
  bool hold_out = false;
  int max_evaluations = replay::RealDriveSearch{}.max_evaluations;
  std::string sensor;  // --sensor: the profile every sensor is fitted as, instead of its type
};

std::vector<replay::ParameterGroup> parse_groups(const std::string& list) {
  std::vector<replay::ParameterGroup> groups;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, comma - start);
    const auto g = replay::parse_parameter_group(name);
    if (!g) throw InputError("--fit", name, std::string("unknown parameter group; one of ") + std::string(replay::kParameterGroupNames));
    if (std::find(groups.begin(), groups.end(), *g) == groups.end()) groups.push_back(*g);
    start = comma + 1;
  }
  return groups;
}

// A change as a ratio in dB (ERCS) or a difference in the parameter's unit.
std::string change_text(const replay::CalibrationParameter& p) {
  if (p.group == replay::ParameterGroup::ercs) return fmt::format("{:+.2f} dB", amplitude_to_db(p.value / p.initial));
  return fmt::format("{:+.3f}", p.value - p.initial);
}

void print_fits(const std::string& title, const std::vector<replay::RecordingFit>& fits) {
  std::cout << fmt::format("\n{}\n{:<24} {:>13} {:>13} {:>7}\n", title, "recording", "GOSPA before", "GOSPA after", "ratio");
  for (const auto& f : fits) {
    std::cout << fmt::format("{:<24} {:>11.3f} m {:>11.3f} m {:>7.2f}\n", f.recording.substr(0, 24), f.gospa_before_m,
                             f.gospa_after_m, f.gospa_before_m > 0.0 ? f.gospa_after_m / f.gospa_before_m : 0.0);
  }
}

void print_figures_header() {
  std::cout << fmt::format("{:<34} {:>7} {:>6} {:>16} {:>14} {:>7} {:>9} {:>9} {:>13} {:>6}\n", "", "count", "objs",
                           "worst object", "det. rate", "Pd bin", "range", "azimuth", "background", "KS");
  std::cout << fmt::format("{:<34} {:>7} {:>6} {:>16} {:>14} {:>7} {:>9} {:>9} {:>13} {:>6}\n", "", "sim/rec", "in goal",
                           "sim/rec", "max diff", "max diff", "RMS m", "RMS deg", "rec / sim", "range");
}

void print_figures(const std::string& label, const replay::RealDriveFigures& f) {
  std::cout << fmt::format("{:<34} {:>7.2f} {:>3}/{:<2} {:>9} {:>6.2f} {:>14.2f} {:>7.2f} {:>9.3f} {:>9.3f} {:>6.1f}/{:<6.1f} {:>6.3f}\n",
                           label, f.object_count_ratio, f.objects_within_ratio_goal, f.objects_counted,
                           f.worst_object.substr(0, 9), f.worst_object_ratio, f.max_detection_rate_difference,
                           f.max_pd_bin_difference, f.residual_range_rms_m, f.residual_azimuth_rms_rad * 180.0 / 3.141592653589793,
                           f.background_per_cycle_recorded, f.background_per_cycle_simulated, f.background_range_ks);
}

// How a real-drive search ended. A flat objective is no convergence: nothing moved it.
std::string search_outcome(const replay::RealDriveFit& fit) {
  if (fit.partial) return "interrupted: the best so far (partial)";
  if (fit.flat) return "the objective is flat (not converged)";
  return fit.converged ? "converged" : "the evaluation budget spent before the steps converged";
}

std::string searched_fields(const replay::RealDriveFit& fit) {
  std::string names;
  for (const replay::FittedValue& v : fit.values) names += (names.empty() ? "" : ", ") + v.field;
  return names;
}

// A word as a shell reads it: as it is if it holds nothing a shell would take apart, else quoted.
std::string shell_word(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./,:=@+") ==
                           std::string::npos) {
    return word;
  }
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// The command that continues an interrupted fit from what it wrote: the same one, with --start
// naming its output (issue 53: "run again to finish it" restarted from evaluation 1).
std::string resume_command(const CalibrateArgs& args) {
  std::string command = "rcsim calibrate";
  for (const std::string& r : args.recordings) command += " " + shell_word(r);
  if (args.real_drive) command += " --real-drive";
  if (args.hold_out) command += " --hold-out";
  if (!args.sensor.empty()) command += " --sensor " + shell_word(args.sensor);
  if (args.real_drive && args.max_evaluations != replay::RealDriveSearch{}.max_evaluations) {
    command += fmt::format(" --max-evaluations {}", args.max_evaluations);
  }
  if (!args.real_drive) {
    if (args.fit != CalibrateArgs{}.fit) command += " --fit " + shell_word(args.fit);
    if (args.initial_step_db != CalibrateArgs{}.initial_step_db) command += fmt::format(" --initial-step-db {}", args.initial_step_db);
    if (args.final_step_db != CalibrateArgs{}.final_step_db) command += fmt::format(" --final-step-db {}", args.final_step_db);
    if (args.cross_validate) command += " --cross-validate";
  }
  if (args.seed != kDefaultSeed) command += fmt::format(" --seed {}", args.seed);
  return command + " --start " + shell_word(args.output_dir) + " -o " + shell_word(args.output_dir);
}

// What an interrupted fit left, and how to go on.
std::string interrupted_text(const CalibrateArgs& args, int evaluations) {
  return fmt::format("{} holds the best fit so far ({} evaluations), marked partial (\"partial\": true in {}; replay "
                     "--calibration says so); to continue the search from it: {}",
                     args.output_dir, evaluations, replay::kCalibrationIndexFile, resume_command(args));
}

// rcsim calibrate --real-drive (docs/sensor-profiles.md): the profile's free values and the
// stationary background fitted to real drives by their figures, with the hold-outs.
void run_real_drive_calibration(const CalibrateArgs& args) {
  std::vector<Recording> recordings;
  for (const auto& dir : recording_dirs(args.recordings)) {
    recordings.push_back(read_recording(dir));
    replay::check_fittable(recordings.back(), Fidelity::no_tracking);
    if (args.hold_out) replay::check_hold_out(recordings.back());  // before an hour is spent on the fit
  }
  if (!args.sensor.empty()) {
    // A file named on the command line is relative to the working directory, not the recording.
    const std::string type = is_builtin_sensor_config(args.sensor) ? args.sensor : std::filesystem::absolute(args.sensor).string();
    if (!is_builtin_sensor_config(args.sensor) && !std::filesystem::is_regular_file(type)) {
      throw InputError("--sensor", args.sensor, "no such built-in profile or rcsim-sensor file; " + unknown_sensor_message(args.sensor));
    }
    for (Recording& r : recordings) {
      for (RecordingSensor& s : r.sensors) s.type = type;
    }
  }
  const FitInterrupt interrupt;
  replay::ReplayOptions options;
  options.seed = args.seed;
  options.fidelity = Fidelity::no_tracking;
  options.stop = interrupt.flag();  // the figures' replays stop at the next cycle too
  const nlohmann::ordered_json start =
      args.start_dir.empty() ? nlohmann::ordered_json() : replay::start_sensor_document(args.start_dir);
  std::vector<const Recording*> all;
  for (const Recording& r : recordings) all.push_back(&r);
  std::cout << fmt::format("rcsim calibrate --real-drive: {} recording(s), seed {}, at most {} evaluations\n", recordings.size(),
                           args.seed, args.max_evaluations);
  replay::RealDriveFit fit;
  try {
    FitProgress progress("calibrate --real-drive");
    replay::RealDriveSearch search{args.max_evaluations, interrupt.flag(), [&](const replay::SearchProgress& p) { progress.update(p); },
                                   start};
    fit = replay::fit_real_drive(all, options, search);
  } catch (const replay::ReplayStopped&) {
    throw FitInterrupted("stopped while the stationary background was fitted, before the first evaluation: nothing "
                         "written; run the same command again");
  }
  std::cout << fmt::format("fitted: {} evaluations, objective {:.4f}, {}; background {:.1f} targets per sensor cycle\n",
                           fit.evaluations, fit.objective, search_outcome(fit),
                           fit.sensor_document["background"]["targets_per_cycle"].get<double>());
  if (fit.flat) {
    std::cout << fmt::format("  the objective is flat: {:.4f} at each of the {} evaluations; no searched value ({}) changed it, "
                             "so the values below are the start's, not fitted (docs/calibration.md, a flat objective)\n",
                             fit.objective, fit.evaluations, searched_fields(fit));
  }
  nlohmann::ordered_json values = nlohmann::ordered_json::array();
  for (const replay::FittedValue& v : fit.values) {
    std::cout << fmt::format("  {:<52} {:>9.3f} (from {:.3f}; searched {:.3f} .. {:.3f}){}\n", v.field, v.value, v.start, v.lower,
                             v.upper, v.on_bound ? "  ON A BOUND: the optimum may lie beyond it" : "");
    values.push_back({{"field", v.field}, {"start", v.start}, {"value", v.value}, {"lower", v.lower}, {"upper", v.upper},
                      {"on_bound", v.on_bound}});
  }
  std::cout << '\n';
  nlohmann::ordered_json index = {{"format", replay::kCalibrationFormat}, {"version", replay::kCalibrationVersion},
                                  {"created_by", "rcsim calibrate --real-drive"}, {"seed", args.seed}};
  nlohmann::ordered_json fitted_on = nlohmann::ordered_json::array();
  for (const Recording& r : recordings) fitted_on.push_back({{"recording", r.name}, {"checksum", fmt::format("{:016x}", r.checksum)}});
  index["fitted_on"] = fitted_on;
  index["fit"] = {{"evaluations", fit.evaluations}, {"objective", fit.objective}, {"converged", fit.converged},
                  {"partial", fit.partial}, {"flat", fit.flat}, {"reference_rcs_dbsm", fit.reference_rcs_dbsm},
                  {"diffuse_relative_ercs_per_sqrt_m", fit.diffuse_relative_ercs_per_sqrt_m},
                  {"occlusion_loss_db", fit.occlusion_loss_db}, {"values", values}};
  // Interrupted: the fit is written at once, without the figures' replays (issue 53: the figures
  // took 15 s after Ctrl-C, with a bare table header on screen).
  nlohmann::ordered_json in_sample = nlohmann::ordered_json::array();
  nlohmann::ordered_json hold_outs = nlohmann::ordered_json::array();
  try {
    if (fit.partial || interrupt.interrupted()) throw replay::ReplayStopped(0, 0);
    print_figures_header();
    const SensorConfig fitted = parse_sensor_config(JsonField(fit.sensor_document, "fitted", ""));
    for (const Recording& r : recordings) {
      const auto figures = replay::real_drive_figures(r, replay::replay_with_sensor(r, options, fitted));
      print_figures(fmt::format("in sample: {}", r.name.substr(0, 22)), figures);
      in_sample.push_back({{"recording", r.name}, {"figures", replay::figures_to_json(figures)}});
    }
    for (const Recording& r : recordings) {
      if (!args.hold_out) break;
      FitProgress progress("calibrate --real-drive --hold-out");
      replay::RealDriveSearch search{args.max_evaluations, interrupt.flag(), [&](const replay::SearchProgress& p) { progress.update(p); },
                                     {}};
      for (const replay::HoldOut& h : replay::hold_outs(r, options, search)) {
        print_figures(fmt::format("{}: in sample", h.name.substr(0, 22)), h.in_sample);
        print_figures(fmt::format("{}: held out", h.name.substr(0, 22)), h.held_out);
        if (h.fit.flat) std::cout << fmt::format("{}: the fit's objective is flat over its {} evaluations\n", h.name, h.fit.evaluations);
        hold_outs.push_back({{"recording", r.name}, {"split", h.name}, {"flat", h.fit.flat},
                             {"reference_rcs_dbsm", h.fit.reference_rcs_dbsm},
                             {"diffuse_relative_ercs_per_sqrt_m", h.fit.diffuse_relative_ercs_per_sqrt_m},
                             {"occlusion_loss_db", h.fit.occlusion_loss_db},
                             {"in_sample", replay::figures_to_json(h.in_sample)},
                             {"held_out", replay::figures_to_json(h.held_out)}});
      }
      if (interrupt.interrupted()) throw replay::ReplayStopped(0, 0);
    }
  } catch (const replay::ReplayStopped&) {
    std::cout << "interrupted: the in-sample and held-out figures are not measured (replay --calibration measures them)\n";
  }
  index["in_sample"] = in_sample;
  index["hold_outs"] = hold_outs;
  index["partial"] = fit.partial || interrupt.interrupted();
  nlohmann::ordered_json document = fit.sensor_document;
  const std::string name = document.value("name", "sensor");
  document["description"] = document.value("description", "") +
                            fmt::format(" Calibrated by rcsim calibrate --real-drive on {} recording(s) (seed {}).",
                                        recordings.size(), args.seed);
  std::filesystem::create_directories(args.output_dir);
  const std::string file = "sensor_" + name + ".json";
  AtomicFileWriter sensor_writer((std::filesystem::path(args.output_dir) / file).string());
  sensor_writer.stream() << document.dump(2) << '\n';
  sensor_writer.commit();
  index["sensors"] = {{name, file}};
  index["models"] = nlohmann::ordered_json::object();
  AtomicFileWriter index_writer((std::filesystem::path(args.output_dir) / replay::kCalibrationIndexFile).string());
  index_writer.stream() << index.dump(2) << '\n';
  index_writer.commit();
  std::cout << fmt::format("\ncalibration written to {}; use it with rcsim replay --calibration {}\n", args.output_dir,
                           args.output_dir);
  if (fit.partial || interrupt.interrupted()) throw FitInterrupted(interrupted_text(args, fit.evaluations));
}

void run_calibrate(const CalibrateArgs& args) {
  replay::check_calibration_output(args.output_dir);  // before the first evaluation, not after the last
  if (args.real_drive) return run_real_drive_calibration(args);
  if (args.hold_out) throw InputError("--hold-out", "", "goes with --real-drive");
  if (!args.sensor.empty()) throw InputError("--sensor", args.sensor, "goes with --real-drive");
  replay::CalibrationOptions options;
  options.groups = parse_groups(args.fit);
  options.seed = args.seed;
  options.initial_step_db = args.initial_step_db;
  options.final_step_db = args.final_step_db;
  options.start_dir = args.start_dir;
  if (options.final_step_db > options.initial_step_db) {
    throw InputError("--final-step-db", fmt::format("{}", args.final_step_db), "must be at most --initial-step-db");
  }
  // Every recording is read (and refused) before the search starts.
  std::vector<Recording> recordings;
  for (const auto& dir : recording_dirs(args.recordings)) recordings.push_back(read_recording(dir));
  if (args.cross_validate && recordings.size() < 2) throw InputError("--cross-validate", "", "needs at least two recordings");

  // Ctrl-C: the search stops at once (a replay under way at its next cycle) and writes the best so far.
  const FitInterrupt interrupt;
  options.replay.stop = interrupt.flag();
  std::cout << fmt::format("rcsim calibrate: {} recording(s), fitting {}, seed {}\n", recordings.size(), args.fit, options.seed);
  const auto progress = [](double step_db, double objective, int evaluations) {
    if (step_db == 0.0) {
      std::cout << fmt::format("  start: objective {:.4f} after {} evaluation (Ctrl-C: stop, keep the best so far)\n",
                               objective, evaluations);
      std::cout.flush();
      return;
    }
    std::cout << fmt::format("  step {:5.2f} dB: objective {:.4f} after {} evaluations\n", step_db, objective, evaluations);
    std::cout.flush();
  };
  replay::CalibrationResult result;
  try {
    result = replay::calibrate(recordings, options, progress);
  } catch (const replay::ReplayStopped&) {
    throw FitInterrupted("stopped during the first evaluation (the starting parameters): nothing written; run the same "
                         "command again");
  }
  if (result.partial) std::cout << "interrupted: the best parameters so far\n";

  std::cout << fmt::format("\n{:<48} {:>10} {:>10} {:>11}\n", "parameter", "initial", "fitted", "change");
  for (const auto& p : result.parameters) {
    std::cout << fmt::format("{:<64} {:>10.4g} {:>10.4g} {:>11}\n", p.name, p.initial, p.value, change_text(p));
  }
  print_fits(fmt::format("fitted on all {} (objective: mean GOSPA after / before = {:.3f})", recordings.size(),
                         result.objective_after),
             result.recordings);
  if (result.flat) {
    std::cout << fmt::format("\nthe objective is flat: {:.4f} at each of the {} evaluations; no parameter changed it, so "
                             "nothing was fitted (docs/calibration.md, a flat objective)\n",
                             result.objective_after, result.evaluations);
  }

  std::vector<replay::RecordingFit> held_out;
  if (args.cross_validate && !result.partial) {
    std::cout << "\nleave-one-out: fitting on all but one recording, in turn\n";
    held_out = replay::cross_validate(recordings, options, [](const replay::RecordingFit& f) {
      std::cout << fmt::format("  {}: {:.3f} m -> {:.3f} m\n", f.recording, f.gospa_before_m, f.gospa_after_m);
      std::cout.flush();
    });
    print_fits("held out (each recording with the parameters fitted on the others)", held_out);
  }
  replay::write_calibration(args.output_dir, result, options, recordings, args.cross_validate ? &held_out : nullptr);
  std::cout << fmt::format("\ncalibration written to {}; use it with rcsim replay or rcsim bench --calibration {}\n",
                           args.output_dir, args.output_dir);
  if (result.partial) throw FitInterrupted(interrupted_text(args, result.evaluations));
}

}  // namespace

void add_calibrate_command(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  auto* cmd = app.add_subcommand("calibrate", "fit the reflectors' ERCS (and optionally the amplitude law) to recordings");
  cmd->add_option("RECORDING_DIR", args->recordings, "recordings (rcsim-recording); default: every one in ./recordings_synthetic");
  cmd->add_option("-o,--output", args->output_dir, "calibration directory to write (rcsim-calibration)")->required();
  cmd->add_option("--fit", args->fit, std::string("comma-separated parameter groups: ") + std::string(replay::kParameterGroupNames))
      ->capture_default_str();
  add_seed_option(*cmd, args->seed, "seed of the model's random draws during the search");
  cmd->add_option("--initial-step-db", args->initial_step_db, "first search step")
      ->check(CLI::Range(0.01, 40.0))
      ->capture_default_str();
  cmd->add_option("--final-step-db", args->final_step_db, "the step halves while at least this")
      ->check(CLI::Range(0.01, 40.0))
      ->capture_default_str();
  cmd->add_option("--start", args->start_dir,
                  "calibration directory to start from instead of the built-ins (an earlier fit, one interrupted by "
                  "Ctrl-C too, or hand-edited models); with --real-drive its sensor profile's values start the search");
  cmd->add_flag("--cross-validate", args->cross_validate,
                "also fit on all recordings but one, in turn, and report each held-out recording's GOSPA");
  cmd->add_flag("--real-drive", args->real_drive,
                "fit a radar-equation profile's reference RCS, diffuse face return, occlusion loss (and a relative "
                "level's range exponent), and the stationary background, to real drives by their object counts and "
                "detection rates, by a bounded search (docs/sensor-profiles.md)");
  cmd->add_flag("--hold-out", args->hold_out,
                "with --real-drive: also fit on the first half of each recording's cycles (frames) and measure on the "
                "second (single frames, up to 20: leave one frame out, each frame measured with the fit on the "
                "others), and with two radars on one and measure on the other (both ways)");
  cmd->add_option("--sensor", args->sensor,
                  "with --real-drive: fit this profile (built-in name or rcsim-sensor file, e.g. from rcsim profile "
                  "derive) for every sensor instead of the recordings' type; replay with the same --sensor and the "
                  "--calibration written");
  cmd->add_option("--max-evaluations", args->max_evaluations, "with --real-drive: the search's budget of replays per fit")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  cmd->callback([args] { run_calibrate(*args); });
}

}  // namespace rcsim::cli
