#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (unit, backend, CLI tests, the extreme
# suite), then fuzzes every file loader for a bounded time (scripts/test-fuzz.sh).
# The suite under ASan + UBSan is scripts/test-sanitizers.sh (not run here: see README).
# ctest runs under xvfb-run (a virtual X display, Debian's xvfb): the window platforms'
# tests (--platform window, `view`) need a display; without one they skip with the reason.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh -DSB_WERROR=ON
(cd build && xvfb-run -a -s "-screen 0 1024x768x24" \
  ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "$@")
scripts/test-fuzz.sh
