#pragma once
#include <CLI/CLI.hpp>

namespace rcsim::cli {

// Each adds its subcommand; the callback does the work and throws on failure.
void add_simulate_command(CLI::App& app);
void add_models_command(CLI::App& app);
void add_synth_command(CLI::App& app);
void add_import_command(CLI::App& app);
void add_replay_command(CLI::App& app);
void add_report_command(CLI::App& app);
void add_stream_command(CLI::App& app);
void add_listen_command(CLI::App& app);
void add_traffic_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_calibrate_command(CLI::App& app);
void add_merge_command(CLI::App& app);
void add_campaign_command(CLI::App& app);

}  // namespace rcsim::cli
