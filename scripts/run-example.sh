#!/usr/bin/env bash
# The main job on the bundled recordings: set up and build, replay every recording of
# recordings_synthetic/ (import, re-simulate, compare per cycle) into the SQLite report
# out/report.sqlite, bench every fidelity level against the signal-level reference on them
# (speed against error, docs/bench.md; about two minutes) into the same database, then write the
# HTML validation report out/report.html. Set RCSIM_SKIP_BENCH=1 to leave the bench out.
# Runs accumulate in the database (rcsim never deletes a report); the HTML shows this batch.
set -euo pipefail
cd "$(dirname "$0")/.."
RCSIM_TARGETS="rcsim rcsim_sqlite" scripts/setup.sh build  # the executable and the SQL extension only; scripts/test.sh builds the rest
mkdir -p out
runs=0
for recording in recordings_synthetic/*/; do
  [ -f "$recording/recording.json" ] || continue
  ./build/bin/rcsim replay "$recording" --db out/report.sqlite --seed 1
  runs=$((runs + 1))
done
if [ "${RCSIM_SKIP_BENCH:-0}" != 1 ]; then
  ./build/bin/rcsim bench --db out/report.sqlite --seed 1
fi
./build/bin/rcsim report out/report.sqlite -o out/report.html --last "$runs"
echo "== open out/report.html in a browser; a run's cycles in SQL: sqlite3 out/report.sqlite '.load build/lib/rcsim' 'SELECT cycle, sensor, gospa_m FROM cycles WHERE run_id = 1'"
