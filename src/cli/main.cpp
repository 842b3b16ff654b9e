// rcsim: automotive radar target list simulation by reflection centers (see README.md).
#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>
#include <string>

#include "cli/commands.hpp"
#include "cli/fit_progress.hpp"
#include "cli/suggestions.hpp"
#include "cli/verdict_options.hpp"
#include "common/input_error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"rcsim: radar target list simulation from reflection-center object models"};
  app.set_version_flag("--version", std::string("rcsim ") + RCSIM_VERSION);
  app.require_subcommand(1);
  rcsim::cli::add_simulate_command(app);
  rcsim::cli::add_import_command(app);
  rcsim::cli::add_replay_command(app);
  rcsim::cli::add_report_command(app);
  rcsim::cli::add_export_command(app);
  rcsim::cli::add_stream_command(app);
  rcsim::cli::add_listen_command(app);
  rcsim::cli::add_synth_command(app);
  rcsim::cli::add_traffic_command(app);
  rcsim::cli::add_bench_command(app);
  rcsim::cli::add_calibrate_command(app);
  rcsim::cli::add_profile_command(app);
  rcsim::cli::add_merge_command(app);
  rcsim::cli::add_campaign_command(app);
  rcsim::cli::add_models_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version end here with 0; any wrong option or value is bad input (README's
    // exit statuses), not CLI11's own numbers (105, 109, ...). A mistyped option or command is
    // named first, with what was probably meant: it is often why a required one is missing.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    if (const auto unknown = rcsim::cli::unknown_argument_message(app)) {
      std::cerr << *unknown << '\n';
      return 2;
    }
    app.exit(e);
    return 2;
  } catch (const rcsim::cli::VerdictsFailed& e) {
    std::cerr << "rcsim: failed: " << e.what() << '\n';
    return rcsim::cli::kExitVerdictsFailed;
  } catch (const rcsim::cli::FitInterrupted& e) {
    std::cerr << "rcsim: interrupted: " << e.what() << '\n';
    return rcsim::cli::kExitInterrupted;
  } catch (const rcsim::InputError& e) {
    std::cerr << "rcsim: error: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "rcsim: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
