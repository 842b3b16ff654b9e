// libFuzzer harness: campaign manifests (schemas/campaign.md), planned into a Slurm batch script.
// Built with -DRCSIM_FUZZ=ON; run by scripts/fuzz.sh (docs/fuzzing.md).
#include "fuzz/fuzz_main.hpp"
#include "fuzz/store_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return rcsim::fuzz::run_one(rcsim::fuzz::fuzz_campaign_manifest, data, size);
}
