// rcsim simulate SCENE.json: target lists for every sensor and cycle, or a recording of them.
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include "cli/commands.hpp"
#include "cli/fidelity_option.hpp"
#include "cli/seed_option.hpp"
#include "common/atomic_file.hpp"
#include "io/recording.hpp"
#include "replay/run/model_recording.hpp"
#include "sim/target_list_mcap.hpp"
#include "sim/target_list_writer.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"

namespace rcsim::cli {
namespace {

namespace fs = std::filesystem;

struct SimulateArgs {
  std::string scene_path;
  std::string level = "tracks";
  std::uint64_t seed = kDefaultSeed;
  bool no_noise = false;
  std::string fidelity = "full";
  bool no_culling = false;
  std::string format = "csv";
  std::string output;
};

// --format recording: the scene as its sensors would have recorded it (rcsim-recording), each at
// its own reporting level, the true boxes as annotation: a drive whose profile is known, for
// `rcsim profile derive` or `rcsim replay` to be checked against.
void write_model_recording(const SimulateArgs& args, const Scene& scene) {
  const fs::path dir = fs::path(args.output).lexically_normal();
  const std::string name = (dir.has_filename() ? dir : dir.parent_path()).filename().string();
  const Recording recording = replay::model_recording(scene, name, args.seed);
  write_recording(args.output, recording);
  std::cerr << fmt::format("rcsim simulate: {} cycles of {} sensor(s), {} targets; recording written to {}\n", recording.cycle_count(),
                           recording.sensors.size(), recording.targets.size(), args.output);
}

void run_simulate(const SimulateArgs& args, const CLI::App& cmd) {
  const ModelLibrary library = ModelLibrary::builtin();
  if (args.format == "recording") {
    if (args.output.empty() || args.output == "-") {
      throw CLI::ValidationError("--output", "--format recording writes a directory: name it with -o RECORDING_DIR");
    }
    for (const char* option : {"--level", "--no-noise", "--fidelity"}) {
      if (cmd.count(option) > 0) {
        throw CLI::ValidationError(option, "--format recording writes what each sensor reports, as the full model makes it");
      }
    }
  }
  const Scene scene = load_scene_file(args.scene_path, library);
  if (args.format == "recording") return write_model_recording(args, scene);
  SimulationOptions options;
  options.level = args.level == "ideal" ? ListLevel::ideal
                  : args.level == "detections" ? ListLevel::detections
                                               : ListLevel::tracks;
  options.seed = args.seed;
  options.noise = !args.no_noise;
  options.fidelity = fidelity_from_arg(args.fidelity);
  options.culling = !args.no_culling;
  if (args.format == "mcap") {
    if (args.output.empty() || args.output == "-") {
      throw CLI::ValidationError("--output", "--format mcap writes a binary file: name it with -o FILE.mcap");
    }
    AtomicFileWriter file(args.output);
    Simulation simulation(scene, options);
    McapTargetListWriter writer(file.stream(), scene, options.level);
    std::vector<const SensorCycleState*> states;
    for (int cycle = 0; cycle < simulation.cycle_count(); ++cycle) {
      simulation.run_cycle(cycle);
      states.clear();
      for (std::size_t s = 0; s < simulation.sensor_count(); ++s) states.push_back(&simulation.sensor_state(s));
      writer.write_cycle(scene, cycle, scene.cycle_time_at(cycle), states);
    }
    const std::uint64_t bytes = writer.finish();
    file.commit();
    std::cerr << fmt::format("rcsim simulate: {} cycles of {} sensor(s), {} messages, {} bytes written to {}\n",
                             simulation.cycle_count(), simulation.sensor_count(), writer.messages(), bytes, args.output);
    return;
  }
  const auto format = args.format == "jsonl" ? TargetListFormat::Jsonl : TargetListFormat::Csv;

  std::optional<AtomicFileWriter> file;
  if (!args.output.empty() && args.output != "-") file.emplace(args.output);
  std::ostream& out = file ? file->stream() : std::cout;

  Simulation simulation(scene, options);
  TargetListWriter writer(out, format, options.level, rows_carry_elevation(scene));
  writer.write_header();
  for (int cycle = 0; cycle < simulation.cycle_count(); ++cycle) {
    simulation.run_cycle(cycle);
    for (std::size_t s = 0; s < simulation.sensor_count(); ++s) {
      writer.write_sensor_cycle(scene, cycle, scene.cycle_time_at(cycle), scene.sensors[s].id, simulation.sensor_state(s));
    }
  }
  if (file) file->commit();
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  auto* cmd = app.add_subcommand("simulate", "simulate the target lists of every sensor and cycle of a scene");
  cmd->add_option("scene", args->scene_path, "Scene file (rcsim-scene, JSON)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--level", args->level, "ideal | detections | tracks")
      ->check(CLI::IsMember({"ideal", "detections", "tracks"}))
      ->capture_default_str();
  add_seed_option(*cmd, args->seed, "Seed of every random draw");
  cmd->add_flag("--no-noise", args->no_noise, "Turn every random draw off: outputs follow the equations exactly");
  add_fidelity_option(*cmd, args->fidelity);
  cmd->add_flag("--no-culling", args->no_culling, "Visit every object's reflectors (the output is the same; for checking and timing)");
  cmd->add_option("--format", args->format,
                  "csv | jsonl | mcap (for Foxglove, schemas/mcap-replay.md; needs -o) | recording (an rcsim-recording directory "
                  "of what each sensor reports, the true boxes as annotation; needs -o)")
      ->check(CLI::IsMember({"csv", "jsonl", "mcap", "recording"}))
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output, "Output file (written atomically); stdout if omitted");
  cmd->callback([args, cmd] { run_simulate(*args, *cmd); });
}

}  // namespace rcsim::cli
