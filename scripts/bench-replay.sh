#!/usr/bin/env bash
# The replay benchmark (issues 4 and 19): streaming replay, metrics and storage of a generated
# two-sensor ring-road drive of 1 h and 3 h, each stored --store full and --store summary.
# Generates the recordings (not committed) with bench/make_long_recording.cpp, then times
# `rcsim replay` with /usr/bin/time (wall time and peak resident memory) and gives the report's
# size per hour of drive.
# Usage: scripts/bench-replay.sh [DURATIONS_S="3600 10800"] [WORK_DIR=/tmp/rcsim-bench-replay]
set -euo pipefail
cd "$(dirname "$0")/.."
durations=${1:-"3600 10800"}
work=${2:-/tmp/rcsim-bench-replay}
bash scripts/setup.sh build >/dev/null
mkdir -p "$work"
grep -m1 "model name" /proc/cpuinfo
echo "cores: $(nproc), rcsim $(build/bin/rcsim --version 2>/dev/null || echo '?')"
printf '%-8s %-8s %10s %10s %14s %14s\n' drive store "wall s" "peak MB" "report MB" "MB per hour"
for duration_s in $durations; do
  rec="$work/ring_drive_${duration_s}s"
  [ -f "$rec/targets.csv" ] || build/bin/rcsim_make_long_recording "$rec" "$duration_s" 1 >/dev/null
  for store in full summary; do
    db="$work/report_${duration_s}_${store}.sqlite"
    rm -f "$db"*
    /usr/bin/time -o "$work/time.txt" -f "%e %M" build/bin/rcsim replay "$rec" --db "$db" --store "$store" \
      >/dev/null 2>"$work/stderr.txt" || { cat "$work/stderr.txt"; exit 1; }
    read -r wall_s peak_kib <"$work/time.txt"
    size_b=$(stat -c %s "$db")
    awk -v d="$duration_s" -v s="$store" -v w="$wall_s" -v p="$peak_kib" -v b="$size_b" 'BEGIN {
      printf "%-8s %-8s %10.2f %10.1f %14.1f %14.1f\n", d / 3600 " h", s, w, p / 1024, b / 1e6, b / 1e6 / (d / 3600) }'
  done
done
