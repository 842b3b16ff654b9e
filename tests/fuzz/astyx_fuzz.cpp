// libFuzzer harness: Astyx HiRes2019 datasets (docs/importers.md), imported and read back.
// Built with -DRCSIM_FUZZ=ON; run by scripts/fuzz.sh (docs/fuzzing.md). Seeds: the base
// (tests/fuzz/base/astyx.txt) and tests/fuzz/corpus/astyx/.
#include "fuzz/fuzz_main.hpp"
#include "fuzz/astyx_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return rcsim::fuzz::run_one(rcsim::fuzz::fuzz_astyx, data, size);
}
