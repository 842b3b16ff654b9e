#!/usr/bin/env bash
# Rewrites tests/golden/golden_hashes.txt from the current build's outputs. Run it only when a
# change of output is deliberate, and say in the commit why the outputs changed.
# Usage: scripts/update-golden.sh [BUILD_DIR]   (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:-build}
cmake --build "$build_dir" -j 2
out=$(mktemp)
figures=$(mktemp)
trap 'rm -f "$out" "$figures"' EXIT
RCSIM_GOLDEN_OUT="$out" RCSIM_GOLDEN_FIGURES_OUT="$figures" "$build_dir/bin/rcsim_tests" --gtest_filter='Bundled/GoldenRun.*' >/dev/null || true
{
  echo "# rcsim golden run (tests/golden/golden_run_test.cpp): FNV-1a 64 of each output, seed 7."
  echo "# Made by scripts/update-golden.sh; a change here is a change of output, said in the commit."
  sort -u "$out"
} > tests/golden/golden_hashes.txt
{
  echo "# rcsim golden run's figures (tests/golden/golden_run_test.cpp), seed 7: compared within tolerances,"
  echo "# so that another compiler, whose hashes differ, is still checked. Made by scripts/update-golden.sh."
  sort "$figures"
} > tests/golden/golden_figures.txt
echo "$(grep -vc '^#' tests/golden/golden_hashes.txt) hashes and $(grep -vc '^#' tests/golden/golden_figures.txt) figures written to tests/golden/"
