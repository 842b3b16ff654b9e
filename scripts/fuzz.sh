#!/usr/bin/env bash
# The libFuzzer harnesses (docs/fuzzing.md): builds them into the sanitizer tree build-asan/
# (scripts/build-sanitize.sh: clang, every library instrumented with libFuzzer's coverage, ASan and
# UBSan; the tree scripts/test.sh also runs the whole suite from), gathers each harness's seed
# corpus from the repository's own files, and runs the harnesses for a bounded time, FUZZ_JOBS at
# a time.
#
# Usage: scripts/fuzz.sh [HARNESS...]          (default: every tests/fuzz/*_fuzz.cpp)
#   FUZZ_SECONDS=60     time per harness (libFuzzer -max_total_time)
#   FUZZ_JOBS=2         harnesses run at once (default: the cores, at most 2)
#   FUZZ_NO_BUILD=1     use the harnesses already built
#   FUZZ_NICE=0         niceness of the runs (long runs beside other work: 10)
#   FUZZ_ARGS="..."     more libFuzzer flags (e.g. -seed=1)
#   RCSIM_FUZZ_CORPUS_DIR  where the corpora grow from run to run, outside the clone, so that a
#                       new clone's 60 s start where the last run ended
#                       (default: ~/.cache/rcsim/fuzz-corpus; never checked in)
# Fails if any harness finds a crash, a sanitizer report, a hang (-timeout) or a memory blow-up
# (-rss_limit_mb, -malloc_limit_mb); the input is in build-asan/fuzz/findings/HARNESS/, the log in
# build-asan/fuzz/logs/HARNESS.log.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=${RCSIM_SANITIZE_BUILD_DIR:-build-asan}
seconds=${FUZZ_SECONDS:-60}
niceness=${FUZZ_NICE:-0}
lanes=${FUZZ_JOBS:-$(( $(nproc) < 2 ? $(nproc) : 2 ))}
work=$root/$build/fuzz
corpus_root=${RCSIM_FUZZ_CORPUS_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/rcsim/fuzz-corpus}

all_harnesses() {
  for f in tests/fuzz/*_fuzz.cpp; do basename "$f" .cpp; done
}
if [ $# -gt 0 ]; then
  harnesses=()
  for h in "$@"; do harnesses+=("${h%_fuzz}_fuzz"); done
else
  mapfile -t harnesses < <(all_harnesses)
fi

# ---- build ----
if [ "${FUZZ_NO_BUILD:-0}" != "1" ]; then
  scripts/build-sanitize.sh "${harnesses[@]}" rcsim_fuzz_regressions
fi

# ---- seeds: the repository's own files, as each harness reads them ----
separator=$'\n=====\n'

# The json code blocks of a schema document, one file each.
schema_examples() {  # schema_examples FILE.md OUT_DIR PREFIX
  awk -v out="$2" -v prefix="$3" '
    /^```json/ { n++; file = sprintf("%s/%s_%d.json", out, prefix, n); inside = 1; next }
    /^```/ { inside = 0; next }
    inside { print > file }' "$1"
}

# A recording cut to its first CYCLES cycles, as one bundle (recording.json, ego.csv, objects.csv,
# targets.csv; tests/fuzz/fuzz_support.hpp).
recording_bundle() {  # recording_bundle DIR CYCLES
  local dir=$1 cycles=$2 t_last
  cat "$dir/recording.json"
  printf '%s' "$separator"
  head -n $((cycles + 1)) "$dir/ego.csv"
  t_last=$(sed -n "$((cycles + 1))p" "$dir/ego.csv" | cut -d, -f1)
  [ -n "$t_last" ] || t_last=$(tail -n 1 "$dir/ego.csv" | cut -d, -f1)
  printf '=====\n'
  awk -F, -v t="$t_last" 'NR == 1 || $1 + 0 <= t + 1e-9' "$dir/objects.csv"
  printf '=====\n'
  awk -F, -v n="$cycles" 'NR == 1 || $2 + 0 < n' "$dir/targets.csv"
}

# One seed per section of a bundle base, at its place (the others kept from the base), and the
# whole base.
base_sections() {  # base_sections BASE_FILE OUT_DIR
  python3 - "$1" "$2" <<'EOF'
import pathlib, sys
base, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
sep = "\n=====\n"
sections = base.read_text().split(sep)
(out / "base").write_text(base.read_text())
for i, s in enumerate(sections):
    if s:
        (out / f"base_section_{i}").write_text(sep * i + s)
EOF
}

gather_seeds() {  # gather_seeds HARNESS DIR
  local h=${1%_fuzz} dir=$2 f n
  rm -rf "$dir"
  mkdir -p "$dir"
  case $h in
    scene)
      n=0
      for f in recordings_synthetic/scenes/*.json recordings_synthetic/campaign/scenes/*.json docs/examples/*.json; do
        n=$((n + 1)); cp "$f" "$dir/$(printf '%03d' $n)_$(basename "$f")"
      done
      schema_examples schemas/scene.md "$dir" schema ;;
    object_model)
      for f in src/model/models/*.json; do cp "$f" "$dir/builtin_$(basename "$f")"; done
      for f in recordings_synthetic/calibration/model_*.json; do cp "$f" "$dir/calibrated_$(basename "$f")"; done
      cp recordings_synthetic/campaign/calibration/model_passenger_car.json "$dir/campaign_model_passenger_car.json"
      schema_examples schemas/object-model.md "$dir" schema ;;
    sensor_config)
      for f in src/sensor/sensors/*.json; do cp "$f" "$dir/builtin_$(basename "$f")"; done
      cp recordings_synthetic/calibration/sensor_srr24.json "$dir/calibrated_srr24.json"
      cp recordings_synthetic/campaign/calibration/sensor_srr24.json "$dir/campaign_srr24.json"
      schema_examples schemas/sensor-config.md "$dir" schema ;;
    recording)
      for f in recordings_synthetic/*/recording.json recordings_synthetic/campaign/*/recording.json; do
        f=$(dirname "$f")
        recording_bundle "$f" 25 > "$dir/$(basename "$f")"
      done
      schema_examples schemas/recording.md "$dir" schema
      base_sections tests/fuzz/base/recording.txt "$dir" ;;
    calibration)
      cp recordings_synthetic/calibration/calibration.json "$dir/synthetic_calibration.json"
      cp recordings_synthetic/campaign/calibration/calibration.json "$dir/campaign_calibration.json"
      schema_examples schemas/calibration.md "$dir" schema
      base_sections tests/fuzz/base/calibration.txt "$dir" ;;
    aimotive)
      base_sections tests/fuzz/base/aimotive.txt "$dir" ;;
    astyx)
      base_sections tests/fuzz/base/astyx.txt "$dir" ;;
    udp_datagram|udp_control|report_database|mcap|openlabel)
      # Datagrams made by the project's encoders (udp_targets.hpp), and report databases replayed
      # from the recording base (store_targets.hpp): written by the harness itself.
      RCSIM_FUZZ_WRITE_SEEDS=$dir "$build/bin/${h}_fuzz" ;;
    campaign_manifest)
      # The schema's examples, read beside drives/a, drives/b and extra/drive_0042 (store_targets.hpp).
      schema_examples schemas/campaign.md "$dir" schema ;;
  esac
  if [ -d "tests/fuzz/corpus/$h" ]; then cp tests/fuzz/corpus/"$h"/* "$dir"/ 2>/dev/null || true; fi
  if [ -d "tests/fuzz/regressions/$h" ]; then cp tests/fuzz/regressions/"$h"/* "$dir"/ 2>/dev/null || true; fi
}

# ---- the checked-in crash inputs and the bases first (tests/fuzz/fuzz_regressions_test.cpp) ----
if [ -x "$build/bin/rcsim_fuzz_regressions" ]; then
  "$build/bin/rcsim_fuzz_regressions" --gtest_brief=1
fi

# ---- runs ----
# The harnesses write each input's files into a scratch directory: on tmpfs where there is one
# (the recording and aiMotive harnesses spent a third of their time in ext4 otherwise).
if [ -z "${TMPDIR:-}" ] && [ -d /dev/shm ] && [ -w /dev/shm ]; then export TMPDIR=/dev/shm; fi
# run_harness HARNESS: gathers its seeds, fuzzes it, and leaves its exit status in logs/HARNESS.status.
run_harness() {
  local harness=$1 h=${1%_fuzz} status=0
  local seeds=$work/seeds/$h corpus=$corpus_root/$h findings=$work/findings/$h log=$work/logs/$h.log
  mkdir -p "$corpus" "$findings" "$work/logs"
  gather_seeds "$h" "$seeds"
  local dict=()
  [ -f "tests/fuzz/$h.dict" ] && dict=(-dict="tests/fuzz/$h.dict")
  echo "== fuzzing $h for ${seconds} s ($(ls "$seeds" | wc -l) seeds, $(ls "$corpus" | wc -l) in the corpus)"
  # shellcheck disable=SC2086
  nice -n "$niceness" "$build/bin/${h}_fuzz" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 \
    -print_final_stats=1 -artifact_prefix="$findings/" "${dict[@]}" ${FUZZ_ARGS:-} "$corpus" "$seeds" > "$log" 2>&1 || status=$?
  echo "$status" > "$work/logs/$h.status"
}

mkdir -p "$work/logs"
for harness in "${harnesses[@]}"; do
  rm -f "$work/logs/${harness%_fuzz}.status"
  while [ "$(jobs -rp | wc -l)" -ge "$lanes" ]; do wait -n || true; done
  run_harness "$harness" &
done
wait

failed=()
summary=()
for harness in "${harnesses[@]}"; do
  h=${harness%_fuzz}
  log=$work/logs/$h.log findings=$work/findings/$h
  status=$(cat "$work/logs/$h.status" 2>/dev/null || echo "?")
  done_line=$(grep -E '^#[0-9]+[[:space:]]+DONE' "$log" | tail -n 1 || true)
  [ -n "$done_line" ] || done_line=$(grep -E '^#[0-9]+' "$log" | tail -n 1 || true)
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$done_line")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$done_line")
  summary+=("$(printf '%-14s %12s execs  cov %6s  ft %7s  %s' "$h" "${execs:-?}" "${cov:-?}" "${ft:-?}" \
               "$([ "$status" = 0 ] && echo ok || echo "FAILED (exit $status)")")")
  if [ "$status" != 0 ]; then
    failed+=("$h")
    echo "-- $h failed (exit $status); the end of $log:"
    tail -n 60 "$log"
    ls -l "$findings"
  fi
done

echo "== fuzz summary (${seconds} s each, ${lanes} at a time; corpora in $corpus_root)"
printf '%s\n' "${summary[@]}"
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: findings in ${failed[*]} (inputs in $work/findings/)" >&2
  exit 1
fi
