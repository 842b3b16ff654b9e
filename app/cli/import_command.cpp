// rcsim import RECORDING_DIR -o SCENE.json: a scene from a recording's ego log and annotated boxes.
// rcsim import --from DATASET RAW_DIR -o RECORDING_DIR [--frames LIST]: a recording from a real dataset's layout.
#include <fmt/format.h>
#include <iostream>

#include "cli/commands.hpp"
#include "cli/replay_options.hpp"
#include "common/atomic_file.hpp"
#include "io/recording.hpp"
#include "replay/import/dataset_importer.hpp"
#include "replay/import/importer.hpp"

namespace rcsim::cli {

namespace {

void import_dataset(const std::string& dataset, const std::string& raw_dir, const std::string& output,
                    const replay::DatasetImportOptions& options) {
  const replay::DatasetImporter& importer = replay::find_dataset_importer(dataset);
  check_output_directory(std::filesystem::absolute(output).lexically_normal(), "recording.json");  // before the work
  const replay::DatasetRecording imported = importer.import(raw_dir, options);
  for (const auto& warning : imported.warnings) std::cerr << "rcsim: warning: " << warning << '\n';
  write_recording(output, imported.recording, imported.extra_files);
  const Recording& rec = imported.recording;
  std::cout << fmt::format("{}: {} cycles, {} sensor{}, {} objects, {} targets; written to {}\n", rec.name,
                           rec.cycle_count(), rec.sensors.size(), rec.sensors.size() == 1 ? "" : "s",
                           rec.objects.size(), rec.targets.size(), output);
}

}  // namespace

void add_import_command(CLI::App& app) {
  struct Args {
    std::string input_dir;
    std::string output;
    std::string dataset;
    std::string ego_log;
    std::string frames;
    ImportArgs import;
  };
  auto args = std::make_shared<Args>();
  std::string datasets;
  for (const auto& importer : replay::dataset_importers()) {
    datasets += fmt::format("\n  {}: {}", importer.name, importer.description);
  }
  auto* cmd = app.add_subcommand(
      "import",
      "a scene from a recording's ego log and annotated object boxes; with --from, a recording from a real "
      "dataset's own layout");
  cmd->add_option("INPUT_DIR", args->input_dir,
                  "recording directory (rcsim-recording); with --from, the dataset's directory")
      ->required();
  cmd->add_option("-o,--output", args->output,
                  "scene file to write (rcsim-scene); with --from, the recording directory to write")
      ->required();
  auto* from = cmd->add_option("--from", args->dataset, "import a real dataset (docs/importers.md):" + datasets);
  cmd->add_option("--ego-log", args->ego_log,
                  "with --from: the ego log to use, in ego.csv's columns (t_s from the first keyframe, x_m, y_m, "
                  "yaw_rad, speed_mps, yaw_rate_radps); without it the ego motion is estimated from the Doppler")
      ->check(CLI::ExistingFile);
  cmd->add_option("--frames", args->frames,
                  "(--from astyx) the frames to import by their number in the dataset: 0-199, 200-399, 0,4 or 0-9,20; "
                  "default all (a fit set and a held-out set are two imports)")
      ->type_name("LIST")
      ->needs(from);
  add_import_options(*cmd, args->import);
  cmd->callback([args] {
    if (!args->dataset.empty()) {
      import_dataset(args->dataset, args->input_dir, args->output, {args->ego_log, args->frames});
      return;
    }
    const Recording recording = read_recording(args->input_dir);
    const replay::ImportedScene scene =
        replay::import_recording(recording, ModelLibrary::builtin(), import_options(args->import));
    for (const auto& warning : scene.warnings) std::cerr << "rcsim: warning: " << warning << '\n';
    replay::write_scene_file(args->output, scene);
  });
}

}  // namespace rcsim::cli
