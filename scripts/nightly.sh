#!/usr/bin/env bash
# The nightly job: the nightly suite (suites/nightly.json) into OUT, every quick-suite pair on
# the compute and mesh paths against the CPU path (scripts/geometry-parity.py; the mesh path
# where drivers/mesa-25.0 is),
# then everything the docs publish whose code changed since it was measured re-measured
# (scripts/docs-refresh-stale.sh: stale stored runs and figure pages) and the docs rendered
# again. Run on a clean checkout; the job commits docs/ and README.md afterwards (or opens a
# change with them).
# Usage: scripts/nightly.sh [OUT]     (default out/nightly-DATE)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/nightly-$(date -u +%F)}
[ -x build/strandbench ] || { echo "nightly.sh: build/strandbench missing: run scripts/setup.sh" >&2; exit 2; }
status=0
build/strandbench sweep suites/nightly.json --out "$out" --resume || status=$?
scripts/geometry-parity.py || status=$?
scripts/docs-refresh-stale.sh || status=$?
exit $status
