#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (unit, backend, CLI tests).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh -DSB_WERROR=ON
cd build
ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "$@"
