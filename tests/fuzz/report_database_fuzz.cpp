// libFuzzer harness: report databases (schemas/report-database.md), rendered and merged.
// Built with -DRCSIM_FUZZ=ON; run by scripts/fuzz.sh (docs/fuzzing.md).
#include "fuzz/fuzz_main.hpp"
#include "fuzz/store_targets.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  rcsim::fuzz::write_seeds_if_asked(rcsim::fuzz::report_database_seeds());
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return rcsim::fuzz::run_one(rcsim::fuzz::fuzz_report_database, data, size);
}
