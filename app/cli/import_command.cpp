// rcsim import --from DATASET RAW_DIR -o RECORDING_DIR [--frames LIST]: a recording from a real dataset's layout.
// rcsim scene RECORDING_DIR -o SCENE.json: a scene from a recording's ego log and annotated boxes
// (once spelt `rcsim import RECORDING_DIR`, which still works and says so).
#include <fmt/format.h>
#include <iostream>

#include "cli/commands.hpp"
#include "cli/replay_options.hpp"
#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "common/safe_text.hpp"
#include "io/recording.hpp"
#include "replay/import/dataset_importer.hpp"
#include "replay/import/importer.hpp"
#include "replay/profile/sensor_clocks.hpp"

namespace rcsim::cli {

namespace {

// The recording with each sensor on the clock its static world's shift shows (sensor_clocks.hpp),
// each clock said in one line.
Recording on_estimated_clocks(const Recording& keyframed, const std::string& raw_dir) {
  Recording named = keyframed;
  named.dir = raw_dir;  // refusals name the dataset
  const std::vector<replay::profile::SensorClock> clocks = replay::profile::estimate_sensor_clocks(named);
  for (const auto& c : clocks) {
    std::cerr << fmt::format("rcsim import: {}: its own clock, period {:.1f} ms ({} of {} steps timed, residual {:.1f} ms RMS, "
                             "{} skipping frames); keyframes minus frames {:+.1f} to {:+.1f} ms\n",
                             c.sensor, 1e3 * c.period_s, c.steps_matched, c.steps, 1e3 * c.step_residual_rms_s, c.steps_skipping,
                             1e3 * c.offset_min_s, 1e3 * c.offset_max_s);
  }
  return replay::profile::on_estimated_clocks(keyframed, clocks);
}

void import_dataset(const std::string& dataset, const std::string& raw_dir, const std::string& output,
                    const replay::DatasetImportOptions& options, const std::string& sensor_clocks) {
  const replay::DatasetImporter& importer = replay::find_dataset_importer(dataset);
  if (options.skip_edges && importer.import_to == nullptr) {
    throw InputError(raw_dir, "--skip-edges", fmt::format("--from {} takes no --skip-edges: it is for a robot's log (--from mcap, rosbag2)", dataset));
  }
  check_output_directory(std::filesystem::absolute(output).lexically_normal(), "recording.json");  // before the work
  if (importer.import_to != nullptr && sensor_clocks != "estimated") {  // streamed to disk
    const replay::ImportSummary s = importer.import_to(raw_dir, options, output);
    for (const auto& warning : s.warnings) std::cerr << "rcsim: warning: " << escape_control_characters(warning) << '\n';
    std::cout << fmt::format("{}: {} sensor cycles on their own clocks, {} sensor{}, {} objects, {} targets; written to {}\n", s.name,
                             s.cycles, s.sensors, s.sensors == 1 ? "" : "s", s.objects, s.targets, output);
    return;
  }
  replay::DatasetRecording imported = importer.import(raw_dir, options);
  for (const auto& warning : imported.warnings) std::cerr << "rcsim: warning: " << escape_control_characters(warning) << '\n';
  if (sensor_clocks == "estimated") imported.recording = on_estimated_clocks(imported.recording, raw_dir);
  write_recording(output, imported.recording, imported.extra_files);
  const Recording& rec = imported.recording;
  std::cout << fmt::format("{}: {} {}, {} sensor{}, {} objects, {} targets; written to {}\n", rec.name, rec.cycle_count(),
                           rec.clock == Clock::per_sensor ? "sensor cycles on their own clocks" : "cycles",
                           rec.sensors.size(), rec.sensors.size() == 1 ? "" : "s",
                           rec.objects.size(), rec.targets.size(), output);
}

void write_scene_of(const std::string& recording_dir, const std::string& output, const ImportArgs& import) {
  const Recording recording = read_recording(recording_dir);
  if (recording.clock == Clock::per_sensor) {
    std::cerr << fmt::format("rcsim: warning: {}: the sensors' own clocks are not part of a scene: it runs every sensor "
                             "every {} s\n", recording_dir, recording.cycle_time_s);
  }
  const replay::ImportedScene scene = replay::import_recording(recording, ModelLibrary::builtin(), import_options(import));
  for (const auto& warning : scene.warnings) std::cerr << "rcsim: warning: " << escape_control_characters(warning) << '\n';
  replay::write_scene_file(output, scene);
}

}  // namespace

void add_scene_command(CLI::App& app) {
  struct Args {
    std::string recording_dir;
    std::string output;
    ImportArgs import;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("scene", "a scene from a recording's ego log and annotated object boxes");
  cmd->add_option("RECORDING_DIR", args->recording_dir, "recording directory (rcsim-recording)")->required();
  cmd->add_option("-o,--output", args->output, "scene file to write (rcsim-scene)")->required();
  add_import_options(*cmd, args->import);
  cmd->callback([args] { write_scene_of(args->recording_dir, args->output, args->import); });
}

void add_import_command(CLI::App& app) {
  struct Args {
    std::string input_dir;
    std::string output;
    std::string dataset;
    std::string ego_log;
    std::string frames;
    std::string sensor_clocks = "keyframe";
    std::string mapping;
    bool skip_edges = false;
    ImportArgs import;
  };
  auto args = std::make_shared<Args>();
  std::string datasets;
  for (const auto& importer : replay::dataset_importers()) {
    datasets += fmt::format("\n  {}: {}", importer.name, importer.description);
  }
  auto* cmd = app.add_subcommand("import", "a recording from a real dataset's own layout (--from DATASET)");
  cmd->add_option("INPUT_DIR", args->input_dir, "the dataset's directory")->required();
  cmd->add_option("-o,--output", args->output, "the recording directory to write")->required();
  auto* from = cmd->add_option("--from", args->dataset, "the dataset's kind (docs/importers.md):" + datasets);
  cmd->add_option("--ego-log", args->ego_log,
                  "with --from: the ego log to use, in ego.csv's columns (t_s from the first keyframe, x_m, y_m, "
                  "yaw_rad, speed_mps, yaw_rate_radps); without it the ego motion is estimated from the Doppler")
      ->check(CLI::ExistingFile);
  cmd->add_option("--frames", args->frames,
                  "(--from astyx, vod) the frames to import by their number in the dataset: 0-199, 200-399, 0,4 or 0-9,20; "
                  "default all (a fit set and a held-out set are two imports)")
      ->type_name("LIST")
      ->needs(from);
  cmd->add_option("--mapping", args->mapping,
                  "(--from mcap) the mapping file: which topic is which radar (with its mounting and profile), the "
                  "ego motion and the annotated boxes (schemas/mcap-mapping.md)")
      ->check(CLI::ExistingFile)
      ->type_name("FILE")
      ->needs(from);
  cmd->add_flag("--skip-edges", args->skip_edges,
               "(--from mcap, rosbag2) leave out, and count, a real log's edges: scans beyond the ego log, scans and ego "
               "poses stamped as the one before (refused otherwise)")
      ->needs(from);
  cmd->add_option("--sensor-clocks", args->sensor_clocks,
                  "(--from aimotive) keyframe: every radar frame stamped with its keyframe's time, as the dataset gives "
                  "it; estimated: each radar on its own clock, timed by the static world's shift (recording v4)")
      ->check(CLI::IsMember({"keyframe", "estimated"}))
      ->type_name("WORD")
      ->needs(from);
  add_import_options(*cmd, args->import);
  cmd->callback([args] {
    if (!args->dataset.empty()) {
      import_dataset(args->dataset, args->input_dir, args->output, {args->ego_log, args->frames, args->mapping, args->skip_edges},
                     args->sensor_clocks);
      return;
    }
    // The old spelling of `rcsim scene`: still works, and says so.
    std::cerr << "rcsim: note: `rcsim import RECORDING_DIR -o SCENE.json` is now `rcsim scene RECORDING_DIR -o "
                 "SCENE.json` (`import` takes --from DATASET); writing the scene\n";
    write_scene_of(args->input_dir, args->output, args->import);
  });
}

}  // namespace rcsim::cli
