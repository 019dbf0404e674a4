#!/usr/bin/env bash
# The error ladder measured (docs/physics-reference.md "The ladder"): suites/physics.json run
# once per reference seed (SEEDS, default 4) with one cache folder; each run's rung-2
# reference (pbr:mode=single, SPP samples per pixel, default 256) is an independent render, so
# the spread of a difference between two techniques' rung-2 errors over the seeds gives its
# 95% interval (Student's t). Then once more against rung 3 (pbr:mode=path, PATH_SPP samples,
# default 512, the same fibre with multiple scattering). SHADINGS: the shading specs (default
# "chiang:opacity=fibre chiang:opacity=fibre,scattering=dual"); a spec with scattering=dual
# gives the dual-scattering columns of the table of the same spec without it, the others a
# table each. Per light placement, shading and shadow technique: the rung-1 error (against the
# rasterized exact reference), the rung-2 error (raw, reference noise removed, at the best
# exposure scale), the rung-3 error of single and of dual scattering, the order of adjacent
# techniques against rung 2 with its interval or "undecided", and the rank correlation of the
# rung-1 and rung-2 orders. Writes them as JSON to $SB_DOCS_RESULTS (the results store:
#   scripts/docs-record.sh physics-ladder scripts/physics-reference.sh
# then build/strandbench docs refresh renders docs/physics-measured.md) and prints a summary.
# Usage: scripts/physics-reference.sh   Needs build/strandbench and ../shared/models.
set -euo pipefail
cd "$(dirname "$0")/.."
seeds=${SEEDS:-4}
spp=${SPP:-256}
pathspp=${PATH_SPP:-512}
shadings=${SHADINGS:-chiang:opacity=fibre chiang:opacity=fibre,scattering=dual}
cli=build/strandbench
[ -x "$cli" ] || { echo "physics-reference.sh: $cli missing: run scripts/setup.sh" >&2; exit 2; }
[ -f ../shared/models/straight.hair ] || {
  echo "physics-reference.sh: ../shared/models/straight.hair missing" >&2; exit 2; }
[[ "$seeds" =~ ^[0-9]+$ && "$seeds" -ge 2 && "$seeds" -le 10 ]] || {
  echo "physics-reference.sh: SEEDS=$seeds: must be 2..10" >&2; exit 2; }
[[ "$spp" =~ ^[0-9]+$ && "$spp" -ge 8 ]] || {
  echo "physics-reference.sh: SPP=$spp: must be a whole number >= 8" >&2; exit 2; }
[[ "$pathspp" =~ ^[0-9]+$ && "$pathspp" -ge 8 ]] || {
  echo "physics-reference.sh: PATH_SPP=$pathspp: must be a whole number >= 8" >&2; exit 2; }
[ -n "${shadings// /}" ] || { echo "physics-reference.sh: SHADINGS is empty" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export SB_PBR_CACHE="$tmp/cache"
t0=$(date +%s)
# Runs 1..SEEDS: rung 2 with that seed; run "path": rung 3.
for k in $(seq 1 "$seeds") path; do
  # The suite with this run's reference and shadings, its model path made absolute (the copy
  # is elsewhere).
  python3 - "$spp" "$pathspp" "$k" "$shadings" "$tmp/suite$k.json" <<'PY'
import json, os, sys
spp, pathspp, run, shadings, path = sys.argv[1:]
s = json.load(open("suites/physics.json"))
d = s["defaults"]
d["scene"] = d["scene"].replace("../shared", os.path.abspath("../shared"))
d["reference"] = ["exact", f"pbr:mode=path,spp={pathspp},seed=1" if run == "path"
                  else f"pbr:mode=single,spp={spp},seed={run}"]
d.pop("shading", None)
for g in s["groups"]:
    g["axes"]["shading"] = shadings.split()
json.dump(s, open(path, "w"), indent=1)
PY
  if ! "$cli" sweep "$tmp/suite$k.json" --out "$tmp/run$k" > "$tmp/run$k.log" 2>&1; then
    tail -20 "$tmp/run$k.log" >&2
    echo "physics-reference.sh: the sweep of run $k failed" >&2
    exit 1
  fi
done
# The two tracers on a sparse groom (SPARSE strands, default 20, that barely overlap): with
# nothing between fibres to transport light, single scattering and the path tracer must agree
# (the check that rung 3 lights a fibre as rung 2 does; the dense groom's difference is then
# the light carried between fibres). One render per light and reference mode.
sparse=${SPARSE:-20}
[[ "$sparse" =~ ^[0-9]+$ && "$sparse" -ge 1 ]] || {
  echo "physics-reference.sh: SPARSE=$sparse: must be a whole number >= 1" >&2; exit 2; }
model=$(cd .. && pwd)/shared/models/straight.hair
for d in "0,-0.3,-1" "-1,-0.3,0" "0,-0.3,1"; do
  for ref in "pbr:mode=single,spp=$spp,seed=1" "pbr:mode=path,spp=$pathspp,seed=1"; do
    "$cli" render --scene "file:path=$model,strands=$sparse" --size 64x64 --backend gl \
      --oit abuffer --primitive world --shadow exact --shading chiang:opacity=fibre \
      --light-direction "$d" --reference "$ref" --warmup 0 --repeat 1 --out "$tmp/sparse.png" \
      --json > "$tmp/sparse.json" 2> "$tmp/sparse.err" || {
      cat "$tmp/sparse.err" >&2; echo "physics-reference.sh: the sparse render failed" >&2; exit 1; }
    python3 -c 'import json, sys; r = json.load(open(sys.argv[1])); print(json.dumps(
      {"light_direction": sys.argv[2], "mode": sys.argv[3], "sparse": int(sys.argv[4]),
       "mean": r["error"]["pbr"]["mean"]["reference"], "noise": r["error"]["pbr"]["noise"]["rmse"],
       "image": r["error"]["pbr"]["mean"]["image"]}))' \
      "$tmp/sparse.json" "$d" "${ref%%,*}" "$sparse" >> "$tmp/sparse.jsonl"
  done
done
t1=$(date +%s)
python3 - "$tmp" "${SB_DOCS_RESULTS:-}" "$seeds" "$spp" "$pathspp" "$((t1 - t0))" <<'PY'
import json, math, os, sys
tmp, out, seeds, spp, pathspp, secs = sys.argv[1:]
seeds = int(seeds)
# Student's t, two-sided 95%, by degrees of freedom.
T95 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262}
def load(name):
    return json.load(open(os.path.join(tmp, f"run{name}", "results.json")))["results"]
runs = [load(k) for k in range(1, seeds + 1)]
path = load("path")
placement = {"0,-0.3,-1": "front", "-1,-0.3,0": "side", "0,-0.3,1": "behind"}
def params(r):
    return r["case"]["params"]
def light(r):
    v = params(r)["light_direction"]
    key = ",".join(f"{x:g}" for x in v) if isinstance(v, list) else str(v)
    return placement.get(key, key)
def key(r):
    return (light(r), params(r)["shading"], params(r)["shadow"])
def is_dual(shading):
    return "scattering=dual" in shading
def base_of(shading):
    return ",".join(p for p in shading.split(",") if p != "scattering=dual").rstrip(":")
cases = {}  # (light, shading, shadow) -> per seed result
for run in runs:
    for r in run:
        cases.setdefault(key(r), []).append(r)
rung3 = {key(r): r for r in path}
lights = [p for p in ["front", "side", "behind"] if any(k[0] == p for k in cases)]
shadings, shadows = [], []
for r in runs[0]:
    if params(r)["shading"] not in shadings:
        shadings.append(params(r)["shading"])
    if params(r)["shadow"] not in shadows:
        shadows.append(params(r)["shadow"])
def mean(v):
    return sum(v) / len(v)
def sd(v):
    m = mean(v)
    return math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1))
def ranks(v):
    order = sorted(range(len(v)), key=lambda i: v[i])
    r = [0.0] * len(v)
    i = 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and v[order[j + 1]] == v[order[i]]:
            j += 1
        for k in range(i, j + 1):
            r[order[k]] = (i + j) / 2 + 1
        i = j + 1
    return r
def spearman(a, b):
    ra, rb = ranks(a), ranks(b)
    ma, mb = mean(ra), mean(rb)
    num = sum((x - ma) * (y - mb) for x, y in zip(ra, rb))
    den = math.sqrt(sum((x - ma) ** 2 for x in ra) * sum((y - mb) ** 2 for y in rb))
    return num / den if den else None
def against3(k):
    """A case's error against rung 3: raw, noise removed, at the best scale; its image mean."""
    if k not in rung3:
        return None
    e = rung3[k]["error"]["pbr"]
    return {"rmse": e["rmse"], "clean": e["noise"]["rmse_without_noise"],
            "scaled": e["scaled"]["rmse"], "scale": e["scaled"]["scale"],
            "mean": e["mean"]["image"], "mean_reference": e["mean"]["reference"],
            "noise": e["noise"]["rmse"]}
first = runs[0][0]["error"]["pbr"]
ref = first["reference"]
p3 = path[0]["error"]["pbr"]["reference"]["pbr"]
data = {
    "scene": runs[0][0]["scene"]["spec"].replace(os.path.abspath("../shared"), "../shared"),
    "size": f"{ref['size'][0]}x{ref['size'][1]}",
    "primitive": params(runs[0][0]).get("primitive", "world"),
    "seeds": seeds, "spp": int(spp), "path_spp": int(pathspp), "path_samples": p3["spp"],
    "thickness_source": ref["pbr"]["thickness_source"], "thickness": ref["pbr"]["thickness"],
    "shadow_rays": ref["pbr"]["shadow_rays"], "tracer_ambient": ref["pbr"]["ambient"]["tracer"],
    "raster_ambient": ref["pbr"]["ambient"]["raster"],
    "shadings": " ".join(shadings), "seconds": int(secs), "tables": [], "summary": [],
    "consistency": [],
}
for l in lights:
    for sh in [s for s in shadings if not is_dual(s)]:
        dual = next((d for d in shadings if is_dual(d) and base_of(d) == sh), None)
        rows = []
        for s in shadows:
            rs = cases.get((l, sh, s), [])
            if len(rs) != seeds:
                continue
            e2 = [r["error"]["pbr"] for r in rs]
            row = {
                "shadow": s,
                "r1": rs[0]["error"]["image"]["rmse"],
                "r2_seeds": [e["rmse"] for e in e2],
                "clean": mean([e["noise"]["rmse_without_noise"] for e in e2]),
                "scaled": mean([e["scaled"]["rmse"] for e in e2]),
                "scale": mean([e["scaled"]["scale"] for e in e2]),
                "noise": mean([e["noise"]["rmse"] for e in e2]),
                "mean_image": e2[0]["mean"]["image"],
                "mean_reference": mean([e["mean"]["reference"] for e in e2]),
                "rung3": against3((l, sh, s)),
            }
            row["r2"] = mean(row["r2_seeds"])
            if dual:
                d3 = against3((l, dual, s))
                if d3:
                    d3["recovered"] = (1 - d3["clean"] / row["rung3"]["clean"]
                                       if row["rung3"] and row["rung3"]["clean"] > 0 else None)
                    row["dual"] = d3
            rows.append(row)
        if not rows:
            continue
        rows.sort(key=lambda r: r["r2"])
        t = T95[seeds - 1]
        decided = quarter_failed = 0
        smallest = None
        for i, r in enumerate(rows):
            r["r2_half"] = t * sd(r["r2_seeds"]) / math.sqrt(seeds)
            r["versus"] = ""
            if i == 0:
                continue
            d = [a - b for a, b in zip(r["r2_seeds"], rows[i - 1]["r2_seeds"])]
            dm, se = mean(d), sd(d) / math.sqrt(seeds)
            dh = t * se
            if dm - dh <= 0 <= dm + dh:
                r["versus"] = f"undecided ({dm:+.5f} +- {dh:.5f}: the interval holds 0)"
            elif se > abs(dm) / 4:
                r["versus"] = (f"undecided ({dm:+.5f} +- {dh:.5f}: the noise {se:.5f} is over "
                               "a quarter of it)")
                quarter_failed += 1
            else:
                r["versus"] = f"{dm:+.5f} [{dm - dh:.5f}, {dm + dh:.5f}], noise {se:.5f}"
                decided += 1
                smallest = abs(dm) if smallest is None else min(smallest, abs(dm))
        have3 = all(r["rung3"] for r in rows)
        table = {
            "light": l, "shading": sh, "dual": dual, "rows": rows,
            "decided": decided, "pairs": len(rows) - 1, "quarter_failed": quarter_failed,
            "techniques": len(rows),
            "smallest_decided": smallest,
            "rho": spearman([r["r1"] for r in rows], [r["r2"] for r in rows]),
            "rho_scaled": spearman([r["r1"] for r in rows], [r["scaled"] for r in rows]),
            "rho3": spearman([r["r2"] for r in rows], [r["rung3"]["clean"] for r in rows])
            if have3 else None,
            "noise2": mean([r["noise"] for r in rows]),
            "noise3": mean([r["rung3"]["noise"] for r in rows]) if have3 else None,
            "mean_rung3": rows[0]["rung3"]["mean_reference"] if have3 else None,
        }
        if dual and all("dual" in r for r in rows):
            # Closer by more than float noise: behind the hair dual adds nothing and its error
            # equals single scattering's but for the last digits.
            table["dual_better"] = sum(r["dual"]["clean"] < r["rung3"]["clean"] * (1 - 1e-4)
                                       for r in rows)
        data["tables"].append(table)
        data["summary"].append({k: table.get(k) for k in
                                ("light", "shading", "decided", "pairs", "rho", "rho3",
                                 "dual_better", "techniques")})
# The sparse groom: rung 2 and rung 3 means per light, beside the dense groom's.
sparse = [json.loads(l) for l in open(os.path.join(tmp, "sparse.jsonl"))]
for l in lights:
    direction = next(k for k, v in placement.items() if v == l)
    by = {r["mode"]: r for r in sparse if r["light_direction"] == direction}
    dense = next((tb for tb in data["tables"] if tb["light"] == l), None)
    data["consistency"].append({
        "light": l, "strands": by["pbr:mode=single"]["sparse"],
        "single": by["pbr:mode=single"]["mean"], "single_noise": by["pbr:mode=single"]["noise"],
        "path": by["pbr:mode=path"]["mean"], "path_noise": by["pbr:mode=path"]["noise"],
        "ratio": by["pbr:mode=path"]["mean"] / by["pbr:mode=single"]["mean"],
        "raster": by["pbr:mode=single"]["image"],
        "dense_single": dense["rows"][0]["mean_reference"] if dense else None,
        "dense_path": dense["mean_rung3"] if dense else None,
        "dense_ratio": dense["mean_rung3"] / dense["rows"][0]["mean_reference"]
        if dense and dense["mean_rung3"] else None})
for tb in data["tables"]:
    print(f"light {tb['light']}, {tb['shading']}: {tb['decided']} of {tb['pairs']} pairs decided, "
          f"Spearman rung 1 vs 2 {tb['rho']}")
    for r in tb["rows"]:
        d = r.get("dual")
        print(f"  {r['shadow']:32s} r1 {r['r1']:.4f} r2 {r['r2']:.4f} r3 "
              f"{r['rung3']['clean'] if r['rung3'] else float('nan'):.4f} dual r3 "
              f"{d['clean'] if d else float('nan'):.4f}  {r['versus']}")
if out:
    json.dump(data, open(out, "w"), indent=1)
PY
