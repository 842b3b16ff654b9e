#pragma once
// What may stand between a replay and its report's sink. The product puts nothing there; the test
// build's rcsim_killable (tests/hooks/) puts a sink that kills the process mid-run, for the tests
// that a killed replay or shard loses no stored run.
#include <functional>
#include <memory>

#include "replay/run/replay_run.hpp"

namespace rcsim::replay {

using RunSinkWrapper = std::function<std::unique_ptr<ReplaySink>(ReplaySink& inner)>;

// Set once, before any run (a test binary's main).
void set_run_sink_wrapper(RunSinkWrapper wrapper);

// `inner`, or the wrapper's sink around it (owned by `keep`).
ReplaySink& wrapped_run_sink(ReplaySink& inner, std::unique_ptr<ReplaySink>& keep);

}  // namespace rcsim::replay
