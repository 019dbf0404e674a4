#!/usr/bin/env bash
# Runs a suite on a Slurm cluster as a job array of N shards plus a merge job that starts when
# every shard has succeeded (--dependency=afterok); the result is OUTROOT/merged.
# Usage: scripts/slurm/submit.sh [--gres GRES] [--sbatch "ARGS"] SUITE OUTROOT N [SWEEP ARGS...]
#   --gres GRES     e.g. gpu:1: a GPU per array task (the merge job asks for none)
#   --sbatch ARGS   more sbatch options for both jobs (partition, time, account), one string
#   SB_CLI          the strandbench binary (default: build/strandbench of this tree)
# OUTROOT must be on a file system every node sees. Prints the two job ids (array, merge).
# Example: scripts/slurm/submit.sh --gres gpu:1 suites/quick.json /shared/nightly/$(date +%F) 4
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
gres=""
extra=""
while (($#)); do
  case "$1" in
    --gres) gres=${2:?--gres needs a value, e.g. gpu:1}; shift 2 ;;
    --sbatch) extra=${2:?--sbatch needs a string of options}; shift 2 ;;
    -h | --help) sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) break ;;
  esac
done
if (($# < 3)); then
  echo "submit.sh: expected SUITE OUTROOT N (see --help)" >&2
  exit 2
fi
suite=$(realpath "$1")
outroot=$(realpath -m "$2")
n=$3
shift 3
[[ "$n" =~ ^[1-9][0-9]*$ ]] || { echo "submit.sh: N=$n: expected a number of shards >= 1" >&2; exit 2; }
[ -f "$suite" ] || { echo "submit.sh: suite $suite: no such file" >&2; exit 2; }
cli=$(realpath "${SB_CLI:-$here/../../build/strandbench}")
[ -x "$cli" ] || { echo "submit.sh: $cli is not an executable (build first, or set SB_CLI)" >&2; exit 2; }
mkdir -p "$outroot/logs"
gresArg=()
[ -n "$gres" ] && gresArg=(--gres="$gres")
# shellcheck disable=SC2086  # $extra is a list of options
array=$(sbatch --parsable --array="0-$((n - 1))" "${gresArg[@]}" $extra \
  --output="$outroot/logs/shard-%a.log" \
  "$here/sweep-array.sbatch" "$cli" "$suite" "$outroot" "$@")
array=${array%%;*}
# shellcheck disable=SC2086
merge=$(sbatch --parsable --dependency="afterok:$array" --kill-on-invalid-dep=yes $extra \
  --output="$outroot/logs/merge.log" "$here/merge.sbatch" "$cli" "$outroot")
merge=${merge%%;*}
echo "array job $array ($n shards), merge job $merge -> $outroot/merged"
