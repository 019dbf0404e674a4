#!/usr/bin/env bash
# The quick, paper and ray-tracing suites on a GPU machine, GL through EGL and Vulkan with GPU
# timestamps, into one folder: OUT/<suite>/ (results.json, report.md, report.html per suite)
# and OUT/summary.md (date, GPU, driver, devices and timing method per backend, time per suite).
# Usage: scripts/gpu-suite.sh [--out DIR] [--small] [--suites "quick paper-dom ..."]
#   --out DIR   the folder (default out/gpu-<date>); a stopped run continues (--resume)
#   --small     the quick suite only (minutes on CPU drivers; proves the script works)
#   --suites S  the suites to run (names in suites/, default: quick, every paper-* and
#               ray-tracing, geometry: the axes geometry=cpu|compute|mesh, lod=, lod_pixels=
#               and instances=; its mesh groups run where Vulkan has VK_EXT_mesh_shader)
# On a machine without an NVIDIA GPU it runs on whatever devices there are (Mesa's llvmpipe
# and lavapipe here) and says so in the summary. Timing: GPU timestamps on both APIs, no
# finish between passes (SB_VULKAN_GPU_TIMING=1, SB_GL_GPU_TIMING=1: Vulkan timestamps, GL
# glQueryCounter; forced also on a CPU device, where they are not trustworthy: docs/measured.md).
# Exit 0, or the first failing sweep's status. Needs build/strandbench (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
out="out/gpu-$(date -u +%Y%m%d)"
suites="quick paper-dom paper-osm paper-occupancy paper-thesis ray-tracing geometry"
while (($#)); do
  case "$1" in
    --out) out=${2:?--out needs a folder}; shift ;;
    --small) suites="quick" ;;
    --suites) suites=${2:?--suites needs names}; shift ;;
    -h | --help) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "gpu-suite.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
cli=build/strandbench
[ -x "$cli" ] || { echo "gpu-suite.sh: $cli missing: run scripts/setup.sh" >&2; exit 2; }
for s in $suites; do
  [ -f "suites/$s.json" ] || { echo "gpu-suite.sh: suites/$s.json: no such suite" >&2; exit 2; }
done
mkdir -p "$out"
export SB_VULKAN_GPU_TIMING=1 SB_GL_GPU_TIMING=1
if command -v nvidia-smi >/dev/null && nvidia-smi -L >/dev/null 2>&1; then
  gpu=$(nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader | head -n 1)
else
  gpu="none: no NVIDIA GPU visible (nvidia-smi); ran on the CPU drivers"
fi
{
  echo "# GPU suite run"
  echo
  echo "- date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "- commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "- GPU (nvidia-smi: name, driver, memory): $gpu"
  echo "- timing forced to GPU timestamps on both APIs (SB_VULKAN_GPU_TIMING=1, SB_GL_GPU_TIMING=1)"
  echo
  echo "| suite | cases | failed | seconds | devices (backend: device, driver, timing) |"
  echo "|---|---|---|---|---|"
} >"$out/summary.md"
status=0
for s in $suites; do
  t0=$(date +%s)
  echo "== $s"
  set +e
  "$cli" sweep "suites/$s.json" --out "$out/$s" --resume
  rc=$?
  set -e
  ((rc == 0)) || { echo "gpu-suite.sh: sweep $s exited $rc" >&2; ((status)) || status=$rc; }
  secs=$(($(date +%s) - t0))
  cases=$(ls "$out/$s/cases" 2>/dev/null | wc -l)
  failed=$( (grep -l '"failed"' "$out/$s"/cases/*.json 2>/dev/null || true) | wc -l)
  # The devices block of results.json's context: one "backend ... timing" group per device.
  devices=$(tr -d '\n' <"$out/$s/results.json" 2>/dev/null |
    grep -o '"devices": *\[[^]]*\]' | grep -o '{[^}]*}' |
    sed -E 's/.*"backend": *"([^"]*)".*"device": *"([^"]*)".*"driver": *"([^"]*)".*"timing": *"([^"]*)".*/\1: \2, \3, \4/' |
    paste -sd ';' -) || true
  echo "| $s | $cases | $failed | $secs | ${devices:-?} |" >>"$out/summary.md"
done
echo
cat "$out/summary.md"
echo "gpu-suite.sh: wrote $out (one folder per suite, summary.md)"
exit "$status"
