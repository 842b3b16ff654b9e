// libFuzzer harness: scene files (schemas/scene.md), simulated for a few cycles.
// Built with -DRCSIM_FUZZ=ON; run by scripts/fuzz.sh (docs/fuzzing.md).
#include "fuzz/fuzz_main.hpp"
#include "fuzz/world_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return rcsim::fuzz::run_one(rcsim::fuzz::fuzz_scene, data, size);
}
