#!/usr/bin/env bash
# The nightly job: the nightly suite (suites/nightly.json) into OUT; the GoogleTest suites too
# heavy for the test command (Nightly/*: each paper figure small on the API the test command
# does not run it on); the file loaders fuzzed for longer (SB_FUZZ_SECONDS, 300 here against the
# test command's 10); every quick-suite pair on the compute and mesh paths against the CPU path
# (scripts/geometry-parity.py; the mesh path where drivers/mesa-25.0 is); then everything the
# docs publish whose code changed since it was measured re-measured
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
build/sb_tests --gtest_filter='Nightly/*' || status=$?
SB_FUZZ_SECONDS=${SB_FUZZ_SECONDS:-300} scripts/test-fuzz.sh || status=$?
scripts/geometry-parity.py || status=$?
scripts/docs-refresh-stale.sh || status=$?
exit $status
