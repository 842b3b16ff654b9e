// rcsim merge SHARD.sqlite... -o CAMPAIGN.sqlite: the runs of many report databases in one.
#include "cli/commands.hpp"

namespace rcsim::cli {

void add_merge_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("merge", "merge report databases (campaign shards) into one, atomically");
  cmd->callback([] {});
}

}  // namespace rcsim::cli
