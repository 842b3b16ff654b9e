// rcsim_killable: rcsim with one difference, for the tests that a replay or a campaign shard
// killed mid-run loses no stored run: with RCSIM_TEST_KILL_AFTER_CYCLES=N in the environment it
// kills itself (SIGKILL) in the first run that passes N sensor cycles to its report. Built with
// the tests, never installed.
#include "cli/command_line.hpp"
#include "hooks/kill_after_cycles.hpp"
#include "replay/run/run_sink_wrapper.hpp"

int main(int argc, char** argv) {
  rcsim::replay::set_run_sink_wrapper(
      [](rcsim::replay::ReplaySink& inner) { return std::make_unique<rcsim::replay::KillAfterCycles>(inner); });
  return rcsim::cli::run_command_line(argc, argv);
}
