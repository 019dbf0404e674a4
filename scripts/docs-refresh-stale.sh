#!/usr/bin/env bash
# Re-measures everything the docs publish whose code changed since it was measured, in one
# command (the merger's and the nightly job's): `strandbench docs refresh --stale` lists the
# stale store blocks and figure pages; each stale stored run is re-recorded with the command in
# its meta.json (scripts/docs-record.sh, or the command itself where its script does not take
# $SB_DOCS_RESULTS but writes the store itself, as scripts/fresh-machine-check.sh does), each stale figure page is re-run with the command in
# its header (its size and rounds, --docs docs/figures) on both APIs (--backend both), then `strandbench docs refresh` renders
# every block. Refused on a tree with uncommitted code (the runs must be a commit's); commit the
# rewritten docs/ afterwards.
# Usage: scripts/docs-refresh-stale.sh [--list] [--only-runs | --only-figures]
#   --list           print what would be re-run, run nothing
#   --only-runs      the stored runs only;  --only-figures: the figure pages only
# SB_FIGURES_OUT: where the figure runs' folders go (default out/figures).
# SB_FIGURE_CASES: the shared case store of the refresh (default: a new folder in
# SB_FIGURES_OUT, removed at the end): a case several stale figures run is measured once, by the
# first, and the others' pages print that measurement (harness/case_store.h).
set -euo pipefail
cd "$(dirname "$0")/.."
list=0 runs=1 figures=1
for a in "$@"; do
  case $a in
    --list) list=1 ;;
    --only-runs) figures=0 ;;
    --only-figures) runs=0 ;;
    *) sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2; exit 2 ;;
  esac
done
cli=build/strandbench
[ -x "$cli" ] || { echo "docs-refresh-stale.sh: $cli missing: run scripts/setup.sh" >&2; exit 2; }
if [ $list = 0 ] && [ -n "$(git status --porcelain --untracked-files=no -- . ':!docs' ':!README.md')" ]; then
  echo "docs-refresh-stale.sh: the tree has uncommitted code; commit it first:" >&2
  git status --short --untracked-files=no -- . ':!docs' ':!README.md' >&2
  exit 2
fi
status=0
stale=$("$cli" docs refresh --stale) || status=$?
# 1: some are stale; anything else: the store could not be read (named above).
[ $status -le 1 ] || exit "$status"
# "PAGE: RUN/BLOCK (run of C): FILES" and "PAGE: figure NAME (run of C): FILES".
mapfile -t stale_runs < <(sed -n 's|^[^:]*: \([^ /]*\)/[^ ]* (run of .*|\1|p' <<<"$stale" | sort -u)
mapfile -t stale_pages < <(sed -n 's|^\([^:]*\): figure [^ ]* (run of .*|\1|p' <<<"$stale" | sort -u)
[ $runs = 1 ] || stale_runs=()
[ $figures = 1 ] || stale_pages=()
echo "docs-refresh-stale.sh: ${#stale_runs[@]} stored runs, ${#stale_pages[@]} figure pages stale"
failed=0
for run in "${stale_runs[@]}"; do
  command=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["command"])' \
    "docs/results/$run/meta.json")
  eval "cmd=($command)"
  script=""
  for w in "${cmd[@]}"; do [[ $w == scripts/* ]] && { script=$w; break; }; done
  if [ -n "$script" ] && ! grep -q 'SB_DOCS_RESULTS' "$script"; then
    line=("${cmd[@]}")  # the script writes its run into the store itself (fresh-machine)
  else
    line=(scripts/docs-record.sh "$run" "${cmd[@]}")
  fi
  echo "run $run: ${line[*]}"
  [ $list = 1 ] && continue
  start=$(date +%s)
  "${line[@]}" || { echo "run $run: failed (exit $?)"; failed=1; }
  echo "run $run: $(($(date +%s) - start)) s"
done
out=${SB_FIGURES_OUT:-out/figures}
if [ $list = 0 ] && [ ${#stale_pages[@]} -gt 0 ] && [ -z "${SB_FIGURE_CASES:-}" ]; then
  mkdir -p "$out"
  SB_FIGURE_CASES=$(mktemp -d "$out/cases.XXXXXX")
  trap 'rm -rf "$SB_FIGURE_CASES"' EXIT
fi
export SB_FIGURE_CASES
[ -z "${SB_FIGURE_CASES:-}" ] || echo "case store of the figures: $SB_FIGURE_CASES"
for page in "${stale_pages[@]}"; do
  # The header's command: `strandbench figure NAME [--small] [--min-reps N] --backend B --out X --docs D`.
  header=$(head -n 1 "$page" | sed -n 's/.*written by `strandbench \(figure [^`]*\)`.*/\1/p')
  [ -n "$header" ] || { echo "$page: no figure command in its header" >&2; failed=1; continue; }
  read -r -a args <<<"$header"
  name=${args[1]}
  keep=()
  for ((i = 2; i < ${#args[@]}; i++)); do
    case ${args[$i]} in
      --out | --docs | --backend) i=$((i + 1)) ;;
      *) keep+=("${args[$i]}") ;;
    esac
  done
  # Every page on both APIs, whichever its header names (a page made before --backend both).
  line=("$cli" figure "$name" "${keep[@]}" --backend both --out "$out/$name" --docs "$(dirname "$page")")
  echo "figure $name: ${line[*]}"
  [ $list = 1 ] && continue
  mkdir -p "$out"
  start=$(date +%s)
  nice -n 19 "${line[@]}" || { echo "figure $name: failed (exit $?)"; failed=1; }
  echo "figure $name: $(($(date +%s) - start)) s"
done
[ $list = 1 ] && exit 0
"$cli" docs refresh
echo "docs-refresh-stale.sh: done; commit docs/ and README.md (git add -A docs README.md)"
exit $failed
