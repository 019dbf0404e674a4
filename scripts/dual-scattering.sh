#!/usr/bin/env bash
# Dual scattering's error against rung 3 of the ladder (docs/shading-and-lights.md "Dual
# scattering"): per light placement and shadow technique, the raster Chiang fibre with single
# scattering (`chiang:opacity=fibre`) and with dual scattering (`...,scattering=dual`, its
# strand count from that technique's visibility), both on world-width strands, against the
# path-traced reference of the same fibre (`pbr:mode=path`, rendered once per light and cached).
# Prints the table; with SB_DOCS_RESULTS set, writes the rows there as JSON for the results store:
#   scripts/docs-record.sh dual-scattering scripts/dual-scattering.sh
# Usage: scripts/dual-scattering.sh [SPP]   (default 64; LIGHTS="front behind side" picks the
# placements, SHADOWS="spec ..." the rows.) Needs build/strandbench and ../shared/models.
set -euo pipefail
cd "$(dirname "$0")/.."
spp=${1:-64}
cli=${STRANDBENCH:-build/strandbench}
[ -x "$cli" ] || { echo "dual-scattering.sh: $cli missing: run scripts/setup.sh" >&2; exit 2; }
model=$(cd .. && pwd)/shared/models/straight.hair
[ -f "$model" ] || { echo "dual-scattering.sh: $model missing" >&2; exit 2; }
[[ "$spp" =~ ^[0-9]+$ && "$spp" -ge 8 ]] || {
  echo "dual-scattering.sh: SPP=$spp: must be a whole number >= 8" >&2; exit 2; }
read -ra lights <<< "${LIGHTS:-front side behind}"
read -ra shadows <<< "${SHADOWS:-exact none shadowmap osm:maps=16 dom:layers=3 dc:clusters=4 occupancy}"
declare -A direction=([front]="0,-0.3,-1" [side]="-1,-0.3,0" [behind]="0,-0.3,1")
for l in "${lights[@]}"; do
  [ -n "${direction[$l]:-}" ] || { echo "dual-scattering.sh: light '$l': front, side or behind" >&2; exit 2; }
done
scene="file:path=$model,strands=1000"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export SB_PBR_CACHE="$tmp/cache"
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
t0=$(date +%s)
for l in "${lights[@]}"; do
  for s in "${shadows[@]}"; do
    for scattering in single dual; do
      "$cli" render --scene "$scene" --size 64x64 --backend gl --oit abuffer --primitive world \
        --shadow "$s" --shading "chiang:opacity=fibre,scattering=$scattering" \
        --light-direction "${direction[$l]}" --reference "pbr:mode=path,spp=$spp" \
        --warmup 0 --repeat 1 --out "$tmp/img.png" --json > "$tmp/r.json" 2> "$tmp/err" || {
        cat "$tmp/err" >&2; echo "dual-scattering.sh: $l $s $scattering failed" >&2; exit 1; }
      python3 - "$l" "$s" "$scattering" "$tmp/r.json" >> "$tmp/rows.jsonl" <<'PY'
import json, sys
light, shadow, scattering, path = sys.argv[1:]
r = json.load(open(path))
e = r["error"]["pbr"]
print(json.dumps({"light": light, "shadow": shadow, "scattering": scattering,
                  "rmse": e["rmse"], "clean": e["noise"]["rmse_without_noise"],
                  "noise": e["noise"]["rmse"], "scaled": e["scaled"]["rmse"],
                  "scale": e["scaled"]["scale"], "mean": e["mean"]["image"],
                  "mean_reference": e["mean"]["reference"],
                  "reference": e["reference"]["spec"], "seconds": e["reference"]["wall_ms"] / 1e3}))
PY
    done
  done
done
t1=$(date +%s)
python3 - "$tmp/rows.jsonl" "$scene" "$spp" "$load_before" "$(cut -d' ' -f1-3 /proc/loadavg)" \
  "$((t1 - t0))" "${SB_DOCS_RESULTS:-}" <<'PY'
import json, sys
rows_path, scene, spp, load0, load1, secs, out = sys.argv[1:]
raw = [json.loads(l) for l in open(rows_path)]
lights = []
for r in raw:
    if r["light"] not in lights:
        lights.append(r["light"])
data = {"scene": scene.split("/")[-1], "size": 64, "spp": int(spp), "seconds": int(secs),
        "lights": []}
for l in lights:
    rows = []
    by = {(r["shadow"], r["scattering"]): r for r in raw if r["light"] == l}
    for shadow in dict.fromkeys(r["shadow"] for r in raw if r["light"] == l):
        s, d = by[(shadow, "single")], by[(shadow, "dual")]
        gap = s["mean_reference"] - s["mean"]
        rows.append({"shadow": shadow, "single": s, "dual": d,
                     # the share of single scattering's error (noise removed) dual removes, and
                     # of the brightness single scattering misses that dual adds
                     "error_recovered": 1 - d["clean"] / s["clean"] if s["clean"] > 0 else 0,
                     "light_recovered": (d["mean"] - s["mean"]) / gap if gap != 0 else 0})
    data["lights"].append({"light": l, "reference_mean": rows[0]["single"]["mean_reference"],
                           "noise": rows[0]["single"]["noise"], "rows": rows})
for l in data["lights"]:
    print(f"light {l['light']}: reference mean {l['reference_mean']:.4f}, noise {l['noise']:.4f}")
    print("| shadow | single RMSE (noise removed) | dual RMSE (noise removed) | error recovered |"
          " single / dual / reference mean | light recovered |")
    for r in l["rows"]:
        s, d = r["single"], r["dual"]
        print(f"| {r['shadow']} | {s['rmse']:.4f} ({s['clean']:.4f}) | {d['rmse']:.4f} "
              f"({d['clean']:.4f}) | {r['error_recovered']:+.3f} | {s['mean']:.4f} / "
              f"{d['mean']:.4f} / {s['mean_reference']:.4f} | {r['light_recovered']:+.3f} |")
if out:
    json.dump(data, open(out, "w"), indent=1)
PY
