#!/usr/bin/env bash
# The whole test suite, in stages (docs/ci.md: the time budget, and what to do when a stage grows):
#   1. Release: set up, build into build/ (shared with scripts/run-example.sh), every test via CTest;
#   2. the sanitizer tree build-asan/ (clang: ASan+UBSan, and libFuzzer's coverage), built once
#      (scripts/build-sanitize.sh): every test again under ASan+UBSan (skip: RCSIM_SKIP_SANITIZE=1);
#   3. the stream's tests under ThreadSanitizer (skip: RCSIM_SKIP_TSAN=1; scripts/tsan.sh);
#   4. every libFuzzer harness for FUZZ_SECONDS (60) each, from the same tree, two at a time
#      (skip: RCSIM_SKIP_FUZZ=1; scripts/fuzz.sh, docs/fuzzing.md).
# Ends with each stage's wall time, also when a stage fails.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(( $(nproc) < 2 ? $(nproc) : 2 ))
# Release tests one more than the cores: many wait on child processes, sockets or Slurm. Under the
# sanitizers the tests are CPU-bound: a third job only slows the longest (docs/ci.md).
test_jobs=$((jobs + 1))

times=()
started=$SECONDS
minutes() { printf '%d min %02d s' $(($1 / 60)) $(($1 % 60)); }
print_times() {
  echo "== stage times ($(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg))"
  [ ${#times[@]} -eq 0 ] || printf '%s\n' "${times[@]}"
  printf '%-44s %s\n' "total" "$(minutes $((SECONDS - started)))"
}
trap print_times EXIT

# stage NAME COMMAND...: runs COMMAND (a program, not a shell function: set -e holds inside it),
# notes its wall time, and stops the suite if it fails.
stage() {
  local name=$1 t0=$SECONDS status=0
  shift
  echo "== $name"
  "$@" || status=$?
  times+=("$(printf '%-44s %s%s' "$name" "$(minutes $((SECONDS - t0)))" "$([ $status -eq 0 ] || echo "  FAILED (exit $status)")")")
  [ $status -eq 0 ] || exit $status
}

stage "Release build" scripts/setup.sh build
stage "Test tools (npm, lockfiles)" scripts/test-tools.sh
stage "Release tests" ctest --test-dir build --output-on-failure -j "$test_jobs"
if [ "${RCSIM_SKIP_SANITIZE:-0}" != "1" ] || [ "${RCSIM_SKIP_FUZZ:-0}" != "1" ]; then
  stage "ASan+UBSan build (clang, with the fuzzers)" scripts/build-sanitize.sh
fi
if [ "${RCSIM_SKIP_SANITIZE:-0}" != "1" ]; then
  stage "ASan+UBSan tests" env ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build-asan --output-on-failure -j "$jobs"
fi
if [ "${RCSIM_SKIP_TSAN:-0}" != "1" ]; then
  stage "TSan: the stream's tests (build and run)" scripts/tsan.sh
fi
if [ "${RCSIM_SKIP_FUZZ:-0}" != "1" ]; then
  stage "libFuzzer: every harness ${FUZZ_SECONDS:-60} s" env FUZZ_NO_BUILD=1 scripts/fuzz.sh
fi
