// Placeholder while live UDP playback (issue 5) is written; replaced by the real command.
#include <stdexcept>

#include "cli/commands.hpp"

namespace rcsim::cli {

void add_stream_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("stream", "(not built yet)");
  cmd->callback([] { throw std::runtime_error("rcsim stream is not available in this build yet"); });
}

}  // namespace rcsim::cli
