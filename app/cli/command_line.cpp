#include "cli/command_line.hpp"

#include <CLI/CLI.hpp>

#include <exception>
#include <filesystem>
#include <iostream>
#include <string>

#include "cli/commands.hpp"
#include "cli/fit_progress.hpp"
#include "cli/suggestions.hpp"
#include "cli/verdict_options.hpp"
#include "common/input_error.hpp"
#include "common/safe_text.hpp"

namespace rcsim::cli {

int run_command_line(int argc, char** argv) {
  CLI::App app{"rcsim: radar target list simulation from reflection-center object models"};
  app.set_version_flag("--version", std::string("rcsim ") + RCSIM_VERSION);
  app.require_subcommand(1);
  add_simulate_command(app);
  add_import_command(app);
  add_scene_command(app);
  add_replay_command(app);
  add_report_command(app);
  add_export_command(app);
  add_stream_command(app);
  add_listen_command(app);
  add_synth_command(app);
  add_traffic_command(app);
  add_bench_command(app);
  add_calibrate_command(app);
  add_profile_command(app);
  add_merge_command(app);
  add_campaign_command(app);
  add_models_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version end here with 0; any wrong option or value is bad input (README's
    // exit statuses), not CLI11's own numbers (105, 109, ...). A mistyped option or command is
    // named first, with what was probably meant: it is often why a required one is missing.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    if (const auto unknown = unknown_argument_message(app)) {
      std::cerr << escape_control_characters(*unknown) << '\n';
      return 2;
    }
    // No command at all (a bare `rcsim`): the commands, then what is missing (issue 53: it said
    // only "A subcommand is required").
    if (app.get_subcommands().empty()) {
      std::cerr << app.help() << "\nrcsim: a command is required: rcsim COMMAND --help lists its options\n";
      return 2;
    }
    // CLI11's own message ("--seed: 1 required UINT missing"), in
    // rcsim's form: the program first, the way to the options after.
    std::cerr << "rcsim: " << escape_control_characters(e.what()) << " (--help lists the options)\n";
    return 2;
  } catch (const VerdictsFailed& e) {
    std::cerr << "rcsim: failed: " << escape_control_characters(e.what()) << '\n';
    return kExitVerdictsFailed;
  } catch (const FitInterrupted& e) {
    std::cerr << "rcsim: interrupted: " << escape_control_characters(e.what()) << '\n';
    return kExitInterrupted;
  } catch (const rcsim::InputError& e) {
    // Every message below may quote the input (a field, a name, a path): its control characters
    // are written out, so that a terminal escape in a recording cannot erase the error or forge a
    // line after it (issue 51).
    std::cerr << "rcsim: error: " << escape_control_characters(e.what()) << '\n';
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // A name given that the file system refuses to look up (too long, a loop of links, no
    // permission) is bad input: named, with why.
    std::cerr << "rcsim: error: " << escape_control_characters((e.path1().empty() ? "" : e.path1().string() + ": ") + e.code().message()) << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "rcsim: error: " << escape_control_characters(e.what()) << '\n';
    return 1;
  }
  return 0;
}

}  // namespace rcsim::cli
