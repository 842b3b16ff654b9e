#!/usr/bin/env bash
# The point-cloud benchmark (issue 52) on the Astyx HiRes2019 frames (../shared/realdata/, never
# in the repository): imports frames 0-399, times `rcsim replay` of them with /usr/bin/time (wall
# time and peak resident memory), then the assignment per frame, the sparse exact one
# (metrics::gospa) against the dense one per connected component (the way before) on the same
# frames, with their equality (bench/bench_pointcloud.cpp), and, where python3-scipy is
# installed, scipy's linear_sum_assignment on the same frames: per component of the pairs closer
# than c (as a careful user would write it) and on the whole frame's dense matrix (first frames).
# Also the HTML report of the run (time, memory, size), `profile derive` and `calibrate
# --real-drive` of the frames (time, memory).
# What it writes (the recording, the frames' positions, the report) stays in WORK_DIR: derived
# from the data, never to be committed.
# Usage: scripts/bench-pointcloud.sh [WORK_DIR=/tmp/rcsim-bench-pointcloud] [FRAMES=0-399]
set -euo pipefail
cd "$(dirname "$0")/.."
work=${1:-/tmp/rcsim-bench-pointcloud}
frames=${2:-0-399}
raw=../shared/realdata/astyx_hires2019/raw/dataset_astyx_hires2019
if [ ! -d "$raw" ]; then
  echo "bench-pointcloud: no Astyx frames at $raw (../shared/realdata/astyx_hires2019/README.md): skipped"
  exit 0
fi
jobs=$(( $(nproc) < 2 ? $(nproc) : 2 ))
cmake --build build -j "$jobs" --target rcsim rcsim_bench_pointcloud >/dev/null
mkdir -p "$work"
grep -m1 "model name" /proc/cpuinfo
echo "cores: $(nproc), load $(cut -d' ' -f1-3 /proc/loadavg), rcsim $(build/bin/rcsim --version 2>/dev/null || echo '?')"

rec="$work/astyx_$frames"
[ -f "$rec/targets.csv" ] || build/bin/rcsim import --from astyx "$raw" -o "$rec" --frames "$frames" >/dev/null 2>&1
db="$work/report.sqlite"
rm -f "$db"*
/usr/bin/time -o "$work/time.txt" -f "%e %M" build/bin/rcsim replay "$rec" --db "$db" >/dev/null 2>"$work/stderr.txt" ||
  { cat "$work/stderr.txt"; exit 1; }
read -r wall_s peak_kib <"$work/time.txt"
awk -v f="$frames" -v w="$wall_s" -v p="$peak_kib" 'BEGIN { printf "replay of Astyx frames %s: %.2f s, peak %.1f MB\n", f, w, p / 1024 }'

# The report of that run, `profile derive` and `calibrate --real-drive` of the frames (issue 52,
# items 2 and 3): wall time and peak memory, the report's size. SKIP_CALIBRATE=1 leaves out the
# calibration (minutes on a loaded machine).
timed() {  # LABEL COMMAND...: prints "LABEL: WALL s, peak MB"
  local label=$1; shift
  /usr/bin/time -o "$work/time.txt" -f "%e %M" "$@" >/dev/null 2>"$work/stderr.txt" || { cat "$work/stderr.txt"; exit 1; }
  read -r wall_s peak_kib <"$work/time.txt"
  awk -v l="$label" -v w="$wall_s" -v p="$peak_kib" 'BEGIN { printf "%s: %.2f s, peak %.1f MB\n", l, w, p / 1024 }'
}
timed "report (HTML) of the run" build/bin/rcsim report "$db" -o "$work/report.html"
awk -v b="$(stat -c %s "$work/report.html")" 'BEGIN { printf "report size: %.2f MB\n", b / 1e6 }'
timed "profile derive of the frames" build/bin/rcsim profile derive "$rec" -o "$work/derived.json"
if [ "${SKIP_CALIBRATE:-0}" != 1 ]; then
  rm -rf "$work/calibration"
  timed "calibrate --real-drive of the frames" build/bin/rcsim calibrate --real-drive "$rec" -o "$work/calibration"
fi

build/bin/rcsim_bench_pointcloud "$rec" "$work/frames.txt" | tee "$work/assignment.txt"

# Debian's python3-scipy lives beside /usr/bin/python3 (a python3 earlier on PATH may lack it).
python=""
for candidate in python3 /usr/bin/python3; do
  if "$candidate" -c "import scipy" 2>/dev/null; then python=$candidate; break; fi
done
if [ -z "$python" ]; then
  echo "scipy: python3-scipy not installed, its linear_sum_assignment not timed"
  exit 0
fi
sparse_ms=$(awk '$1 == "all" && $2 == "targets" { print $4 }' "$work/assignment.txt")
"$python" - "$work/frames.txt" "$sparse_ms" <<'EOF'
# scipy.optimize.linear_sum_assignment on the same frames, GOSPA's costs min(d, c)^2, c = 2 m.
import sys, time
import numpy as np
from scipy.optimize import linear_sum_assignment
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

c = 2.0
data = np.loadtxt(sys.argv[1])
sparse_ms = float(sys.argv[2])
frames = []
for k in np.unique(data[:, 0]).astype(int):
    rows = data[data[:, 0] == k]
    frames.append((rows[rows[:, 1] == 0][:, 2:4], rows[rows[:, 1] == 1][:, 2:4]))

def per_component(x, y):
    """The pairs closer than c, their connected components, one dense assignment each."""
    pairs = cKDTree(x).query_ball_tree(cKDTree(y), c)
    i = np.repeat(np.arange(len(x)), [len(p) for p in pairs])
    j = np.concatenate([np.asarray(p, dtype=int) for p in pairs]) if len(i) else np.zeros(0, int)
    n = len(x) + len(y)
    graph = coo_matrix((np.ones(len(i)), (i, len(x) + j)), shape=(n, n))
    _, label = connected_components(graph, directed=False)
    total = 0.0
    for component in np.unique(label[i]) if len(i) else []:
        xi = np.flatnonzero(label[: len(x)] == component)
        yj = np.flatnonzero(label[len(x):] == component)
        d = np.linalg.norm(x[xi, None, :] - y[None, yj, :], axis=2)
        cost = np.minimum(d, c) ** 2
        r, s = linear_sum_assignment(cost)
        total += cost[r, s].sum()
    return total

start = time.perf_counter()
for x, y in frames:
    per_component(x, y)
component_ms = 1e3 * (time.perf_counter() - start) / len(frames)
print(f"scipy linear_sum_assignment per component, {len(frames)} frames: {component_ms:.1f} ms a frame "
      f"({component_ms / sparse_ms:.0f} x the sparse assignment's {sparse_ms:.3f} ms)")
whole = frames[:3]
start = time.perf_counter()
for x, y in whole:
    d = np.linalg.norm(x[:, None, :] - y[None, :, :], axis=2)
    linear_sum_assignment(np.minimum(d, c) ** 2)
whole_ms = 1e3 * (time.perf_counter() - start) / len(whole)
print(f"scipy linear_sum_assignment on the whole frame's dense matrix, first {len(whole)} frames: {whole_ms:.0f} ms a frame "
      f"({whole_ms / sparse_ms:.0f} x)")
EOF
