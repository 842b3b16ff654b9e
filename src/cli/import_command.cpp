// rcsim import RECORDING_DIR -o SCENE.json: a scene from a recording's ego log and annotated boxes.
#include <iostream>

#include "cli/commands.hpp"
#include "cli/replay_options.hpp"
#include "io/recording.hpp"
#include "replay/import/importer.hpp"

namespace rcsim::cli {

void add_import_command(CLI::App& app) {
  struct Args {
    std::string recording_dir;
    std::string output;
    ImportArgs import;
  };
  auto args = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("import", "a scene from a recording's ego log and annotated object boxes");
  cmd->add_option("RECORDING_DIR", args->recording_dir, "recording directory (rcsim-recording)")->required();
  cmd->add_option("-o,--output", args->output, "scene file to write (rcsim-scene)")->required();
  add_import_options(*cmd, args->import);
  cmd->callback([args] {
    const Recording recording = read_recording(args->recording_dir);
    const replay::ImportedScene scene =
        replay::import_recording(recording, ModelLibrary::builtin(), import_options(args->import));
    for (const auto& warning : scene.warnings) std::cerr << "rcsim: warning: " << warning << '\n';
    replay::write_scene_file(args->output, scene);
  });
}

}  // namespace rcsim::cli
