// libFuzzer harness: sensor configuration files (schemas/sensor-config.md), simulated in a small scene.
// Built with -DRCSIM_FUZZ=ON; run by scripts/fuzz.sh (docs/fuzzing.md).
#include "fuzz/fuzz_main.hpp"
#include "fuzz/world_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return rcsim::fuzz::run_one(rcsim::fuzz::fuzz_sensor_config, data, size);
}
