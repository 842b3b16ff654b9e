#!/usr/bin/env bash
# Installs what rcsim needs from Debian's packages (only what is missing), then configures and
# builds. Usage: scripts/setup.sh [BUILD_DIR] [extra cmake arguments...]
#   RCSIM_TARGETS="rcsim ..."  builds only these targets (default: everything)
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:-build}
shift || true

# slurm-wlm and munge: the campaign tests start a one-node Slurm cluster on loopback
# (tests/end_to_end/slurm_cluster.hpp); libxml2-utils: xmllint validates the JUnit output.
# shellcheck disable=SC2046
scripts/install-packages.sh $(cat scripts/build-packages.txt) chromium fonts-dejavu-core tshark slurm-wlm munge libxml2-utils

# ccache keys on paths relative to the checkout, so that a fresh clone elsewhere reuses the
# cache (and a debug build's working directory is left out of the key).
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-1}"
jobs=$(( $(nproc) < 2 ? $(nproc) : 2 ))
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
# shellcheck disable=SC2086
cmake --build "$build_dir" -j "$jobs" ${RCSIM_TARGETS:+--target $RCSIM_TARGETS}
