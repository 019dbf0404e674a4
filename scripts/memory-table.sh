#!/usr/bin/env bash
# Shadow memory at 512x512 with fp32 maps (memory.shadow_bytes, the device's own
# accounting) beside Sintorn & Assarsson's table. Hair only (no mesh), so only
# the techniques' maps count.
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-straight:strands=200,points=8,head=0}
bytes() {
  build/strandbench render --scene "$scene" --shadow "$1" --size 64x64 --json |
    sed -n 's/.*"shadow_bytes": \([0-9]*\).*/\1/p'
}
printf '%-34s %14s %10s %s\n' technique bytes MiB "paper (MB)"
declare -A shown=()  # techniques with a row
row() {
  local b
  shown[${1%%:*}]=1
  b=$(bytes "$1")
  printf '%-34s %14s %10.2f %s\n' "$1" "$b" "$(awk -v b="$b" 'BEGIN{print b/1048576}')" "$2"
}
row "occupancy:slices=128,slabs=4,size=512" "10"
row "dom:layers=15,size=512" "18 (DOM 16 slices)"
row "dom:layers=31,size=512" "34 (DOM 32 slices)"
row "osm:maps=128,size=512,bits=32" "130"
row "osm:maps=256,size=512,bits=32" "258"
row "dc:clusters=4,size=512" "-"
row "shadowmap:size=512" "-"
row "adsm:size=512" "- (TressFX: one depth map)"
row "fom:coefficients=8,size=512" "-"
row "fom:coefficients=16,size=512" "-"
row "msm:moments=4,size=512" "-"
row "msm:moments=8,size=512" "-"
row "dom:layers=3,size=512,spacing=power,filter=pcf6x4" "- (Unreal: 4 layers)"
# Deep shadow maps depend on the hair: the exact technique's light-space lists
# they are built from, plus node slots; the paper's memory is the nodes kept.
for eps in 0 0.02 0.1; do
  spec="dsm:epsilon=$eps,size=512"
  row "$spec" "-"
  build/strandbench render --scene "$scene" --shadow "$spec" --size 64x64 --json | python3 -c '
import json, sys
c = json.load(sys.stdin)["counters"]
print("  %s nodes kept per texel with hair min/mean/max %d/%.2f/%d: %d bytes (%.2f MiB) of %d in slots"
      % (sys.argv[1], c["dsm_nodes_min"], c["dsm_nodes_mean"], c["dsm_nodes_max"],
         c["dsm_kept_bytes"], c["dsm_kept_bytes"] / 1048576, c["dsm_slot_bytes"]))' "$spec"
done
# Adaptive volumetric shadow maps: the paper's memory is the nodes (a count and
# `nodes` (depth, transmittance) pairs per texel); without fragment-shader
# interlock the curves are built from the exact lists, counted apart.
for nodes in 4 8 16; do
  spec="avsm:nodes=$nodes,size=512"
  row "$spec" "-"
  build/strandbench render --scene "$scene" --shadow "$spec" --size 64x64 --json | python3 -c '
import json, sys
c = json.load(sys.stdin)["counters"]
print("  %s curves (the paper'"'"'s memory) %d bytes (%.2f MiB), the emulation'"'"'s lists %d bytes (%.2f MiB)"
      % (sys.argv[1], c["avsm_map_bytes"], c["avsm_map_bytes"] / 1048576, c["avsm_list_bytes"],
         c["avsm_list_bytes"] / 1048576))' "$spec"
done
# Voxelized density: grid^3 uint counters, whatever the map size.
for grid in 64 128 256; do row "voxel:grid=$grid,size=512" "-"; done
# Every other registered shadow technique with a light map (`strandbench list --json`).
while read -r name; do
  [ -n "${shown[$name]:-}" ] || row "$name:size=512" "-"
done < <(build/strandbench list --json | python3 -c '
import json, sys
for t in json.load(sys.stdin)["shadow"]:
    if any(o["name"] == "size" for o in t["options"]): print(t["name"])')
occ=$(bytes "occupancy:slices=128,slabs=4,size=512")
osm=$(bytes "osm:maps=128,size=512,bits=32")
echo "OSM(128) / occupancy = $(awk -v a="$osm" -v b="$occ" 'BEGIN{printf "%.1f", a/b}') (paper: 13)"
