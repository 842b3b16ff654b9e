#!/usr/bin/env bash
# The MCAP benchmark (issue 33): `rcsim import --from mcap` of a generated two-radar ring-road drive
# of 1 h (and more), written as a ROS 2 log by the tests' tool (tests/tools/mcap/write_ros2_log.js:
# RadarScan in CDR or foxglove.PointCloud, Odometry, SceneUpdate boxes; zstd chunks), and
# `rcsim export --format mcap` of its replay. Times both with /usr/bin/time (wall time and peak
# resident memory); the same drive with a 300 MiB attachment and as ROS 2 bags (sqlite3 and mcap
# storage, split in two). Needs Node.js and the tool (scripts/test-tools.sh).
# Usage: scripts/bench-mcap.sh [DURATIONS_S="600 3600"] [WORK_DIR=/tmp/rcsim-bench-mcap]
set -euo pipefail
cd "$(dirname "$0")/.."
durations=${1:-"600 3600"}
work=${2:-/tmp/rcsim-bench-mcap}
bash scripts/setup.sh build >/dev/null
bash scripts/test-tools.sh >/dev/null
mkdir -p "$work"
grep -m1 "model name" /proc/cpuinfo
echo "cores: $(nproc), rcsim $(build/bin/rcsim --version 2>/dev/null || echo '?')"
printf '%-7s %-22s %10s %10s %12s\n' drive step "wall s" "peak MB" "file MB"
timed() {  # timed LABEL DURATION FILE COMMAND...: one row
  local label=$1 duration_s=$2 file=$3
  shift 3
  /usr/bin/time -o "$work/time.txt" -f "%e %M" "$@" >/dev/null 2>"$work/stderr.txt" || { cat "$work/stderr.txt"; exit 1; }
  read -r wall_s peak_kib <"$work/time.txt"
  local size_b=0
  [ -e "$file" ] && size_b=$(du -sb "$file" | cut -f1)
  awk -v d="$duration_s" -v l="$label" -v w="$wall_s" -v p="$peak_kib" -v b="$size_b" 'BEGIN {
    printf "%-7s %-22s %10.2f %10.1f %12.1f\n", d / 60 " min", l, w, p / 1024, b / 1e6 }'
}
for duration_s in $durations; do
  rec="$work/ring_drive_${duration_s}s"
  [ -f "$rec/targets.csv" ] || build/bin/rcsim_make_long_recording "$rec" "$duration_s" 1 >/dev/null
  for detections in radarscan pointcloud; do
    log="$work/drive_${duration_s}s_${detections}.mcap"
    [ -f "$log" ] || node --max-old-space-size=8000 tests/tools/mcap/write_ros2_log.js "$rec" "$log" --compression zstd \
      --detections "$detections" --mapping "$log.mapping.json" >/dev/null
    rm -rf "$work/imported"
    timed "import ($detections)" "$duration_s" "$log" build/bin/rcsim import --from mcap "$log" --mapping "$log.mapping.json" -o "$work/imported"
  done
  # A log with a 300 MiB attachment (skipped unread), and the drive as ROS 2 bags split in two,
  # in either storage (issue 50).
  log="$work/drive_${duration_s}s_attached.mcap"
  [ -f "$log" ] || node --max-old-space-size=8000 tests/tools/mcap/write_ros2_log.js "$rec" "$log" --compression zstd \
    --attachment-mib 300 --mapping "$log.mapping.json" >/dev/null
  rm -rf "$work/imported"
  timed "import (300 MiB attached)" "$duration_s" "$log" build/bin/rcsim import --from mcap "$log" --mapping "$log.mapping.json" -o "$work/imported"
  for storage in sqlite3 mcap; do
    bag="$work/bag_${duration_s}s_${storage}"
    [ -f "$bag/metadata.yaml" ] || node --max-old-space-size=8000 tests/tools/mcap/write_ros2_log.js "$rec" "$bag" --compression zstd \
      --storage "$storage" --split 2 --boxes openlabel --mapping "$bag.mapping.json" >/dev/null
    # The bag alone (a ROS 2 bag carries no foxglove JSON boxes), then with the boxes of a
    # 144 MB OpenLABEL file beside it (read whole).
    python3 -c "import json, sys; m = json.load(open(sys.argv[1])); m.pop('objects'); json.dump(m, open(sys.argv[2], 'w'))" \
      "$bag.mapping.json" "$bag.noboxes.json"
    rm -rf "$work/imported"
    timed "import (bag, $storage)" "$duration_s" "$bag" build/bin/rcsim import --from rosbag2 "$bag" --mapping "$bag.noboxes.json" -o "$work/imported"
    rm -rf "$work/imported"
    timed "  + OpenLABEL boxes" "$duration_s" "$bag" build/bin/rcsim import --from rosbag2 "$bag" --mapping "$bag.mapping.json" -o "$work/imported"
  done
  db="$work/report_${duration_s}.sqlite"
  rm -f "$db"*
  timed "replay (own clocks)" "$duration_s" "$db" build/bin/rcsim replay "$work/imported" --db "$db"
  timed "export (own clocks)" "$duration_s" "$work/run.mcap" build/bin/rcsim export "$db" --run 1 --format mcap -o "$work/run.mcap"
  # The same drive on one shared clock (the generated recording itself): its replay exported.
  rm -f "$db"*
  timed "replay (shared clock)" "$duration_s" "$db" build/bin/rcsim replay "$rec" --db "$db"
  timed "export (shared clock)" "$duration_s" "$work/run.mcap" build/bin/rcsim export "$db" --run 1 --format mcap -o "$work/run.mcap"
done
