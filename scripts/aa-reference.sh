#!/usr/bin/env bash
# The anti-aliased exact reference measured (docs/ground-truth.md "The anti-aliased
# reference"): one scene rendered with `--reference --reference aa:samples=S` for S = 1, 2, 4,
# 8 on GL; per S its cost (wall time, frame time, resources, host memory), the error of the
# technique and of the aliased reference against it, and its own convergence (the error
# between S and 2S); and the technique with --msaa 4 against both references. Writes the data
# as JSON to $SB_DOCS_RESULTS (or the file given): record it into the results store with
#   scripts/docs-record.sh aa-reference scripts/aa-reference.sh
# and `build/strandbench docs refresh` renders docs/aa-reference-measured.md's and
# docs/ground-truth.md's blocks from it (docs/results/aa-reference/blocks.json).
# Usage: scripts/aa-reference.sh [OUT.json]     Needs build/strandbench (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-${SB_DOCS_RESULTS:-out/aa-reference.json}}
mkdir -p "$(dirname "$out")"
cli=build/strandbench
[ -x "$cli" ] || { echo "aa-reference.sh: $cli missing: run scripts/setup.sh" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run=(render --scene curly:strands=500,points=16,seed=2 --shadow dom:layers=3,size=256
     --oit wboit --size 128x128 --warmup 0 --backend gl --reference)
for s in 1 2 4 8; do
  "$cli" "${run[@]}" --reference "aa:samples=$s" --json --out "$tmp/image.png" \
    --reference-out "$tmp/ref-$s.exr" > "$tmp/s$s.json"
done
# The same technique anti-aliased (--msaa 4, what the device has beside 1) against both.
"$cli" "${run[@]}" --reference aa:samples=8 --msaa 4 --json > "$tmp/msaa4.json"
# The convergence: the aa reference at S against the one at 2S, as float images (EXR: no
# 8-bit rounding; FLIP is then HDR-FLIP).
for s in 1 2 4; do
  "$cli" compare "$tmp/ref-$s.aa.exr" "$tmp/ref-$((s * 2)).aa.exr" > "$tmp/c$s.json"
done
"$cli" compare "$tmp/ref-1.exr" "$tmp/ref-8.aa.exr" > "$tmp/aliased.json"
python3 - "$tmp" "$out" "${run[*]}" <<'PY'
import json, os, sys
tmp, out, run = sys.argv[1:]
r = {s: json.load(open(os.path.join(tmp, f"s{s}.json"))) for s in (1, 2, 4, 8)}
c = {s: json.load(open(os.path.join(tmp, f"c{s}.json"))) for s in (1, 2, 4)}
aliased = json.load(open(os.path.join(tmp, "aliased.json")))
msaa = json.load(open(os.path.join(tmp, "msaa4.json")))
rows = []
for s in (1, 2, 4, 8):
    a = r[s]["error"]["aa"]
    ref = a["reference"]
    rows.append({"S": s, "samples": f"{ref['size'][0]}x{ref['size'][1]}",
                 "light_map": ref["light_map_size"], "wall_ms": ref["wall_ms"],
                 "frame_ms": ref["frame_ms"], "bytes": ref["bytes"], "host_bytes": ref["host_bytes"],
                 "rmse": a["rmse"], "flip": a["flip"]["mean"],
                 "next_rmse": c[s]["rmse"] if s in c else None,
                 "next_flip": c[s]["flip"]["mean"] if s in c else None})
techniques = []
for name, j in (("`--msaa 1`", r[8]), ("`--msaa 4`", msaa)):
    e = j["error"]
    techniques.append({"shadow": j["shadow"], "oit": j["oit"], "msaa": name,
                       "image_rmse": e["image"]["rmse"], "image_flip": e["image"]["flip"]["mean"],
                       "aa_rmse": e["aa"]["rmse"], "aa_flip": e["aa"]["flip"]["mean"]})
img = r[1]["error"]["image"]
data = {"render": "strandbench " + run, "rows": rows, "techniques": techniques,
        "image": {"rmse": img["rmse"], "flip": img["flip"]["mean"]},
        "aliased_vs_aa8": {"rmse": aliased["rmse"], "flip": aliased["flip"]["mean"]}}
with open(out, "w") as f:
    json.dump(data, f, indent=1)
    f.write("\n")
print("wrote", out)
PY
