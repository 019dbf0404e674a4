#!/usr/bin/env bash
# docs/figures/: one generated page per paper figure (strandbench figure NAME --docs
# docs/figures), each with its header (command, commit, digest) that tests/test_figure_docs.cpp
# checks. One run per figure (both APIs interleaved: --backend both), one after the other, at
# nice 19.
# Usage: scripts/figures-docs.sh [--full] [NAME...]   (default: every figure, --small)
#   --full   the figures at the paper's size (hours for some: DOM Figs. 3 and 5, occ Fig. 1,
#            thesis Table 2); without it the --small variants
# SB_FIGURES_REPS=N: at least N timed rounds per case (the intervals and verdicts need >= 3).
# Commit first: a page names the commit it was made on (a dirty tree is said in the page).
set -euo pipefail
cd "$(dirname "$0")/.."
small=--small
if [[ ${1:-} == --full ]]; then
  small=
  shift
fi
names=("$@")
if [[ ${#names[@]} -eq 0 ]]; then
  mapfile -t names < <(build/strandbench figure --list | cut -d' ' -f1)
fi
out=${SB_FIGURES_OUT:-out/figures}
mkdir -p "$out"
for n in "${names[@]}"; do
  start=$(date +%s)
  nice -n 19 build/strandbench figure "$n" $small ${SB_FIGURES_REPS:+--min-reps $SB_FIGURES_REPS} --backend both --out "$out/$n" \
    --docs docs/figures || echo "figure $n: exit $?"
  echo "figure $n: $(($(date +%s) - start)) s"
done
