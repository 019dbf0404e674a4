#!/usr/bin/env bash
# The main job on the software renderers (Mesa llvmpipe for GL, lavapipe for
# Vulkan): set up, build, render the default scene on both backends, writing
# images and JSON reports (with the error against the reference) into out/
# (or the folder given).
set -euo pipefail
cd "$(dirname "$0")/.."
outdir=${1:-out}
scripts/setup.sh
mkdir -p "$outdir"
for backend in gl vulkan; do
  for shadow in none shadowmap osm dom dc occupancy exact; do
    name="default.$backend.$shadow"
    # JSON goes to a temporary file first: a failed run leaves no half-written report.
    build/strandbench render --backend "$backend" --shadow "$shadow" --repeat 3 --reference \
      --out "$outdir/$name.png" --json > "$outdir/$name.json.tmp"
    mv "$outdir/$name.json.tmp" "$outdir/$name.json"
    echo "wrote $outdir/$name.png and $outdir/$name.json"
  done
done
