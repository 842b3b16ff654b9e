#pragma once
// Command-line options shared by rcsim import and rcsim replay.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "replay/import/importer.hpp"
#include "sensor/sensor_config.hpp"

namespace rcsim::cli {

struct ImportArgs {
  double smoothing_half_window_s = replay::ImportOptions{}.smoothing_half_window_s;
  double max_gap_s = replay::ImportOptions{}.max_gap_s;
  std::string effects;  // empty: the recording's declared effects, else all three
  std::string sensor;
};

inline void add_import_options(CLI::App& cmd, ImportArgs& args) {
  cmd.add_option("--smooth-half-window-s", args.smoothing_half_window_s,
                 "half width of the local quadratic smoothing of annotated boxes (0: none)")
      ->check(CLI::Range(0.0, 60.0))
      ->capture_default_str();
  cmd.add_option("--max-gap-s", args.max_gap_s, "longest hole in an object's annotation that is bridged; during a longer one the object is absent")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd.add_option("--effects", args.effects,
                 "effects of the re-simulation, comma-separated from clutter,multibounce,occlusion, or none; default: "
                 "those the recording declares (recording.json source.effects), else all three");
  cmd.add_option("--sensor", args.sensor,
                 "simulate every sensor with this configuration (built-in name or rcsim-sensor file) instead of "
                 "the recording's");
}

// --calibration DIR (rcsim replay, rcsim bench): sensors and models fitted by rcsim calibrate.
inline void add_calibration_option(CLI::App& cmd, std::string& dir) {
  cmd.add_option("--calibration", dir,
                 "calibration directory written by rcsim calibrate: its sensors and models replace the built-ins of "
                 "the same name")
      ->check(CLI::ExistingDirectory);
}

inline replay::ImportOptions import_options(const ImportArgs& args) {
  replay::ImportOptions options;
  options.smoothing_half_window_s = args.smoothing_half_window_s;
  options.max_gap_s = args.max_gap_s;
  if (!args.sensor.empty()) {
    // A built-in profile's name, or a file relative to the working directory (not the
    // recording's); anything else is the option's fault, said before a recording's
    // sensors[].type could be blamed for it.
    if (is_builtin_sensor_config(args.sensor)) {
      options.sensor_type_override = args.sensor;
    } else if (std::filesystem::is_regular_file(args.sensor)) {
      options.sensor_type_override = std::filesystem::absolute(args.sensor).string();
    } else {
      throw InputError("--sensor", args.sensor,
                       "no such built-in profile or rcsim-sensor file; " + unknown_sensor_message(args.sensor));
    }
  }
  if (args.effects.empty()) return options;  // the recording's declared effects, else all three
  options.effects = {};
  options.effects_from_recording = false;
  std::string rest = args.effects;
  while (!rest.empty() && rest != "none") {
    const auto comma = rest.find(',');
    const std::string name = rest.substr(0, comma);
    if (name == "clutter") options.effects.clutter = true;
    else if (name == "multibounce") options.effects.multibounce = true;
    else if (name == "occlusion") options.effects.occlusion = true;
    else throw CLI::ValidationError("--effects", "unknown effect '" + name + "' (clutter, multibounce, occlusion, none)");
    rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
  }
  return options;
}

}  // namespace rcsim::cli
