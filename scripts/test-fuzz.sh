#!/usr/bin/env bash
# Every scene file loader fuzzed for a bounded time with libFuzzer (clang; build-fuzz/).
# scripts/test.sh runs this after the test suite; scripts/setup.sh installs clang and
# libclang-rt-14-dev. SB_FUZZ_SECONDS=N sets the seconds per target (default 20).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
# Clang (libFuzzer); SB_FUZZ builds only the scene library and fuzz/ (see fuzz/CMakeLists.txt).
cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSB_FUZZ=ON -DSB_WERROR=ON \
  "-DSB_FUZZ_SECONDS=${SB_FUZZ_SECONDS:-20}" >/dev/null
cmake --build build-fuzz -j "$jobs"
(cd build-fuzz && ctest --output-on-failure -j "$jobs" -L fuzz)
