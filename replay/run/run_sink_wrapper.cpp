#include "replay/run/run_sink_wrapper.hpp"

namespace rcsim::replay {
namespace {

RunSinkWrapper& the_wrapper() {
  static RunSinkWrapper wrapper;
  return wrapper;
}

}  // namespace

void set_run_sink_wrapper(RunSinkWrapper wrapper) { the_wrapper() = std::move(wrapper); }

ReplaySink& wrapped_run_sink(ReplaySink& inner, std::unique_ptr<ReplaySink>& keep) {
  if (!the_wrapper()) return inner;
  keep = the_wrapper()(inner);
  return *keep;
}

}  // namespace rcsim::replay
