#!/usr/bin/env bash
# Shadow memory at 512x512 with fp32 maps (memory.shadow_bytes, the device's own
# accounting) beside Sintorn & Assarsson's table. Hair only (no mesh), so only
# the techniques' maps count. Writes JSON to $SB_DOCS_RESULTS (or out/memory-table.json):
# record it with `scripts/docs-record.sh memory-table scripts/memory-table.sh` and
# `build/strandbench docs refresh` renders docs/shadow-techniques.md's memory table.
# Usage: scripts/memory-table.sh [SCENE]
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-straight:strands=200,points=8,head=0}
out=${SB_DOCS_RESULTS:-out/memory-table.json}
mkdir -p "$(dirname "$out")"
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
declare -A shown=()  # techniques with a row
# One JSON line per technique: its render's shadow bytes and counters, and the paper's MB.
row() {
  shown[${1%%:*}]=1
  build/strandbench render --scene "$scene" --shadow "$1" --size 64x64 --json | python3 -c '
import json, sys
r = json.load(sys.stdin)
c = r.get("counters", {})
keep = {k: v for k, v in c.items() if k.startswith(("dsm_", "avsm_"))}
print(json.dumps({"spec": sys.argv[1], "bytes": r["memory"]["shadow_bytes"], "paper": sys.argv[2],
                  "counters": keep}))' "$1" "$2" >>"$tmp"
}
row "occupancy:slices=128,slabs=4,size=512" "10 MB"
row "dom:layers=15,size=512" "18 MB (DOM 16 slices)"
row "dom:layers=31,size=512" "34 MB (DOM 32 slices)"
row "osm:maps=128,size=512,bits=32" "130 MB"
row "osm:maps=256,size=512,bits=32" "258 MB"
row "dc:clusters=4,size=512" "-"
row "shadowmap:size=512" "-"
row "adsm:size=512" "- (TressFX: one depth map)"
row "fom:coefficients=8,size=512" "-"
row "fom:coefficients=16,size=512" "-"
row "msm:moments=4,size=512" "-"
row "msm:moments=8,size=512" "-"
row "dom:layers=3,size=512,spacing=power,filter=pcf6x4" "- (Unreal: 4 layers)"
# Deep shadow maps depend on the hair: the exact technique's light-space lists they are
# built from, plus node slots; the paper's memory is the nodes kept (counters dsm_*).
for eps in 0 0.02 0.1; do row "dsm:epsilon=$eps,size=512" "-"; done
# Adaptive volumetric shadow maps: the paper's memory is the nodes (a count and `nodes`
# (depth, transmittance) pairs per texel, avsm_map_bytes); without fragment-shader
# interlock the curves are built from the exact lists, counted apart (avsm_list_bytes).
for nodes in 4 8 16; do row "avsm:nodes=$nodes,size=512" "-"; done
# Voxelized density: grid^3 uint counters, whatever the map size.
for grid in 64 128 256; do row "voxel:grid=$grid,size=512" "-"; done
# Every other registered shadow technique with a light map (`strandbench list --json`).
while read -r name; do
  [ -n "${shown[$name]:-}" ] || row "$name:size=512" "-"
done < <(build/strandbench list --json | python3 -c '
import json, sys
for t in json.load(sys.stdin)["shadow"]:
    if any(o["name"] == "size" for o in t["options"]): print(t["name"])')
python3 - "$tmp" "$out" "$scene" <<'PY'
import json, sys
tmp, out, scene = sys.argv[1:]
rows = [json.loads(l) for l in open(tmp)]
by = {r["spec"]: r["bytes"] for r in rows}
occ, osm = by["occupancy:slices=128,slabs=4,size=512"], by["osm:maps=128,size=512,bits=32"]
data = {"scene": scene, "rows": rows, "osm128_over_occupancy": osm / occ}
with open(out, "w") as f:
    json.dump(data, f, indent=1)
    f.write("\n")
print("wrote", out)
PY
