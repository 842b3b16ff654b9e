#pragma once
// For the interruption tests, in the test build's rcsim_killable only (killable_main.cpp): with
// RCSIM_TEST_KILL_AFTER_CYCLES=N in the environment, its replay and campaign run-shard kill themselves (SIGKILL, no clean-up of any kind) in the
// first run that passes N sensor cycles to the report (counted per run), i.e. in the middle of a run's transaction, exactly like
// a process killed from outside. Without the variable the sink only passes everything on.
#include <csignal>
#include <cstdlib>

#include "replay/run/replay_run.hpp"

namespace rcsim::replay {

class KillAfterCycles final : public ReplaySink {
 public:
  explicit KillAfterCycles(ReplaySink& inner) : inner_(inner) {
    const char* n = std::getenv("RCSIM_TEST_KILL_AFTER_CYCLES");
    remaining_ = n != nullptr ? std::atol(n) : 0;
  }
  void begin_run(const Recording& r, const ImportedScene& i, const Scene& s, const ReplayOptions& o) override {
    inner_.begin_run(r, i, s, o);
  }
  void add_cycle(const CycleComparison& c) override {
    inner_.add_cycle(c);
    if (remaining_ > 0 && --remaining_ == 0) std::raise(SIGKILL);
  }
  void end_run(const ReplaySummary& s) override { inner_.end_run(s); }

 private:
  ReplaySink& inner_;
  long remaining_ = 0;
};

}  // namespace rcsim::replay
