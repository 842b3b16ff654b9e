// libFuzzer harness: datagrams as rcsim listen receives them (schemas/udp-stream.md).
// Built with -DRCSIM_FUZZ=ON; run by scripts/fuzz.sh (docs/fuzzing.md).
#include "fuzz/fuzz_main.hpp"
#include "fuzz/udp_targets.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  rcsim::fuzz::write_seeds_if_asked(rcsim::fuzz::udp_datagram_seeds());
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return rcsim::fuzz::run_one(rcsim::fuzz::fuzz_udp_datagrams, data, size);
}
