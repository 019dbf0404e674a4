#!/usr/bin/env bash
# Measures ray-traced transparency (--oit rt: on GL the software tier;
# scripts/rt-oit-tiers.sh compares the tiers) for
# docs/transparency-techniques.md ("Ray-traced transparency"): its image error
# against the exact reference (pixel centres: what the rasterizer covers) and
# against the anti-aliased reference (aa:samples=4: strands at their true
# width), beside peeling (the exact reference itself) and the approximate
# techniques, all under exact shadows; its frame time, the eye BVH's build
# time, size and memory, and the hits. Writes the rows as JSON to $SB_DOCS_RESULTS
# (or out/rt-oit.json): `scripts/docs-record.sh rt-oit scripts/rt-oit.sh` keeps them in the
# results store and `strandbench docs refresh` renders docs/rt-oit-measured.md.
# Usage: scripts/rt-oit.sh [backend]   (default gl)
set -euo pipefail
cd "$(dirname "$0")/.."
backend=${1:-gl}
out=${SB_DOCS_RESULTS:-out/rt-oit.json}
mkdir -p "$(dirname "$out")"
sb=build/strandbench
[ -x "$sb" ] || { echo "rt-oit.sh: $sb missing: run scripts/setup.sh" >&2; exit 2; }
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
row() {  # scene, oit, size, extra render args: one JSON line in $tmp
  local scene=$1 oit=$2 size=$3
  shift 3
  echo "$sb render --scene $scene --shadow exact --oit $oit --size $size --backend $backend --warmup 1 --repeat 3 --reference --reference aa:samples=4 --json $*" >&2
  "$sb" render --scene "$scene" --shadow exact --oit "$oit" --size "$size" --backend "$backend" \
    --warmup 1 --repeat 3 --reference --reference aa:samples=4 --json "$@" |
    python3 -c '
import json, sys
j = json.load(sys.stdin)
e, c = j["error"], j.get("counters", {})
print(json.dumps({"scene": sys.argv[1], "args": sys.argv[2], "oit": sys.argv[3],
                  "device": str(j["device"]), "exact_rmse": e["image"]["rmse"],
                  "exact_flip": e["image"]["flip"]["mean"], "aa_rmse": e["aa"]["rmse"],
                  "aa_flip": e["aa"]["flip"]["mean"], "frame_ms": j["frame_ms"]["median"],
                  "bytes": j["memory"]["oit_bytes"], "bvh_nodes": c.get("rt.oit_bvh_nodes"),
                  "bvh_depth": c.get("rt.oit_bvh_depth"), "bvh_build_ms": c.get("rt.oit_bvh_build_ms"),
                  "hits": c.get("rt.oit_hits")}))' "$scene" "$*" "$oit" >>"$tmp"
}
for oit in rt rt:k=8 rt:k=1 peel abuffer kbuffer mboit peel:layers=4; do
  row "stray:alpha=0.4" "$oit" 128x128
done
for oit in rt peel kbuffer; do
  row "curly:strands=300,seed=3,alpha=0.4" "$oit" 128x128
done
for oit in rt peel; do
  row "curly:strands=300,seed=3,alpha=0.4" "$oit" 128x128 --primitive ribbons --ribbon-width 3
done
python3 - "$tmp" "$out" "$backend" <<'PY'
import json, sys
src, out, backend = sys.argv[1:]
rows = [json.loads(l) for l in open(src)]
with open(out, "w") as f:
    json.dump({"backend": backend, "device": rows[0]["device"] if rows else None, "rows": rows}, f,
              indent=1)
    f.write("\n")
PY
echo "rt-oit.sh: wrote $out" >&2
