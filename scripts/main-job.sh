#!/usr/bin/env bash
# The main job on the software renderers (Mesa llvmpipe for GL, lavapipe for
# Vulkan): set up, build, run suites/quick.json (every technique on both
# backends against the exact reference, layer sweeps, scaling, a light-ray
# probe) and write the reports into out/quick (or the folder given):
# results.json, results.csv, report.md and an offline report.html.
# A stopped run continues where it stopped (--resume).
set -euo pipefail
cd "$(dirname "$0")/.."
outdir=${1:-out/quick}
scripts/setup.sh
build/strandbench sweep suites/quick.json --out "$outdir" --resume
