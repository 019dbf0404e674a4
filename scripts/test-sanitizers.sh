#!/usr/bin/env bash
# The whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/),
# under xvfb-run, then every scene file loader fuzzed for a bounded time with libFuzzer
# (build-fuzz/), whether or not the suite passed; exits non-zero if either failed.
# scripts/test.sh runs this after the normal tests; scripts/setup.sh installs what it needs
# (clang and libclang-rt-14-dev for libFuzzer, llvm for llvm-symbolizer).
# Usage: scripts/test-sanitizers.sh [ctest args for the sanitizer suite...]
#   SB_FUZZ_SECONDS=N   seconds each fuzz target runs (default 20)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
jobs=$(nproc 2>/dev/null || echo 2)

# --- 1. the test suite under ASan + UBSan ----------------------------------------------
# GCC, because clang 14 (Debian 12) cannot build the harness (C++20 lambdas capturing
# structured bindings). -Og: GCC with -fsanitize=undefined compiles about twice as fast at
# -Og as at -O1 (the heaviest harness file: 22 s against 42 s; a Release -O3 build: 22 s),
# and the tests run about as fast. -g1 gives file:line in reports. _GLIBCXX_ASSERTIONS adds
# bounds checks to std::vector::operator[] and the like (ASan alone misses reads between a
# vector's size and its capacity); float-cast-overflow is not in GCC's -fsanitize=undefined.
# SB_SANITIZE makes UB fatal (-fno-sanitize-recover) and keeps drivers loaded until exit
# (cmake/keep_libraries_loaded.c). The instrumentation confuses GCC's flow analysis
# (-Wmaybe-uninitialized false positives in <regex>), so this build does not use -Werror:
# the normal build is the warnings gate.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DSB_SANITIZE=ON \
  "-DCMAKE_CXX_FLAGS_DEBUG=-Og -g1 -D_GLIBCXX_ASSERTIONS -fsanitize=float-cast-overflow -Wno-maybe-uninitialized" \
  "-DCMAKE_C_FLAGS_DEBUG=-Og -g1" >/dev/null
cmake --build build-asan -j "$jobs"

# Runtime options, inherited by the CLI processes the tests start:
# - The executables link the sanitizer runtimes themselves, so the drivers that libEGL,
#   OSMesa and the Vulkan loader dlopen (llvmpipe, lavapipe, the validation layer) run
#   under them with no LD_PRELOAD: their malloc/free go through ASan, their code is not
#   instrumented (no reports from inside them), and Mesa's JIT'd shaders run as usual.
# - Leaks: LeakSanitizer runs at every exit. scripts/lsan.supp suppresses leaks allocated
#   inside third-party libraries only (each entry says why); a leak from our code fails the
#   test. print_suppressions=0 keeps the suppression summary off stderr, which some CLI
#   tests require to be empty. Reporting unsuppressed driver leaks is slow (a Vulkan test
#   leaking lavapipe's 65 MB took 27 s instead of 4.6 s), another reason to keep them out.
# - intercept_tls_get_addr=0: GCC 12's runtime (and LLVM's up to 16) misreads some dynamic
#   TLS blocks (the drivers' TLS, dlopen'ed) as pre-glibc-2.25 ones, and LeakSanitizer's
#   tracer then dies at exit ("Tracer caught signal 11"), failing about 1 test run in 300.
#   The TLS blocks stay reachable through each thread's DTV, so leak checking loses nothing.
# - UBSan: halt_on_error=1 as well as -fno-sanitize-recover, so a report fails the test.
# - SB_VALIDATION=1 (set by ctest) keeps the Vulkan validation layer on; it works under
#   ASan unchanged.
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:check_initialization_order=1:intercept_tls_get_addr=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$root/scripts/lsan.supp:print_suppressions=0"
if command -v llvm-symbolizer >/dev/null; then
  export ASAN_SYMBOLIZER_PATH
  ASAN_SYMBOLIZER_PATH=$(command -v llvm-symbolizer)
fi
# Under a virtual X display (Debian's xvfb), as scripts/test.sh runs the suite: the window
# platforms' and the viewer's tests need one and would otherwise skip. A failure here does
# not stop the script: the loaders are still fuzzed, and the exit status is non-zero at the
# end if either part failed.
failed=()
if command -v xvfb-run >/dev/null; then
  (cd build-asan && xvfb-run -a -s "-screen 0 1024x768x24 -noreset" \
    ctest --output-on-failure -j "$jobs" "$@") || failed+=("the test suite under ASan + UBSan")
else
  echo "test-sanitizers: xvfb-run not found (apt-get install xvfb): the window and viewer" \
    "tests skip" >&2
  (cd build-asan && ctest --output-on-failure -j "$jobs" "$@") ||
    failed+=("the test suite under ASan + UBSan")
fi

# --- 2. fuzz the loaders -----------------------------------------------------------------
scripts/test-fuzz.sh || failed+=("fuzzing (scripts/test-fuzz.sh)")

if ((${#failed[@]})); then
  printf 'test-sanitizers: failed: %s\n' "${failed[@]}" >&2
  exit 1
fi
