#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (unit, backend, CLI tests, the extreme
# suite), then fuzzes every file loader for a bounded time (scripts/test-fuzz.sh, 10 s each here;
# the nightly job fuzzes longer).
# The suite under ASan + UBSan is scripts/test-sanitizers.sh (not run here: see docs/testing.md).
# ctest runs under xvfb-run (a virtual X display): the window platforms' tests need one.
# -noreset: Xvfb otherwise resets when its last client leaves and refuses the next meanwhile.
# CI=true (as CI sets it; the default here) makes a test that cannot create its backend, its
# window or Chromium fail instead of skipping (tests/main.cpp); CI=false lets them skip.
# At the end it prints the skips by reason and the slowest tests.
set -euo pipefail
cd "$(dirname "$0")/.."
export CI=${CI:-true}
scripts/setup.sh --tests
rm -rf build/test-skips build/test-xml
status=0
(cd build && xvfb-run -a -s "-screen 0 1024x768x24 -noreset" \
  ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "$@") || status=$?
scripts/test-report.sh build
SB_FUZZ_SECONDS=${SB_FUZZ_SECONDS:-10} scripts/test-fuzz.sh || status=1
exit "$status"
