#!/usr/bin/env bash
# The papers' temporal claims, measured on both backends: under a light orbit,
#  1. straight hair lit from the side: OSM (16 maps) flickers more than DOM (3 layers);
#  2. the stray scene (occupancy paper, Fig. 5a): DOM (3 layers) flickers more than occupancy.
# Flicker is render --animate's mean over frames and pixels of
# |(T_t - T_{t-1}) - (R_t - R_{t-1})| (README "Error under animation"), in
# visibility (the shadow technique alone) and in the image. Prints one line per
# run, then each claim per backend with "holds" or "does not hold".
#
#   scripts/temporal-claims.sh [SIZE [FRAMES [DEGREES]]]   (defaults 128x128, 8, 30)
# With SB_DOCS_RESULTS set, also writes the rows and claims there as JSON, for the results
# store: scripts/docs-record.sh temporal-claims scripts/temporal-claims.sh
set -euo pipefail
cd "$(dirname "$0")/.."
size=${1:-128x128}
frames=${2:-8}
degrees=${3:-30}
bin=${STRANDBENCH:-build/strandbench}
animate="light-orbit:frames=$frames,degrees=$degrees"
straight=(--scene straight:strands=2000,points=16 --light-direction -1,0,0)
stray=(--scene stray:strands=3000)

# flicker BACKEND SHADOW SCENE-ARGS...: "visibility image" flicker.
flicker() {
  local backend=$1 shadow=$2
  shift 2
  "$bin" render "$@" --shadow "$shadow" --backend "$backend" --size "$size" --repeat 1 \
    --warmup 0 --reference --animate "$animate" --json |
    jq -r '"\(.animation.flicker.visibility) \(.animation.flicker.image)"'
}

json=$(mktemp)
trap 'rm -f "$json"' EXIT
echo "animate $animate, size $size ($bin)"
printf '%-8s %-9s %-26s %14s %14s\n' backend scene shadow "vis flicker" "image flicker"
declare -A vis
for backend in gl vulkan; do
  for run in "straight osm:maps=16,size=256" "straight dom:layers=3,size=256" \
    "stray dom:layers=3,size=256" "stray occupancy:size=256"; do
    read -r scene shadow <<<"$run"
    if [ "$scene" = straight ]; then args=("${straight[@]}"); else args=("${stray[@]}"); fi
    read -r v i < <(flicker "$backend" "$shadow" "${args[@]}")
    vis["$backend $scene ${shadow%%:*}"]=$v
    printf '%-8s %-9s %-26s %14.6f %14.6f\n' "$backend" "$scene" "$shadow" "$v" "$i"
    printf 'row %s %s %s %s %s\n' "$backend" "$scene" "$shadow" "$v" "$i" >>"$json"
  done
done

# claim BACKEND SCENE MORE LESS: "MORE flickers more than LESS" by visibility flicker.
claim() {
  local a=${vis["$1 $2 $3"]} b=${vis["$1 $2 $4"]}
  local verdict
  verdict=$(awk -v a="$a" -v b="$b" 'BEGIN{print (a > b) ? "holds" : "does not hold"}')
  printf '%-8s %-9s %s flickers more than %s: %.6f vs %.6f (ratio %.2f): %s\n' "$1" "$2" "$3" \
    "$4" "$a" "$b" "$(awk -v a="$a" -v b="$b" 'BEGIN{print (b > 0) ? a / b : 0}')" "$verdict"
  printf 'claim %s %s %s %s %s %s %s\n' "$1" "$2" "$3" "$4" "$a" "$b" "${verdict// /_}" >>"$json"
}
echo
for backend in gl vulkan; do
  claim "$backend" straight osm dom
  claim "$backend" stray dom occupancy
done
[ -n "${SB_DOCS_RESULTS:-}" ] || exit 0
python3 - "$json" "$SB_DOCS_RESULTS" "$size" "$animate" <<'PY'
import json, sys
src, out, size, animate = sys.argv[1:]
rows, claims = [], []
for line in open(src):
    kind, *f = line.split()
    if kind == "row":
        rows.append({"backend": f[0], "scene": f[1], "shadow": f[2], "visibility": float(f[3]),
                     "image": float(f[4])})
    else:
        a, b = float(f[4]), float(f[5])
        claims.append({"backend": f[0], "scene": f[1], "more": f[2], "less": f[3], "a": a, "b": b,
                       "ratio": a / b if b > 0 else None, "verdict": f[6].replace("_", " ")})
with open(out, "w") as fh:
    json.dump({"size": size, "animate": animate, "rows": rows, "claims": claims}, fh, indent=1)
    fh.write("\n")
PY
