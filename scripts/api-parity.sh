#!/usr/bin/env bash
# Measures how closely GL and Vulkan images agree (PSNR, max abs difference),
# for ribbons and lines, with Vulkan's Bresenham lines and with its default lines.
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-curly:strands=2000,points=32,seed=7}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for prim in ribbons lines; do
  build/strandbench render --scene "$scene" --shadow shadowmap --backend gl --primitive "$prim" --out "$tmp/gl.exr" >/dev/null
  for lines in bresenham default; do
    SB_VULKAN_LINES=$lines build/strandbench render --scene "$scene" --shadow shadowmap --backend vulkan \
      --primitive "$prim" --out "$tmp/vk.exr" >/dev/null
    result=$(build/strandbench compare "$tmp/gl.exr" "$tmp/vk.exr" | tr -d ' \n')
    psnr=$(sed -E 's/.*"psnr":([^,}]*).*/\1/' <<<"$result")
    maxabs=$(sed -E 's/.*"max_abs":([^,}]*).*/\1/' <<<"$result")
    over=$(sed -E 's/.*"fraction_over":([^,}]*).*/\1/' <<<"$result")
    echo "$prim (vulkan lines: $lines): PSNR $psnr dB, max abs $maxabs, fraction of pixels over 1/255: $over"
  done
done
