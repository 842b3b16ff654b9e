#pragma once
#include <CLI/CLI.hpp>

#include <cstdlib>
#include <string>

namespace rcsim::cli {

// A number of 0 or more; refusing "-1" says so in one short line (CLI11's own check prints
// its upper bound, DBL_MAX, with all its 309 digits).
inline const CLI::Validator kNonNegative(
    [](std::string& text) -> std::string {
      char* end = nullptr;
      const double value = std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size()) return "'" + text + "' is not a number";
      return value >= 0.0 ? std::string() : "must be 0 or more, got " + text;
    },
    "NUMBER >= 0");

// Each adds its subcommand; the callback does the work and throws on failure.
void add_simulate_command(CLI::App& app);
void add_models_command(CLI::App& app);
void add_synth_command(CLI::App& app);
void add_import_command(CLI::App& app);
void add_scene_command(CLI::App& app);
void add_replay_command(CLI::App& app);
void add_report_command(CLI::App& app);
void add_stream_command(CLI::App& app);
void add_listen_command(CLI::App& app);
void add_traffic_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_calibrate_command(CLI::App& app);
void add_merge_command(CLI::App& app);
void add_campaign_command(CLI::App& app);
void add_export_command(CLI::App& app);
void add_profile_command(CLI::App& app);

}  // namespace rcsim::cli
