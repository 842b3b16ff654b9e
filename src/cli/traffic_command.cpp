// Placeholder while the traffic model (issue 6) is written; replaced by the real command.
#include <stdexcept>

#include "cli/commands.hpp"

namespace rcsim::cli {

void add_traffic_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("traffic", "(not built yet)");
  cmd->callback([] { throw std::runtime_error("rcsim traffic is not available in this build yet"); });
}

}  // namespace rcsim::cli
