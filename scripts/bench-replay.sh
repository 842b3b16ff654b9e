#!/usr/bin/env bash
# The replay benchmark of issue 4: replay, metrics and storage of a one-hour, two-sensor recording.
# Generates the recording (not committed) with bench/make_long_recording.cpp, then times
# `rcsim replay` with /usr/bin/time (wall time and peak resident memory).
# Usage: scripts/bench-replay.sh [DURATION_S=3600] [WORK_DIR=/tmp/rcsim-bench-replay]
set -euo pipefail
cd "$(dirname "$0")/.."
duration_s=${1:-3600}
work=${2:-/tmp/rcsim-bench-replay}
bash scripts/setup.sh build >/dev/null
mkdir -p "$work"
rm -rf "$work/long_ring_drive" "$work/report.sqlite"*
echo "== generating a ${duration_s} s two-sensor recording"
/usr/bin/time -f "   generated in %e s, peak %M KiB" build/bin/rcsim_make_long_recording "$work/long_ring_drive" "$duration_s" 1
du -sh "$work/long_ring_drive"
echo "== rcsim replay"
/usr/bin/time -f "   replay wall %e s, user %U s, peak memory %M KiB" \
  build/bin/rcsim replay "$work/long_ring_drive" --db "$work/report.sqlite" --json
ls -l "$work/report.sqlite"
grep -m1 "model name" /proc/cpuinfo
