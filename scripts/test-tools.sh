#!/usr/bin/env bash
# The test suite's tools from the npm registry, pinned by their lockfiles (docs/ci.md): Node.js and
# npm from Debian where the machine has neither command, then `npm ci` in each tests/tools/*/ that
# holds a package-lock.json (again only when the lockfile changed). Where the registry cannot be
# reached the tools stay missing, and the tests that need one say so in one line and skip that
# part: this stage never fails the suite.
set -uo pipefail
cd "$(dirname "$0")/.."
if ! command -v npm >/dev/null || ! command -v node >/dev/null; then
  scripts/install-packages.sh nodejs npm || echo "test tools: Node.js and npm could not be installed"
fi
command -v npm >/dev/null || exit 0
for tool in tests/tools/*/; do
  [ -f "$tool/package-lock.json" ] || continue
  marker="$tool/node_modules/.rcsim-lock"
  if cmp -s "$tool/package-lock.json" "$marker"; then continue; fi  # installed as locked
  if npm ci --prefix "$tool" --no-audit --no-fund --loglevel=error; then
    cp "$tool/package-lock.json" "$marker"
  else
    echo "test tools: npm ci in $tool failed (no registry?): the tests that use it skip that part"
  fi
done
exit 0
