// rcsim replay RECORDING_DIR --db REPORT.sqlite: import, re-simulate, compare per cycle, store.
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/fidelity_option.hpp"
#include "cli/fit_progress.hpp"
#include "cli/replay_options.hpp"
#include "cli/seed_option.hpp"
#include "cli/verdict_options.hpp"
#include "common/safe_text.hpp"
#include "io/recording.hpp"
#include "io/recording_stream.hpp"
#include "model/model_library.hpp"
#include "replay/import/calibration.hpp"
#include "replay/import/importer.hpp"
#include "replay/run/run_sink_wrapper.hpp"
#include "replay/run/replay_run.hpp"
#include "replay/store/report_store.hpp"
#include "replay/store/run_identity.hpp"

namespace rcsim::cli {

namespace {

struct ReplayArgs {
  std::string recording_dir;
  std::string db_path;
  std::uint64_t seed = kDefaultSeed;
  bool json = false;
  std::string fidelity;  // empty: from what the recording's sensors report
  double cutoff_m = 2.0;
  double order_p = 2.0;
  double gate_m = 1.0;
  double stationary_gate_mps = 0.5;
  ImportArgs import;
  std::string calibration;
  std::string store = "full";  // what the report keeps (schemas/report-database.md)
  VerdictArgs verdicts;
  bool again = false;  // store a run whose identity the report holds already
};

const replay::QuantityDistance* find_distance(const replay::ReplaySummary& s, const std::string& quantity) {
  for (const auto& d : s.distances) {
    if (d.quantity == quantity) return &d;
  }
  return nullptr;
}

std::string percent_of(long long part, long long whole) {
  return whole > 0 ? fmt::format("{:.1f} %", 100.0 * static_cast<double>(part) / static_cast<double>(whole)) : "-";
}

// The figures that tell the annotated objects from the unmodelled world, and the latency and
// merge-artefact figures judged against the scene geometry (docs/metrics.md).
void print_class_figures(const replay::ReplaySummary& s, bool snapshots) {
  long long in_view = 0, detected_recorded = 0, detected_simulated = 0;
  for (const auto& o : s.objects) {
    in_view += o.cycles_in_view;
    detected_recorded += o.cycles_detected_recorded;
    detected_simulated += o.cycles_detected_simulated;
  }
  std::cout << fmt::format("  objects: {} / {} targets, GOSPA mean {:.3f} m, OSPA mean {:.3f} m; detection rate {} / {} "
                           "of {} object-sensor cycles in view\n",
                           s.classes.object[0], s.classes.object[1], s.gospa_object_mean_m, s.ospa_object_mean_m,
                           percent_of(detected_recorded, in_view), percent_of(detected_simulated, in_view), in_view);
  const double sensor_cycles = std::max(1.0, static_cast<double>(s.sensor_cycles));
  std::string distances;
  for (const char* q : {"background_range", "background_azimuth"}) {
    const replay::QuantityDistance* d = find_distance(s, q);
    if (d == nullptr || std::isnan(d->distance.wasserstein1)) continue;
    distances += fmt::format(", {} W1 {:.3g} {} KS {:.3f}", std::string_view(q).substr(11), d->distance.wasserstein1,
                             d->unit, d->distance.kolmogorov_smirnov);
  }
  const std::string latency =
      snapshots
          ? std::string("none (snapshots: no time between the frames to confirm in)")
          : fmt::format("simulated - recorded {} over {} episodes both confirmed; never confirmed {} / {} of {} episodes",
                        s.latency_pairs > 0 ? fmt::format("{:+.3f} s", s.latency_difference_mean_s) : std::string("-"),
                        s.latency_pairs, s.latency_unconfirmed_recorded, s.latency_unconfirmed_simulated,
                        s.latency_episodes);
  std::cout << fmt::format("  latency: {}; merge artefacts matched by position {} of {}\n", latency,
                           s.merge_artefacts_matched, s.merge_artefacts_recorded);
  std::cout << fmt::format("  stationary background: {} / {} targets ({:.2f} / {:.2f} per sensor cycle){}; other: {} / {}\n",
                           s.classes.background[0], s.classes.background[1],
                           static_cast<double>(s.classes.background[0]) / sensor_cycles,
                           static_cast<double>(s.classes.background[1]) / sensor_cycles, distances, s.classes.other[0],
                           s.classes.other[1]);
}

nlohmann::ordered_json summary_json(std::int64_t run_id, const Recording& rec, const replay::ReplaySummary& s) {
  const auto optional = [](double value) { return value < 0.0 ? nlohmann::ordered_json() : nlohmann::ordered_json(value); };
  nlohmann::ordered_json distances = nlohmann::ordered_json::object();
  for (const auto& d : s.distances) {
    distances[d.quantity] = {{"wasserstein1", std::isnan(d.distance.wasserstein1) ? nlohmann::ordered_json() : nlohmann::ordered_json(d.distance.wasserstein1)},
                             {"kolmogorov_smirnov", std::isnan(d.distance.kolmogorov_smirnov) ? nlohmann::ordered_json() : nlohmann::ordered_json(d.distance.kolmogorov_smirnov)},
                             {"unit", d.unit}};
  }
  long long in_view = 0, detected[2] = {0, 0};
  for (const auto& o : s.objects) {
    in_view += o.cycles_in_view;
    detected[0] += o.cycles_detected_recorded;
    detected[1] += o.cycles_detected_simulated;
  }
  const nlohmann::ordered_json classes = {
      {"object", {{"recorded", s.classes.object[0]}, {"simulated", s.classes.object[1]}}},
      {"background", {{"recorded", s.classes.background[0]}, {"simulated", s.classes.background[1]}}},
      {"other", {{"recorded", s.classes.other[0]}, {"simulated", s.classes.other[1]}}}};
  return {{"run_id", run_id},
          {"recording", rec.name},
          {"cycles", s.cycles},
          {"sensors", rec.sensors.size()},
          {"targets_recorded", s.targets_recorded},
          {"targets_simulated", s.targets_simulated},
          {"targets_matched", s.targets_matched},
          {"gospa_mean", s.gospa_mean_m},
          {"ospa_mean", s.ospa_mean_m},
          {"gospa_object_mean", s.gospa_object_mean_m},
          {"ospa_object_mean", s.ospa_object_mean_m},
          {"target_classes", classes},
          {"object_sensor_cycles_in_view", in_view},
          {"object_cycles_detected_recorded", detected[0]},
          {"object_cycles_detected_simulated", detected[1]},
          {"merge_artefacts_recorded", s.merge_artefacts_recorded},
          {"merge_artefacts_simulated", s.merge_artefacts_simulated},
          {"merge_artefacts_matched", s.merge_artefacts_matched},
          {"latency_recorded_s", optional(s.latency_recorded_s)},
          {"latency_simulated_s", optional(s.latency_simulated_s)},
          {"latency_pairs", s.latency_pairs},
          {"latency_difference_mean_s", s.latency_pairs > 0 ? nlohmann::ordered_json(s.latency_difference_mean_s)
                                                             : nlohmann::ordered_json()},
          {"latency_episodes", s.latency_episodes},
          {"latency_unconfirmed_recorded", s.latency_unconfirmed_recorded},
          {"latency_unconfirmed_simulated", s.latency_unconfirmed_simulated},
          {"residual_range_rms_m", s.residual_range_rms_m},
          {"residual_azimuth_rms_rad", s.residual_azimuth_rms_rad},
          {"residual_range_rate_rms_mps", s.residual_range_rate_rms_mps},
          {"residual_amplitude_mean_db", s.residual_amplitude_mean_db},
          {"distribution_distances", distances},
          {"simulate_cpu_s", s.simulate_cpu_s},
          {"wall_s", s.total_wall_s}};
}

// Prints what the import noticed (bridged or split annotation gaps) to stderr, as rcsim scene
// does: the recording is read as the replay goes, so each warning as soon as it is found, the
// first kMaxPrinted of them, then how many more there were.
class PrintImportWarnings final : public replay::ReplaySink {
 public:
  explicit PrintImportWarnings(replay::ReplaySink& inner) : inner_(inner) {}
  void begin_run(const Recording& r, const replay::ImportedScene& i, const Scene& s,
                 const replay::ReplayOptions& o) override {
    imported_ = &i;
    print_new();
    inner_.begin_run(r, i, s, o);
  }
  void add_cycle(const replay::CycleComparison& c) override {
    if (imported_->warnings.size() > seen_) print_new();
    inner_.add_cycle(c);
  }
  void end_run(const replay::ReplaySummary& s) override {
    print_new();
    const long long more = static_cast<long long>(seen_ - std::min(seen_, kMaxPrinted)) + imported_->warnings_not_kept;
    if (more > 0) std::cerr << "rcsim: warning: " << more << " more warnings of this import not shown\n";
    inner_.end_run(s);
  }

 private:
  static constexpr std::size_t kMaxPrinted = 20;
  void print_new() {
    for (; seen_ < imported_->warnings.size(); ++seen_) {
      if (seen_ < kMaxPrinted) std::cerr << "rcsim: warning: " << escape_control_characters(imported_->warnings[seen_]) << '\n';
    }
  }
  replay::ReplaySink& inner_;
  const replay::ImportedScene* imported_ = nullptr;
  std::size_t seen_ = 0;
};

void replay_and_store(ReplayArgs& args);

void run_replay(ReplayArgs& args) {
  try {
    replay_and_store(args);
  } catch (const replay::StoreError& e) {
    // A full disk or a failing file system while the run was stored: it was rolled back, the runs
    // stored before are intact. Named, with SQLite's reason.
    throw std::runtime_error(fmt::format("{}: cannot store the run: {}; the report keeps the runs stored before it",
                                         args.db_path, e.what()));
  }
}

// The figures under the verdict: all targets, then the classes (print_class_figures).
void print_figures(const Recording& recording, const replay::ReplaySummary& summary,
                   ListLevel kind) {
  std::cout << fmt::format(
      "  all targets: {} recorded / {} simulated, GOSPA mean {:.3f} m{}; merge artefacts {} / {}; latency {} / {}\n",
      summary.targets_recorded, summary.targets_simulated, summary.gospa_mean_m,
      kind == ListLevel::detections ? " (not judged: the background is drawn from a density, docs/verdicts.md)" : "",
      summary.merge_artefacts_recorded, summary.merge_artefacts_simulated,
      summary.latency_recorded_s < 0 ? std::string("-") : fmt::format("{:.3f} s", summary.latency_recorded_s),
      summary.latency_simulated_s < 0 ? std::string("-") : fmt::format("{:.3f} s", summary.latency_simulated_s));
  print_class_figures(summary, recording.timeline == Timeline::snapshots);
}

// The verdict of one run among `verdicts`, if it was judged.
const replay::verdict::RunVerdict* verdict_of(const std::optional<replay::verdict::Verdicts>& verdicts,
                                               std::int64_t run_id) {
  if (!verdicts) return nullptr;
  for (const auto& r : verdicts->runs) {
    if (r.run_id == run_id) return &r;
  }
  return nullptr;
}

// The run's first line says its verdict where it has one.
std::string verdict_word(const replay::verdict::RunVerdict* verdict) {
  return verdict == nullptr ? "stored" : (verdict->passed ? "PASS" : "FAIL");
}

// A run of this identity stored already (the same recording, seed, sensors and parameters give
// the same figures): said, with its verdict, and nothing stored.
bool print_if_stored(replay::ReportDatabase& db, const ReplayArgs& args, const Recording& recording,
                     const replay::ReplayOptions& options) {
  const replay::RunIdentity planned = replay::planned_run_identity(
      recording_checksum(args.recording_dir),
      replay::import_header(recording, 0.0, ModelLibrary::builtin(), options.import), options,
      replay::store_level_from_name(args.store));
  for (const auto& [run_id, identity] : replay::stored_run_identities(db)) {
    if (identity != planned) continue;
    const auto verdicts = judge_runs(db, args.verdicts, run_id, recording.name, true);
    if (args.json) {
      nlohmann::ordered_json json = {{"run_id", run_id}, {"recording", recording.name}, {"already_stored", true}};
      json["verdicts"] = verdicts_json(verdicts);
      std::cout << json.dump(2) << '\n';
    } else {
      const auto* verdict = verdict_of(verdicts, run_id);
      std::cout << fmt::format("run {}: {}: {}, stored already in {} (same recording, seed, sensors and parameters); "
                               "nothing stored, --again stores another copy\n",
                               run_id, recording.name, verdict_word(verdict), args.db_path);
      if (verdict != nullptr) print_run_verdict(std::cout, *verdicts, *verdict);
    }
    throw_if_failed(verdicts);
    return true;
  }
  return false;
}

void store_and_print(replay::ReportDatabase& db, ReplayArgs& args, const Recording& recording,
                     const replay::ReplayOptions& options);

// Reads the criteria and the recording's header, opens the report, and stores the run unless one
// of its identity is there already.
void replay_and_store(ReplayArgs& args) {
  read_verdict_criteria(args.verdicts);  // a bad criteria file is refused before the replay
  // The header only: the rows are read as the replay goes (replay_recording_dir).
  Recording recording = read_recording_header(args.recording_dir);
  replay::ReplayOptions options;
  options.seed = args.seed;
  options.fidelity = args.fidelity.empty() ? default_fidelity_for(recording) : fidelity_from_arg(args.fidelity);
  options.import = import_options(args.import);
  options.import.calibration_dir = args.calibration;
  // A fit interrupted by Ctrl-C is the best so far, not a finished one (issue 53): said before the run.
  if (!args.calibration.empty() && replay::load_calibration(args.calibration)->partial) {
    std::cerr << fmt::format("rcsim: warning: the calibration {} is a partial fit (interrupted, \"partial\": true in its "
                             "calibration.json): the best values so far, not a finished fit; rcsim calibrate --start {} "
                             "continues it\n",
                             args.calibration, args.calibration);
  }
  options.gospa = {args.cutoff_m, args.order_p};
  options.association_gate_m = args.gate_m;
  options.stationary_gate_mps = args.stationary_gate_mps;
  const bool existed = std::filesystem::exists(args.db_path);
  auto db = replay::open_report_database(args.db_path, true);
  // Ctrl-C (issue 53, trap 4: it exited 130 silently and left an empty database): the replay stops
  // at the next cycle boundary and stores nothing, the run being one transaction; the report keeps
  // the runs stored before it, and one this replay created is removed.
  const FitInterrupt interrupt;
  options.stop = interrupt.flag();
  try {
    if (!args.again && print_if_stored(*db, args, recording, options)) return;
    store_and_print(*db, args, recording, options);
  } catch (const replay::ReplayStopped& stopped) {
    if (!existed) replay::discard_if_unused(db, args.db_path);
    const bool kept = db != nullptr && std::filesystem::exists(args.db_path);
    throw FitInterrupted(fmt::format(
        "{}: the replay stopped at cycle {} of {}; nothing of it stored{} (a run is stored whole or not at all); "
        "run the same command again to replay it",
        recording.name, stopped.cycles_done, stopped.cycles,
        kept ? fmt::format(": {} holds the runs stored before, unchanged", args.db_path)
             : fmt::format(", and {}, which this replay created, removed", args.db_path)));
  } catch (...) {
    // A replay refused (a damaged row found as it went) leaves no report it created behind; a
    // stored run keeps it (a failed verdict).
    if (!existed) replay::discard_if_unused(db, args.db_path);
    throw;
  }
}

// The replay stored as one run, judged, and printed verdict first.
void store_and_print(replay::ReportDatabase& db, ReplayArgs& args, const Recording& recording,
                     const replay::ReplayOptions& options) {
  replay::ReportWriter writer(db, replay::store_level_from_name(args.store));
  std::unique_ptr<replay::ReplaySink> wrapper;
  PrintImportWarnings sink(replay::wrapped_run_sink(writer, wrapper));
  const replay::ReplaySummary summary = replay::replay_recording_dir(args.recording_dir, options, sink);
  // The run judged: by --criteria, else the report's own criteria, else the default tolerances of
  // its kind (per-recording criteria only).
  const auto verdicts = judge_runs(db, args.verdicts, writer.run_id(), recording.name, true);
  if (args.json) {
    auto json = summary_json(writer.run_id(), recording, summary);
    json["verdicts"] = verdicts_json(verdicts);
    std::cout << json.dump(2) << '\n';
  } else {
    const replay::RunLabel label = replay::read_run_labels(db, writer.run_id()).at(writer.run_id());
    const auto* verdict = verdict_of(verdicts, writer.run_id());
    std::cout << fmt::format("run {}: {}: {}; stored in {}\n", writer.run_id(), recording.name, verdict_word(verdict),
                             args.db_path);
    std::cout << fmt::format("  {} {}, {} sensor{}, {}; {}\n", summary.cycles,
                             recording.clock == Clock::per_sensor ? "sensor cycles on their own clocks" : "cycles",
                             recording.sensors.size(), recording.sensors.size() == 1 ? "" : "s", label.level,
                             label.text());
    if (verdict != nullptr) print_run_verdict(std::cout, *verdicts, *verdict);
    print_figures(recording, summary, replay::compared_level(label.level, label.fidelity));
  }
  throw_if_failed(verdicts);
}

}  // namespace

void add_replay_command(CLI::App& app) {
  auto args = std::make_shared<ReplayArgs>();
  auto* cmd = app.add_subcommand("replay", "re-simulate a recording, compare it cycle by cycle, store the report");
  cmd->add_option("RECORDING_DIR", args->recording_dir, "recording directory (rcsim-recording)")->required();
  cmd->add_option("--db", args->db_path, "report database (rcsim-report, SQLite); created if missing")->required();
  add_seed_option(*cmd, args->seed, "seed of the simulation's random draws");
  cmd->add_flag("--json", args->json, "print the run's summary as JSON");
  cmd->add_flag("--again", args->again,
                "store the run even if the report holds one of the same identity (recording, seed, sensors, "
                "parameters); without it such a replay says so and stores nothing");
  cmd->add_option("--fidelity", args->fidelity,
                  std::string("fidelity level: ") + std::string(kFidelityNames) +
                      " (docs/fidelity.md); default: full, or no_tracking where every sensor of the recording reports "
                      "raw detections");
  cmd->add_option("--gospa-cutoff-m", args->cutoff_m, "GOSPA/OSPA cut-off c")->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--gospa-order", args->order_p, "GOSPA/OSPA order p")->check(CLI::Range(1.0, 100.0))->capture_default_str();
  cmd->add_option("--gate-m", args->gate_m, "target-to-object association gate")->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--stationary-gate-mps", args->stationary_gate_mps,
                  "stationary background: |range rate - that of a stationary point| at most this (m/s)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--store", args->store,
                  "what the report keeps: full (every target, the annotated boxes, the sensor poses) or summary (the "
                  "per-cycle, per-object and per-run figures, no targets)")
      ->check(CLI::IsMember({"full", "summary"}))
      ->capture_default_str();
  add_import_options(*cmd, args->import);
  add_calibration_option(*cmd, args->calibration);
  add_verdict_options(*cmd, args->verdicts);
  cmd->callback([args] { run_replay(*args); });
}

}  // namespace rcsim::cli
