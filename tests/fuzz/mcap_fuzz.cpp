// libFuzzer harness: MCAP logs as `rcsim import --from mcap` reads them (docs/importers.md).
// Built with -DRCSIM_FUZZ=ON; run by scripts/fuzz.sh (docs/fuzzing.md). Seeds: written by the
// harness itself (mcap_targets.hpp).
#include "fuzz/fuzz_main.hpp"
#include "fuzz/mcap_targets.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  rcsim::fuzz::write_seeds_if_asked(rcsim::fuzz::mcap_seeds());
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return rcsim::fuzz::run_one(rcsim::fuzz::fuzz_mcap, data, size);
}
