#!/usr/bin/env bash
# The sanitizer tree (docs/ci.md): one clang build into build-asan/ with AddressSanitizer +
# UndefinedBehaviorSanitizer and libFuzzer's coverage on every library (-DRCSIM_SANITIZE=ON
# -DRCSIM_FUZZ=ON), at -O1 with line tables only. scripts/test.sh runs the whole suite from it,
# scripts/fuzz.sh its harnesses: the code is compiled once for both.
# Usage: scripts/build-sanitize.sh [TARGET...]   (default: everything)
#   RCSIM_SANITIZE_BUILD_DIR=build-asan
set -euo pipefail
cd "$(dirname "$0")/.."
build=${RCSIM_SANITIZE_BUILD_DIR:-build-asan}
# shellcheck disable=SC2046
scripts/install-packages.sh clang libclang-rt-14-dev $(cat scripts/build-packages.txt)
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-1}"
jobs=$(( $(nproc) < 2 ? $(nproc) : 2 ))
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only -DNDEBUG" \
  -DRCSIM_SANITIZE=ON -DRCSIM_FUZZ=ON -DRCSIM_BUILD_BENCHMARKS=OFF >/dev/null
targets=()
[ $# -eq 0 ] || targets=(--target "$@")
cmake --build "$build" -j "$jobs" "${targets[@]}"
