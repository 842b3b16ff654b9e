// Placeholder while the replay harness (issue 4) is written.
#include <stdexcept>

#include "cli/commands.hpp"

namespace rcsim::cli {

void add_import_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("import", "(not built yet)");
  cmd->callback([] { throw std::runtime_error("rcsim import is not available in this build yet"); });
}

}  // namespace rcsim::cli
