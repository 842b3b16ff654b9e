#pragma once
// main() of the Google Benchmark programs in bench/, instead of BENCHMARK_MAIN(): -h as well as
// --help prints the usage (what the program measures, then Google Benchmark's own flags) and ends
// with 0; an unknown flag or argument ends with 2 (BENCHMARK_MAIN ends with 1), as rcsim does.
#include <benchmark/benchmark.h>

#include <iostream>
#include <string>

namespace rcsim::bench_tools {

inline int run_benchmark_main(int argc, char** argv, const char* name, const char* description) {
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--help" || argument == "-h") {
      std::cout << "usage: " << name << " [--benchmark_filter=REGEX] [--benchmark_... flags]\n\n"
                << description << "\n\nGoogle Benchmark's flags:\n";
      benchmark::PrintDefaultHelp();
      return 0;
    }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
    std::cerr << name << " --help lists the flags\n";
    return 2;
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace rcsim::bench_tools
