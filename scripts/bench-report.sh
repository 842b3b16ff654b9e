#!/usr/bin/env bash
# The campaign report benchmark (issue 20, docs/report.md "Campaign report"): generates a campaign
# database of RUNS runs with bench/make_campaign_db.cpp (one --store summary replay of RECORDING,
# copied with varied figures, and six criteria; not committed), then times `rcsim report` on it with
# /usr/bin/time (wall time and peak resident memory): the default page (the campaign overview and
# the last 20 runs in detail), the overview alone (--campaign only), and the default page with
# --runs-dir (the pages of the runs the overview lists).
# Usage: scripts/bench-report.sh [RUNS=10000] [WORK_DIR=/tmp/rcsim-bench-report]
#                                [RECORDING=recordings_synthetic/front_approach]
# BUILD_DIR (default build) names the build; RCSIM_SKIP_BUILD=1 uses it as it is.
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-10000}
work=${2:-/tmp/rcsim-bench-report}
recording=${3:-recordings_synthetic/front_approach}
build=${BUILD_DIR:-build}
[ "${RCSIM_SKIP_BUILD:-0}" = 1 ] || bash scripts/setup.sh "$build" -DRCSIM_BUILD_BENCHMARKS=ON >/dev/null
rcsim="$build/bin/rcsim"
mkdir -p "$work"
grep -m1 "model name" /proc/cpuinfo
echo "cores: $(nproc), load $(cut -d' ' -f1-3 /proc/loadavg), rcsim $($rcsim --version 2>/dev/null || echo '?'), $runs runs of $recording"
db="$work/campaign_$runs.sqlite"
if [ ! -f "$db" ]; then
  rm -f "$db.part"*
  "$build/bin/rcsim_make_campaign_db" "$db.part" "$runs" "$recording" >/dev/null
  mv "$db.part" "$db"
fi
printf '%-40s %8s %9s %10s\n' "rcsim report" "wall s" "peak MB" "HTML MB"
timed() {  # label, html, arguments...
  local label=$1 html=$2
  shift 2
  /usr/bin/time -o "$work/time.txt" -f "%e %M" "$rcsim" report "$db" -o "$html" "$@" 2>"$work/stderr.txt" ||
    { cat "$work/stderr.txt"; exit 1; }
  read -r wall_s peak_kib <"$work/time.txt"
  awk -v l="$label" -v w="$wall_s" -v p="$peak_kib" -v b="$(stat -c %s "$html")" \
    'BEGIN { printf "%-40s %8.2f %9.1f %10.2f\n", l, w, p / 1024, b / 1e6 }'
}
timed "default (overview + last 20 runs)" "$work/campaign.html"
timed "--campaign only" "$work/overview.html" --campaign only
rm -rf "$work/campaign-runs"
timed "--runs-dir (listed runs' pages)" "$work/campaign-with-runs.html" --runs-dir "$work/campaign-runs"
echo "run pages: $(ls "$work/campaign-runs" | wc -l), $(du -sm "$work/campaign-runs" | cut -f1) MB"
