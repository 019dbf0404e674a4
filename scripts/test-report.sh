#!/usr/bin/env bash
# After ctest: the GoogleTest tests one by one (passed, failed by name, skipped by reason),
# from the XML reports and skip logs the test processes write (cmake/TestSuites.cmake,
# tests/main.cpp), and the slowest ctest tests of the last run with their seconds.
# Usage: scripts/test-report.sh [BUILD_DIR] [--markdown FILE]
#   --markdown FILE   also write them as a Markdown page (docs/test-times.md), headed by
#                     the command, commit, date and machine load that produced them
set -uo pipefail
build=${1:-build}
markdown=""
if [ "${2:-}" = "--markdown" ]; then markdown=${3:?--markdown needs a file}; fi

skip_counts() { cat "$build"/test-skips/*.txt 2>/dev/null | cut -f1 | sed 's/: .*//' | sort | uniq -c | sort -rn; }
# LastTest.log: a "N/M Test: NAME" line, later "Test time =   S sec".
slowest() {
  local log="$build/Testing/Temporary/LastTest.log"
  [ -f "$log" ] || return 0
  awk '/^[0-9]+\/[0-9]+ Test: /{name=$3} /^Test time =/{printf "%8.1f  %s\n", $4, name}' "$log" |
    sort -rn | head -n "$1"
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
slowest 10

if [ -n "$markdown" ]; then
  {
    echo "# The slowest tests"
    echo
    echo "Written by \`scripts/test-report.sh $build --markdown $markdown\` after \`scripts/test.sh\`,"
    echo "commit $(git rev-parse --short HEAD), $(date -u '+%Y-%m-%d %H:%M') UTC, $(nproc) cores, load"
    echo "average $(cut -d' ' -f1-3 /proc/loadavg) when written. Seconds are wall time under"
    echo "\`ctest -j$(nproc)\`, so a test shares the machine with another."
    echo
    echo "| seconds | ctest test (a GoogleTest suite, or an extreme-suite shard) |"
    echo "|---:|---|"
    slowest 20 | awk '{printf "| %s | `%s` |\n", $1, $2}'
    echo
    echo "Skipped: $skips."
    skip_counts | awk '{n=$1; $1=""; printf "- %s:%s\n", n, $0}'
  } >"$markdown.tmp"
  mv "$markdown.tmp" "$markdown"
  echo "wrote $markdown"
fi
