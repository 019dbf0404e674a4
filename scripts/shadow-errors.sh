#!/usr/bin/env bash
# Visibility RMSE against the exact visibility and shadow time for every
# shadow technique on the straight, curly and stray scenes, on both backends:
# the README's "Shadow techniques: error against time" table.
#   scripts/shadow-errors.sh [SIZE] [REPEAT]    (defaults 256 and 5; STRANDBENCH=path
#   runs another binary; SHADOWS="spec spec ..." measures only those rows)
# Shadow time: the median over the timed frames of the technique's own passes
# (names starting "<technique>.", and "exact." for dsm and avsm, which build
# their curves from the exact technique's light-space lists), in ms; avsm's
# is marked "timing emulated" (its resolve stands in for fragment-shader
# interlock: render JSON "timing_emulated"). Image SIZExSIZE, light maps at
# the techniques' default size.
set -euo pipefail
cd "$(dirname "$0")/.."
size=${1:-256}
repeat=${2:-5}
scenes=("straight:strands=4000,points=16,head=0" "curly:strands=1500,points=48,head=0"
        "stray:strands=3000,points=16")
bin=${STRANDBENCH:-build/strandbench}
# Every registered shadow technique (`strandbench list --json`) but none, at its
# defaults, or as the variants named here.
declare -A variants=(
  [osm]="osm:maps=16 osm:maps=16,filter=pcf6x4" [dc]="dc:clusters=4"
  [dom]="dom:layers=3 dom:layers=3,spacing=power,filter=pcf6x4"
  [dsm]="dsm:epsilon=0,max_nodes=65536 dsm:epsilon=0.02 dsm:epsilon=0.1"
  [fom]="fom:coefficients=4 fom:coefficients=16"
  [msm]="msm:moments=4 msm:moments=8 msm:moments=8,kind=trig"
  [avsm]="avsm:nodes=4 avsm:nodes=8 avsm:nodes=16" [voxel]="voxel:grid=64,steps=64 voxel")
shadows=()
while read -r name; do
  [ "$name" = none ] && continue
  # shellcheck disable=SC2206
  shadows+=(${variants[$name]:-$name})
done < <("$bin" list --json |
  python3 -c 'import json, sys; print("\n".join(t["name"] for t in json.load(sys.stdin)["shadow"]))')
if [ -n "${SHADOWS:-}" ]; then read -ra shadows <<< "$SHADOWS"; fi
row() {  # scene backend shadow
  "$bin" render --scene "$1" --backend "$2" --shadow "$3" --size "${size}x${size}" \
    --repeat "$repeat" --warmup 1 --reference --no-image --json |
    python3 -c '
import json, sys, statistics
r = json.load(sys.stdin)
tech = r["shadow"].split(":")[0]
prefixes = (tech + ".",) + (("exact.",) if tech in ("dsm", "avsm") else ())
ms = sum(p["ms"]["median"] for p in r["passes"] if p["name"].startswith(prefixes))
rmse = r["error"]["visibility"]["rmse"]
note = " (timing emulated)" if r.get("timing_emulated") else ""
print("| %s | %s | %s | %.4f | %.2f%s |" % (sys.argv[1].split(":")[0], sys.argv[2], r["shadow"], rmse, ms, note))
' "$1" "$2"
}
echo "| scene | backend | shadow | visibility RMSE | shadow ms |"
echo "|---|---|---|---:|---:|"
for scene in "${scenes[@]}"; do
  for backend in gl vulkan; do
    for shadow in "${shadows[@]}"; do row "$scene" "$backend" "$shadow"; done
  done
done
