// rcsim bench [RECORDING_DIR ...]: speed against error of every fidelity level, the signal-level
// reference and the noise floor (docs/bench.md); optionally stored for rcsim report.
#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli/commands.hpp"
#include "cli/fidelity_option.hpp"
#include "cli/recording_dirs.hpp"
#include "cli/replay_options.hpp"
#include "cli/seed_option.hpp"
#include "common/input_error.hpp"
#include "common/safe_text.hpp"
#include "replay/evaluate/bench.hpp"
#include "replay/store/bench_store.hpp"
#include "replay/import/calibration.hpp"
#include "replay/store/report_store.hpp"

namespace rcsim::cli {

namespace {

struct BenchArgs {
  std::vector<std::string> recordings;
  std::string db_path;
  std::uint64_t seed = kDefaultSeed;
  std::string levels = "full,no_monopulse,points_only,no_tracking";
  bool no_reference = false;
  bool json = false;
  double min_timing_cpu_s = replay::BenchOptions{}.min_timing_cpu_s;
  std::string calibration;
};

std::vector<Fidelity> parse_levels(const std::string& list) {
  std::vector<Fidelity> levels;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, comma - start);
    if (name == "none") {
      // no model level: only the reference rows
    } else if (const auto f = parse_fidelity(name)) {
      if (std::find(levels.begin(), levels.end(), *f) == levels.end()) levels.push_back(*f);
    } else {
      throw InputError("--levels", name, std::string("unknown fidelity level; one of ") + std::string(kFidelityNames) + ", or none");
    }
    start = comma + 1;
  }
  return levels;
}

std::string speed_text(double v) { return v < 0.0 ? "-" : fmt::format("{:.0f}", v); }
std::string ratio_text(double v) { return v < 0.0 ? "-" : fmt::format("{:.2f}", v); }
std::string latency_text(bool has, double v) { return has ? fmt::format("{:+.3f}", v) : "-"; }

void print_row_header(std::ostream& out) {
  out << fmt::format("{:<24} {:<13} {:>14} {:>9} {:>7} {:>7} {:>18} {:>9}\n", "recording", "level", "cycles/CPU s",
                     "GOSPA m", "/floor", "tgt x", "merge fnd/mis/spu", "lat.d s");
}

void print_row(std::ostream& out, const replay::BenchRow& r, double floor_m) {
  out << fmt::format("{:<24} {:<13} {:>14} {:>9.3f} {:>7} {:>7} {:>18} {:>9}\n", r.recording_name.substr(0, 24), r.level,
                     speed_text(r.sensor_cycles_per_cpu_s), r.gospa_mean_m,
                     floor_m > 0.0 ? fmt::format("{:.2f}", r.gospa_mean_m / floor_m) : "-",
                     ratio_text(r.targets_per_cycle_ratio),
                     fmt::format("{}/{}/{}", r.merge_found, r.merge_missed, r.merge_spurious),
                     latency_text(r.has_latency, r.latency_difference_s));
}

void print_summary(std::ostream& out, const std::vector<replay::BenchRow>& rows) {
  out << "\nall recordings (speed: all timed sensor cycles / all CPU time; errors: mean over recordings; "
         "/floor: mean GOSPA / mean noise floor)\n";
  out << fmt::format("{:<13} {:>14} {:>9} {:>7} {:>7} {:>18} {:>9}\n", "level", "cycles/CPU s", "GOSPA m", "/floor",
                     "tgt x", "merge fnd/mis/spu", "lat.d s");
  for (const auto& l : replay::summarise_levels(rows)) {
    out << fmt::format("{:<13} {:>14} {:>9.3f} {:>7} {:>7} {:>18} {:>9}\n", l.level, speed_text(l.sensor_cycles_per_cpu_s),
                       l.gospa_mean_m, ratio_text(l.gospa_over_noise_floor), ratio_text(l.targets_per_cycle_ratio),
                       fmt::format("{}/{}/{}", l.merge_found, l.merge_missed, l.merge_spurious),
                       latency_text(l.has_latency, l.latency_difference_s));
  }
  const replay::BenchGoals g = replay::evaluate_goals(rows);
  if (!g.evaluable) {
    out << "\ngoals: not evaluated (they need the levels full, reference and noise_floor)\n";
    return;
  }
  const auto met = [](bool ok) { return ok ? "met" : "NOT met"; };
  out << fmt::format("\ngoals (docs/bench.md):\n  default level (full) error {:.3f} m within 10 % of the best level's "
                     "({}, {:.3f} m): {}\n",
                     g.default_error_m, g.best_level, g.best_error_m, met(g.within_10_percent));
  out << fmt::format("  default level at least 100 x faster than the reference: {:.0f} x: {}\n", g.speedup, met(g.at_least_100x));
  std::string misses, floor_misses;
  int within = 0, within_floor = 0;
  for (const auto& p : g.per_recording) {
    if (p.within_1_1_reference) {
      ++within;
    } else {
      misses += fmt::format("{}{} ({:.2f} x)", misses.empty() ? "" : ", ", p.recording, p.over_reference);
    }
    if (p.within_1_5) {
      ++within_floor;
    } else {
      floor_misses += fmt::format("{}{} ({:.2f} x)", floor_misses.empty() ? "" : ", ", p.recording, p.ratio);
    }
  }
  out << fmt::format("  default level GOSPA within 1.1 x the reference's on the imported scene on every recording: {} of {}: "
                     "{}{}\n", within, g.per_recording.size(), met(g.all_within_1_1_reference),
                     misses.empty() ? "" : "; over on " + misses);
  out << fmt::format("  (information: within 1.5 x the noise floor on {} of {}{})\n", within_floor, g.per_recording.size(),
                     floor_misses.empty() ? "" : "; over on " + floor_misses);
  const auto reference_within = std::count_if(g.per_recording.begin(), g.per_recording.end(),
                                              [](const auto& p) { return p.reference_ratio <= 1.5; });
  out << fmt::format("  (for comparison, the reference on the imported scene is within 1.5 x the noise floor on {} of {})\n",
                     reference_within, g.per_recording.size());
}

// A figure, or null where it does not exist.
nlohmann::ordered_json optional(bool present, double v) { return present ? nlohmann::ordered_json(v) : nlohmann::ordered_json(); }

nlohmann::ordered_json row_json(const replay::BenchRow& r) {
  return {{"recording", r.recording_name},
          {"recording_checksum", fmt::format("{:016x}", r.recording_checksum)},
          {"level", r.level},
          {"sensor_cycles", r.sensor_cycles},
          {"cpu_s", optional(r.cpu_s >= 0.0, r.cpu_s)},
          {"sensor_cycles_per_cpu_s", optional(r.sensor_cycles_per_cpu_s >= 0.0, r.sensor_cycles_per_cpu_s)},
          {"gospa_mean_m", r.gospa_mean_m},
          {"targets_recorded", r.targets_recorded},
          {"targets_simulated", r.targets_simulated},
          {"targets_per_cycle_ratio", optional(r.targets_per_cycle_ratio >= 0.0, r.targets_per_cycle_ratio)},
          {"merge_artefacts", {{"recorded", r.merge_recorded}, {"found", r.merge_found}, {"missed", r.merge_missed}, {"spurious", r.merge_spurious}}},
          {"latency_difference_s", optional(r.has_latency, r.latency_difference_s)},
          {"latency_pairs", r.latency_pairs}};
}

nlohmann::ordered_json bench_json(const replay::BenchOptions& options, const std::string& machine, std::int64_t bench_id,
                                  const std::vector<replay::BenchRow>& rows) {
  nlohmann::ordered_json j = {{"format", "rcsim-bench"}, {"version", 2}};
  j["bench_id"] = bench_id > 0 ? nlohmann::ordered_json(bench_id) : nlohmann::ordered_json();
  j["machine"] = machine;
  j["seed"] = options.seed;
  j["parameters"] = replay::bench_parameters_json(options);
  j["rows"] = nlohmann::ordered_json::array();
  for (const auto& r : rows) j["rows"].push_back(row_json(r));
  j["levels"] = nlohmann::ordered_json::array();
  for (const auto& l : replay::summarise_levels(rows)) {
    j["levels"].push_back({{"level", l.level},
                           {"recordings", l.recordings},
                           {"sensor_cycles", l.sensor_cycles},
                           {"sensor_cycles_per_cpu_s", optional(l.sensor_cycles_per_cpu_s >= 0.0, l.sensor_cycles_per_cpu_s)},
                           {"gospa_mean_m", l.gospa_mean_m},
                           {"gospa_over_noise_floor", optional(l.gospa_over_noise_floor >= 0.0, l.gospa_over_noise_floor)},
                           {"targets_per_cycle_ratio", optional(l.targets_per_cycle_ratio >= 0.0, l.targets_per_cycle_ratio)},
                           {"merge_artefacts", {{"recorded", l.merge_recorded}, {"found", l.merge_found}, {"missed", l.merge_missed}, {"spurious", l.merge_spurious}}},
                           {"latency_difference_s", optional(l.has_latency, l.latency_difference_s)},
                           {"latency_pairs", l.latency_pairs}});
  }
  const replay::BenchGoals g = replay::evaluate_goals(rows);
  if (g.evaluable) {
    nlohmann::ordered_json per = nlohmann::ordered_json::array();
    for (const auto& p : g.per_recording) {
      per.push_back({{"recording", p.recording}, {"gospa_over_reference", p.over_reference},
                     {"met", p.within_1_1_reference}, {"gospa_over_noise_floor", p.ratio},
                     {"within_1_5_noise_floor", p.within_1_5}, {"reference_gospa_over_noise_floor", p.reference_ratio}});
    }
    j["goals"] = {{"default_within_10_percent_of_best", {{"default_m", g.default_error_m}, {"best_m", g.best_error_m}, {"best_level", g.best_level}, {"met", g.within_10_percent}}},
                  {"default_at_least_100x_faster_than_reference", {{"speedup", g.speedup}, {"met", g.at_least_100x}}},
                  {"default_within_1_1_reference", {{"recordings", per}, {"met", g.all_within_1_1_reference}}},
                  {"noise_floor_information", {{"within_1_5", g.all_within_1_5}}}};
  } else {
    j["goals"] = nullptr;
  }
  return j;
}

void run_bench(const BenchArgs& args) {
  replay::BenchOptions options;
  options.seed = args.seed;
  options.levels = parse_levels(args.levels);
  options.reference = !args.no_reference;
  options.min_timing_cpu_s = args.min_timing_cpu_s;
  options.replay.import.calibration_dir = args.calibration;
  if (options.levels.empty() && !options.reference) throw InputError("--levels", args.levels, "nothing to bench: no level and --no-reference");
  // Every recording is read (and refused) before anything is measured or stored.
  std::vector<Recording> recordings;
  for (const auto& dir : recording_dirs(args.recordings)) recordings.push_back(read_recording(dir));
  const auto db = args.db_path.empty() ? nullptr : replay::open_report_database(args.db_path, true);
  const std::string machine = replay::machine_description();
  std::ostream& progress = args.json ? std::cerr : std::cout;
  progress << fmt::format("rcsim bench: {} recording(s), seed {}, on {}\n", recordings.size(), options.seed, machine);
  if (!args.calibration.empty()) {
    // A calibration fitted on a recording makes that recording's errors in-sample: say so.
    const auto calibration = replay::load_calibration(args.calibration);
    const auto& fitted = calibration->fitted_on_checksums;
    std::string in_sample;
    for (const Recording& r : recordings) {
      if (std::find(fitted.begin(), fitted.end(), fmt::format("{:016x}", r.checksum)) != fitted.end()) {
        if (!in_sample.empty()) in_sample += ", ";
        in_sample += r.name;
      }
    }
    progress << fmt::format("calibration {}{}\n", args.calibration,
                            in_sample.empty() ? std::string(": fitted on none of these recordings")
                                              : ": fitted on " + in_sample + " (their errors are in-sample)");
  }
  print_row_header(progress);
  std::vector<replay::BenchRow> rows;
  for (std::size_t i = 0; i < recordings.size(); ++i) {
    // The reference row waits for the noise floor (measured after it) so that it shows its ratio too.
    double floor_m = -1.0;
    std::optional<replay::BenchRow> reference;
    const auto done = [&](const replay::BenchRow& r) {
      if (r.level == replay::kReferenceLevel) {
        reference = r;
        return;
      }
      if (r.level == replay::kNoiseFloorLevel) floor_m = r.gospa_mean_m;
      if (reference) {
        print_row(progress, *reference, floor_m);
        reference.reset();
      }
      print_row(progress, r, floor_m);
      progress.flush();
    };
    // What the import noticed, as rcsim replay prints it (stderr, also with --json).
    const auto warn = [&](const std::string& warning) {
      progress.flush();
      std::cerr << "rcsim: warning: " << escape_control_characters(warning) << '\n';
    };
    for (auto& r : replay::bench_recording(recordings[i], static_cast<int>(i), options, done, warn)) rows.push_back(std::move(r));
  }
  if (!args.json) print_summary(std::cout, rows);
  const std::int64_t bench_id = db ? replay::store_bench(*db, options, machine, rows) : 0;
  if (args.json) {
    std::cout << bench_json(options, machine, bench_id, rows).dump(2) << '\n';
  } else if (db) {
    std::cout << fmt::format("\nbench {} stored in {}; rcsim report {} -o REPORT.html shows it\n", bench_id, args.db_path, args.db_path);
  }
}

}  // namespace

void add_bench_command(CLI::App& app) {
  auto args = std::make_shared<BenchArgs>();
  auto* cmd = app.add_subcommand("bench", "speed against error: every fidelity level, the signal-level reference and the noise floor over recordings");
  cmd->add_option("RECORDING_DIR", args->recordings, "recordings (rcsim-recording); default: every one in ./recordings_synthetic");
  cmd->add_option("--db", args->db_path, "report database (rcsim-report) to store the bench in; created if missing");
  add_seed_option(*cmd, args->seed, "seed of the model (the reference's are seed + 1 and seed + 2)");
  cmd->add_option("--levels", args->levels, std::string("comma-separated model levels: ") + std::string(kFidelityNames) + ", or none")
      ->capture_default_str();
  cmd->add_flag("--no-reference", args->no_reference, "skip the signal-level reference and the noise floor (the slow rows)");
  cmd->add_option("--min-cpu-s", args->min_timing_cpu_s, "model levels: repeat the timed pass over a recording until this much CPU time")
      ->check(CLI::Range(0.0, 60.0))
      ->capture_default_str();
  cmd->add_flag("--json", args->json, "print the table as JSON (rcsim-bench v2, schemas/bench.md); progress goes to stderr");
  add_calibration_option(*cmd, args->calibration);
  cmd->callback([args] { run_bench(*args); });
}

}  // namespace rcsim::cli
