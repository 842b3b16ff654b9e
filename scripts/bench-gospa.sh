#!/usr/bin/env bash
# GOSPA per call: the sparse exact assignment (metrics::gospa), the dense one per connected
# component and one assignment over all pairs
# (the ways before), at 5, 20, 200 and 2,000 targets per side on uniform clouds, cars of 100
# points and a 1-m wall (bench/bench_gospa.cpp; docs/performance.md, "GOSPA per cycle").
# Usage: scripts/bench-gospa.sh [BENCH=build/bin/rcsim_bench_gospa] [Google Benchmark flags...]
# Builds the tool first when BENCH is the default and it is missing (the full assignment at
# 2,000 targets takes seconds a call: about a minute in all).
set -euo pipefail
cd "$(dirname "$0")/.."
bench=${1:-build/bin/rcsim_bench_gospa}
shift || true
if [ ! -x "$bench" ] && [ "$bench" = build/bin/rcsim_bench_gospa ]; then
  jobs=$(( $(nproc) < 2 ? $(nproc) : 2 ))
  cmake --build build -j "$jobs" --target rcsim_bench_gospa
fi
grep -m1 "model name" /proc/cpuinfo
echo "cores: $(nproc), load $(cut -d' ' -f1-3 /proc/loadavg)"
"$bench" --benchmark_counters_tabular=true "$@"
