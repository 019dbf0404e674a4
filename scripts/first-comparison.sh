#!/usr/bin/env bash
# The README's first comparison, and its picture: docs/first-comparison.png (the technique,
# the exact reference and their difference heatmap side by side, made with oiiotool).
# Usage: scripts/first-comparison.sh [OUT.png]   (needs build/strandbench)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-docs/first-comparison.png}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
build/strandbench render --scene curly:strands=2000,points=24 --shadow dom:layers=3 \
  --oit wboit --size 256x256 --reference --out "$tmp/dom.png" --reference-out "$tmp/exact.png" \
  --heatmap "$tmp/diff.png"
build/strandbench compare "$tmp/dom.png" "$tmp/exact.png"
oiiotool "$tmp/dom.png" --ch R,G,B "$tmp/exact.png" --ch R,G,B "$tmp/diff.png" --ch R,G,B \
  --mosaic:pad=4 3x1 \
  -o "$tmp/all.png"
mv "$tmp/all.png" "$out"
echo "wrote $out"
