#!/usr/bin/env bash
# The merge benchmark (issue 20, docs/merge.md): two shards of RUNS runs each, replayed from one
# recording with `rcsim replay` (--store summary, the first 5 of each shard --store full), each run
# another seed; then `rcsim merge` timed three ways: both shards into a new report, the same again
# (every run a duplicate), and one more shard of new runs into the merged report.
# Usage: scripts/bench-merge.sh [RCSIM=build/bin/rcsim] [WORK_DIR=/tmp/rcsim-bench-merge] [RUNS=100]
#                               [RECORDING=recordings_synthetic/two_in_one_cell]
set -euo pipefail
cd "$(dirname "$0")/.."
rcsim=${1:-build/bin/rcsim}
work=${2:-/tmp/rcsim-bench-merge}
runs=${3:-100}
recording=${4:-recordings_synthetic/two_in_one_cell}
mkdir -p "$work"
grep -m1 "model name" /proc/cpuinfo
echo "cores: $(nproc), $($rcsim --version), recording $recording, $runs runs per shard"
for shard in 0 1 2; do
  db="$work/shard-$shard.sqlite"
  [ -f "$db" ] && continue
  for k in $(seq 1 "$runs"); do
    store=summary
    [ "$k" -le 5 ] && store=full
    "$rcsim" replay "$recording" --db "$db.part" --seed $((shard * runs + k)) --store "$store" >/dev/null 2>"$work/replay.err" || { cat "$work/replay.err"; exit 1; }
  done
  mv "$db.part" "$db"
done
out="$work/campaign.sqlite"
rm -f "$out"
timed() {  # label, command...: wall time and peak memory
  local label=$1
  shift
  /usr/bin/time -o "$work/time.txt" -f "%e %M" "$@" >"$work/merge.txt"
  read -r wall_s peak_kib <"$work/time.txt"
  printf '%-44s %6.2f s %6.1f MB   %s\n' "$label" "$wall_s" "$(echo "$peak_kib / 1024" | bc -l)" "$(tail -n 1 "$work/merge.txt")"
}
timed "2 shards into a new report" "$rcsim" merge "$work/shard-0.sqlite" "$work/shard-1.sqlite" -o "$out"
timed "the same 2 shards again (all duplicates)" "$rcsim" merge "$work/shard-0.sqlite" "$work/shard-1.sqlite" -o "$out"
timed "a third shard into the merged report" "$rcsim" merge "$work/shard-2.sqlite" -o "$out"
ls -l "$work"/shard-0.sqlite "$out" | awk '{ printf "%s %.1f MB\n", $NF, $5 / 1e6 }'
