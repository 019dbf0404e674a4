#!/usr/bin/env bash
# The compute strand rasterizer measured against the hardware-rasterized approximate
# transparency techniques (docs/transparency-techniques.md, "Compute strand rasterizer"):
# sweeps suites/compute-raster-aa.json (error against the aliased and the anti-aliased exact
# reference, frame time with its 95% interval, memory) into out/compute-raster-aa and writes
# its numbers as JSON to $SB_DOCS_RESULTS (or out/compute-raster.json), with a verdict per
# scene and backend: is compute_raster's error against the anti-aliased reference below every
# approximate hardware-rasterized technique's? `scripts/docs-record.sh compute-raster
# scripts/compute-raster.sh`, then `build/strandbench docs refresh` renders
# docs/compute-raster-measured.md.
# Usage: scripts/compute-raster.sh     Needs build/strandbench (scripts/setup.sh) and
# ../shared/models (the groom group; without it that group's cases fail and are listed).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${SB_DOCS_RESULTS:-out/compute-raster.json}
mkdir -p "$(dirname "$out")"
cli=build/strandbench
[ -x "$cli" ] || { echo "compute-raster.sh: $cli missing: run scripts/setup.sh" >&2; exit 2; }
sweep_dir=out/compute-raster-aa
rm -rf "$sweep_dir"  # a new measurement, not a resumed one
"$cli" sweep suites/compute-raster-aa.json --out "$sweep_dir" || true  # failed cases are listed
python3 - "$sweep_dir/results.json" "$out" <<'PY'
import json, sys
results_path, out = sys.argv[1:]
d = json.load(open(results_path))
# The hardware-rasterized approximate techniques compute_raster is judged against.
approx = ("kbuffer", "mlab", "mboit", "wboit", "peel:layers=4")
def oit(r):
    return r["case"]["params"]["oit"]
def err(r, ref):
    e = r.get("error", {}).get(ref)
    return {"rmse": e["rmse"], "flip": e["flip"]["mean"]} if e else None
groups = []
for g in d["groups"]:
    rs = [r for r in d["results"] if r["case"].get("group") == g["name"] and "failed" not in r]
    group = {"name": g["name"], "description": g.get("description", ""), "backends": []}
    groups.append(group)
    if not rs:
        group["empty"] = True
        continue
    first = rs[0]
    group["scene"] = {"spec": first["scene"]["spec"], "strands": first["scene"]["strands"],
                      "segments": first["scene"]["segments"],
                      "size": f"{first['size'][0]}x{first['size'][1]}",
                      "aa": first["error"]["aa"]["reference"]["spec"] if err(first, "aa") else "-"}
    for backend in sorted({r["backend"] for r in rs}):
        rows = []
        for r in (r for r in rs if r["backend"] == backend):
            ci = r.get("measurement", {}).get("median_ci95_ms")
            row = {"oit": oit(r), "ms": r["frame_ms"]["median"], "bytes": r["memory"]["total_bytes"]}
            if ci:
                row["ci"] = {"lo": ci[0], "hi": ci[1]}
            for ref in ("image", "aa"):
                if err(r, ref):
                    row[ref] = err(r, ref)
            rows.append(row)
        b = {"backend": backend, "rows": rows}
        cr = next((r for r in rows if r["oit"] == "compute_raster" and "aa" in r), None)
        others = [r for r in rows if r["oit"] in approx and "aa" in r]
        if cr and others:
            better = [r["oit"] for r in others if r["aa"]["rmse"] < cr["aa"]["rmse"]]
            b["verdict"] = {"rmse": cr["aa"]["rmse"],
                            "text": "below every approximate technique's" if not better else
                            "not below: " + ", ".join(f"`{o}`" for o in better) + " are lower"}
        group["backends"].append(b)
data = {"devices": [{"backend": x["backend"], "device": x["device"], "driver": x["driver"]}
                    for x in d["context"].get("devices", [])],
        "groups": groups,
        "failed": [{"id": r["case"]["id"], "reason": r["failed"]["reason"]}
                   for r in d["results"] if "failed" in r]}
with open(out, "w") as f:
    json.dump(data, f, indent=1)
    f.write("\n")
print("wrote", out)
PY
