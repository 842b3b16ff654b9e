#!/usr/bin/env bash
# The main job on a bundled scene: set up, build, simulate the paper's situation 1 with both
# sensors and write the tracked target list to out/front_approach.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh build
mkdir -p out
./build/bin/rcsim simulate docs/examples/front_approach.json --seed 1 -o out/front_approach.csv
echo "== wrote out/front_approach.csv ($(($(wc -l < out/front_approach.csv) - 1)) targets); first rows:"
head -n 6 out/front_approach.csv
