#!/usr/bin/env bash
# After ctest: the GoogleTest tests one by one (passed, failed by name, skipped by reason),
# from the XML reports and skip logs the test processes write (cmake/TestSuites.cmake,
# tests/main.cpp), and the slowest ctest tests of the last run with their seconds.
# Usage: scripts/test-report.sh [BUILD_DIR]
# (docs/test-times.md is rendered from the fresh-machine check's stored run of this report.)
set -uo pipefail
build=${1:-build}

skip_counts() { cat "$build"/test-skips/*.txt 2>/dev/null | cut -f1 | sed 's/: .*//' | sort | uniq -c | sort -rn; }
# LastTest.log: a "N/M Test: NAME" line, later "Test time =   S sec".
slowest() {
  local log="$build/Testing/Temporary/LastTest.log"
  [ -f "$log" ] || return 0
  # The first N by reading every line (not head, which would close the pipe early and end
  # sort with SIGPIPE: under pipefail, a failed report and so a failed test command).
  awk '/^[0-9]+\/[0-9]+ Test: /{name=$3} /^Test time =/{printf "%8.1f  %s\n", $4, name}' "$log" |
    sort -rn | awk -v n="$1" 'NR <= n'
}

# Sums an attribute over the <testsuite> elements of every report.
total() { (cat "$build"/test-xml/*.xml 2>/dev/null || true) | (grep -o "<testsuite [^>]*" | grep -o " $1=\"[0-9]*\"" |
  grep -o "[0-9]*" || true) | awk '{s += $1} END {print s + 0}'; }
tests=$(total tests)
failures=$(total failures)
echo "== GoogleTest tests: $tests, failed: $failures, skipped: $(total skipped)"
if ((failures)); then
  cat "$build"/test-xml/*.xml | awk '/<testcase /{match($0, /name="[^"]*"/); t=substr($0, RSTART+6, RLENGTH-7);
    match($0, /classname="[^"]*"/); c=substr($0, RSTART+11, RLENGTH-12)} /<failure /{print "  FAILED " c "." t}' | sort -u
fi
skips=$( (cat "$build"/test-skips/*.txt 2>/dev/null || true) | wc -l)
echo "== skipped tests: $skips"
skip_counts
echo "== slowest tests (seconds)"
slowest 20
