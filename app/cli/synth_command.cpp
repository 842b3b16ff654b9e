// rcsim synth SCENE.json -o RECORDING_DIR: the signal-level reference simulation into a recording
// (docs/synth.md), optionally with a bird's-eye SVG of its targets against another target list.
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "cli/commands.hpp"
#include "cli/seed_option.hpp"
#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "common/json_reader.hpp"
#include "io/recording.hpp"
#include "replay/report/recording_birdseye.hpp"
#include "scene/scene.hpp"
#include "synth/reference_simulator.hpp"
#include "synth/sensor_design.hpp"

namespace rcsim::cli {
namespace {

namespace fs = std::filesystem;

struct SynthArgs {
  std::string scene_path;
  std::string output;
  std::uint64_t seed = kDefaultSeed;
  std::string svg;
  std::string svg_compare;
  double svg_time_s = -1.0;
};

void require_parent_directory(const std::string& path, const std::string& what) {
  const fs::path target = fs::absolute(path).lexically_normal();
  const fs::path parent = target.filename().empty() ? target.parent_path().parent_path() : target.parent_path();
  if (!fs::is_directory(parent)) throw InputError(path, "", what + ": the parent directory does not exist");
}

void run_synth(const SynthArgs& args) {
  const std::uint64_t seed = args.seed;
  if (args.output.empty()) throw InputError("-o", "", "an output recording directory is required");
  require_parent_directory(args.output, "output recording directory");
  check_output_directory(fs::absolute(args.output).lexically_normal(), "recording.json");  // before the work
  if (!args.svg.empty()) {
    require_parent_directory(args.svg, "SVG file");
    check_output_file(args.svg);
  }
  if (!args.svg_compare.empty() && !fs::is_regular_file(args.svg_compare)) {
    throw InputError(args.svg_compare, "", "no such target list file");
  }

  const Scene scene = load_scene_file(args.scene_path, ModelLibrary::builtin());
  const nlohmann::json scene_json = parse_json_file(args.scene_path);
  synth::RecordingInfo info;
  const fs::path out = fs::absolute(args.output).lexically_normal();
  info.name = out.filename().empty() ? out.parent_path().filename().string() : out.filename().string();
  if (scene_json.contains("description") && scene_json["description"].is_string()) {
    info.description = scene_json["description"].get<std::string>();
  }
  info.scene_file = fs::path(args.scene_path).filename().string();

  // Each sensor as its own radar (docs/synth.md, "One radar per profile"), all on one cycle clock:
  // or refused, naming the scene and the sensors, before the work.
  const synth::SynthConfig design;
  try {
    synth::require_one_recording(scene, design);
  } catch (const std::invalid_argument& e) {
    throw InputError(args.scene_path, "ego.sensors", e.what());
  }
  const Recording recording = synth::make_recording(scene, design, seed, info);
  if (!args.svg.empty()) {
    replay::svg::RecordingPictureOptions options;
    options.time_s = args.svg_time_s;
    options.compare_path = args.svg_compare;
    options.title = info.name;
    options.recorded_label = "reference target";
    options.compared_label = "compared target";
    const std::string svg = replay::svg::recording_birdseye_svg(recording, options);
    AtomicFileWriter file(args.svg);
    file.stream() << svg;
    file.commit();
  }
  write_recording(args.output, recording);
}

}  // namespace

void add_synth_command(CLI::App& app) {
  auto args = std::make_shared<SynthArgs>();
  auto* cmd = app.add_subcommand("synth", "signal-level reference simulation of a scene into a recording");
  cmd->add_option("scene", args->scene_path, "Scene file (rcsim-scene, JSON)")->required();
  cmd->add_option("-o,--output", args->output, "Recording directory to write (atomically)")->required();
  add_seed_option(*cmd, args->seed, "Seed of every random draw (receiver noise, clutter, annotation)");
  cmd->add_option("--svg", args->svg, "Also write a bird's-eye SVG of the targets (last 10 cycles before --svg-time)");
  cmd->add_option("--svg-compare", args->svg_compare,
                  "Target list CSV (rcsim simulate output) drawn against the reference in the SVG");
  cmd->add_option("--svg-time", args->svg_time_s, "Time of the SVG snapshot in s (default: the last cycle)");
  cmd->callback([args] { run_synth(*args); });
}

}  // namespace rcsim::cli
