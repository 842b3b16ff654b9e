#!/usr/bin/env bash
# The whole test suite: set up, build, run every test through CTest; then the same under
# AddressSanitizer + UndefinedBehaviorSanitizer (skip with RCSIM_SKIP_SANITIZE=1); then the
# stream's tests under ThreadSanitizer (skip with RCSIM_SKIP_TSAN=1; tests/stream/tsan.cmake);
# then every libFuzzer harness for FUZZ_SECONDS (60) each, built with clang (skip with
# RCSIM_SKIP_FUZZ=1; docs/fuzzing.md).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh build
ctest --test-dir build --output-on-failure -j 2
if [ "${RCSIM_SKIP_SANITIZE:-0}" != "1" ]; then
  echo "== AddressSanitizer + UndefinedBehaviorSanitizer build"
  scripts/setup.sh build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRCSIM_SANITIZE=ON -DRCSIM_BUILD_BENCHMARKS=OFF
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --test-dir build-asan --output-on-failure -j 2
fi
if [ "${RCSIM_SKIP_TSAN:-0}" != "1" ]; then
  echo "== ThreadSanitizer: the stream's tests"
  scripts/tsan.sh
fi
if [ "${RCSIM_SKIP_FUZZ:-0}" != "1" ]; then
  echo "== libFuzzer harnesses (clang, ASan+UBSan), ${FUZZ_SECONDS:-60} s each"
  scripts/fuzz.sh
fi
