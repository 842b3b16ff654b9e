// Placeholder until the signal-level reference lands (issue 3); replaced by its real command.
#include <stdexcept>

#include "cli/commands.hpp"

namespace rcsim::cli {

void add_synth_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("synth", "signal-level reference simulation into a recording (not built yet)");
  cmd->callback([] { throw std::runtime_error("rcsim synth is not available in this build yet"); });
}

}  // namespace rcsim::cli
