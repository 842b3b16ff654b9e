// libFuzzer harness: ASAM OpenLABEL files as `rcsim import --from mcap` reads them beside a log
// (replay/import/openlabel.hpp). Built with -DRCSIM_FUZZ=ON; run by scripts/fuzz.sh
// (docs/fuzzing.md). Seeds: written by the harness itself (openlabel_targets.hpp).
#include "fuzz/fuzz_main.hpp"
#include "fuzz/openlabel_targets.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  rcsim::fuzz::write_seeds_if_asked(rcsim::fuzz::openlabel_seeds());
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return rcsim::fuzz::run_one(rcsim::fuzz::fuzz_openlabel, data, size);
}
