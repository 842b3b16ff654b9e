#!/usr/bin/env bash
# The stream's tests under ThreadSanitizer (issue 21; run by scripts/test.sh, skip there with
# RCSIM_SKIP_TSAN=1): builds into build-tsan/ only the layers the stream uses and its in-process
# tests (rcsim_stream_tests, tests/app/stream/tsan.cmake), then runs them through CTest (label tsan).
# Any report of a race fails the test it happens in; line tables (-g1) are all a report needs.
# Usage: scripts/tsan.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:-build-tsan}
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-1}"
jobs=$(( $(nproc) < 2 ? $(nproc) : 2 ))
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG" -DRCSIM_TSAN=ON -DRCSIM_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build_dir" -j "$jobs" --target rcsim_stream_tests
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 ${TSAN_OPTIONS:-}" \
  ctest --test-dir "$build_dir" -L tsan --output-on-failure -j "$jobs"
