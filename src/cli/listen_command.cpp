// Placeholder while live UDP playback (issue 5) is written; replaced by the real command.
#include <stdexcept>

#include "cli/commands.hpp"

namespace rcsim::cli {

void add_listen_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("listen", "(not built yet)");
  cmd->callback([] { throw std::runtime_error("rcsim listen is not available in this build yet"); });
}

}  // namespace rcsim::cli
