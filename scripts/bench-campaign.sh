#!/usr/bin/env bash
# The campaign benchmark (issue 20, docs/campaigns.md): 200 generated drives of 10 minutes each
# (a 33-hour campaign, about 1.7 GB of CSV, not committed) replayed serially and as a Slurm job
# array of 2 shards on a one-node cluster the program starts on loopback (as root, slurm-wlm and
# munge from scripts/setup.sh), then merged.
# Usage: scripts/bench-campaign.sh [WORK_DIR=/tmp/rcsim-bench-campaign] [DRIVES=200] [DURATION_S=600] [SHARDS=2]
set -euo pipefail
cd "$(dirname "$0")/.."
work=${1:-/tmp/rcsim-bench-campaign}
bash scripts/setup.sh build >/dev/null
grep -m1 "model name" /proc/cpuinfo
echo "cores: $(nproc), rcsim $(build/bin/rcsim --version 2>/dev/null || echo '?')"
build/bin/rcsim_bench_campaign "$work" "${2:-200}" "${3:-600}" "${4:-2}"
