#!/usr/bin/env bash
# Benchmark (not a test): a 1M-segment scene (62,500 straight strands x 16
# segments) at 512x512 on both backends, median ms per pass over repetitions.
# Usage: scripts/bench-1m.sh [repeat] [extra render args...]
set -euo pipefail
cd "$(dirname "$0")/.."
repeat=${1:-5}
shift || true
for backend in gl vulkan; do
  for primitive in lines ribbons; do
    build/strandbench render --scene straight:strands=62500,points=17,seed=1 --shadow shadowmap \
      --backend "$backend" --primitive "$primitive" --size 512x512 --repeat "$repeat" --warmup 1 "$@"
  done
done
