#!/usr/bin/env bash
# The error ladder measured (docs/physics-reference.md "The ladder"): suites/physics.json run
# once per reference seed (SEEDS, default 4) with one cache folder; each run's rung-2
# reference (pbr:mode=single, SPP samples per pixel, default 256) is an independent render, so
# the spread of a difference between two techniques' rung-2 errors over the seeds gives its
# 95% interval (Student's t). Then once more against rung 3 (pbr:mode=path, PATH_SPP samples,
# default 256, the same fibre with multiple scattering). SHADINGS: the shading specs, one row
# set each (default "chiang:opacity=fibre"; the dual-scattering rows are added by naming their
# spec here, SHADINGS="chiang:opacity=fibre chiang:opacity=fibre,scattering=dual"). Writes
# docs/physics-measured.md (or the file given): per light placement, shading and shadow
# technique the rung-1 error (against the rasterized exact reference), the rung-2 error (raw,
# reference noise removed, at the best exposure scale), the rung-3 error, the order of
# adjacent techniques against rung 2 with its interval or "undecided", and the rank
# correlation of the rung-1 and rung-2 orders.
# Usage: scripts/physics-reference.sh [OUT.md]   Needs build/strandbench and ../shared/models.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-docs/physics-measured.md}
seeds=${SEEDS:-4}
spp=${SPP:-256}
pathspp=${PATH_SPP:-256}
shadings=${SHADINGS:-chiang:opacity=fibre}
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
load_before=$(cut -d' ' -f1-3 /proc/loadavg)
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
t1=$(date +%s)
python3 - "$tmp" "$out" "$seeds" "$spp" "$pathspp" "$load_before" \
  "$(cut -d' ' -f1-3 /proc/loadavg)" "$((t1 - t0))" <<'PY'
import datetime, json, math, os, subprocess, sys
tmp, out, seeds, spp, pathspp, load0, load1, secs = sys.argv[1:]
seeds = int(seeds)
commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                        text=True).stdout.strip()
dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"],
                       capture_output=True, text=True).stdout.strip()
commit += " (with uncommitted changes)" if dirty else ""
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
    return num / den if den else float("nan")
first = runs[0][0]["error"]["pbr"]
ref = first["reference"]
p3 = path[0]["error"]["pbr"]["reference"]["pbr"]
lines = [
    "# The error ladder, measured",
    "",
    "<!-- generated by scripts/physics-reference.sh: do not edit by hand -->",
    "",
    "Written by `scripts/physics-reference.sh` (suite `suites/physics.json`, GL on llvmpipe). "
    f"Commit {commit}, {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC, "
    f"load {load0} before, {load1} after; {secs} s.",
    "",
    "```sh",
    f"SEEDS={seeds} SPP={spp} PATH_SPP={pathspp} SHADINGS=\"{' '.join(shadings)}\" "
    "scripts/physics-reference.sh",
    "   # = build/strandbench sweep suites/physics.json, once per reference seed, once vs path",
    "```",
    "",
    f"Scene `{runs[0][0]['scene']['spec']}` at {ref['size'][0]}x{ref['size'][1]}, primitive "
    f"`{params(runs[0][0]).get('primitive', 'world')}`, exact transparency (`abuffer`). "
    "Rung 1: the rasterized exact reference (same shading model; its exact shadow at the "
    "technique's map size). Rung 2: "
    f"`pbr:mode=single,spp={spp}` (traced single scattering, the Chiang fibre, world widths "
    f"({ref['pbr']['thickness_source']}, mean {ref['pbr']['thickness']:.3g}), shadow rays "
    f"{ref['pbr']['shadow_rays']}; tracer ambient {ref['pbr']['ambient']['tracer']}, raster "
    f"ambient {ref['pbr']['ambient']['raster']:g}), rendered {seeds} times with independent "
    f"seeds. Rung 3: `pbr:mode=path,spp={pathspp}` (the same fibre, multiple scattering, "
    f"{p3['spp']} samples, noise RMSE {path[0]['error']['pbr']['noise']['rmse']:.5f} at the "
    "first case), once.",
    "",
    "Columns: RMSE (linear RGB) against rung 1; against rung 2, the mean over the seeds and its "
    "95% half-width, the same with the reference's noise removed (sqrt(rmse^2 - noise^2)), and "
    "at the best exposure scale (the least-squares factor, given); the image means (image / "
    "rung 2); against rung 3, raw and at the best scale. Order: techniques by their rung-2 "
    "error; each adjacent pair's difference (this row minus the row above) with its 95% "
    "interval over the seeds. A pair is *decided* only where the interval excludes 0 and the "
    "reference's noise in that difference (its standard error over the seeds: the seeds differ "
    "only in the reference) is at most a quarter of the difference; otherwise *undecided*, "
    "with the reason.",
    "",
]
summary = []
for l in lights:
    for sh in shadings:
        rows = []
        for s in shadows:
            rs = cases.get((l, sh, s), [])
            if len(rs) != seeds:
                continue
            e2 = [r["error"]["pbr"] for r in rs]
            e3 = rung3[(l, sh, s)]["error"]["pbr"] if (l, sh, s) in rung3 else None
            rows.append({
                "shadow": s,
                "r1": rs[0]["error"]["image"]["rmse"],
                "r2": [e["rmse"] for e in e2],
                "clean": mean([e["noise"]["rmse_without_noise"] for e in e2]),
                "scaled": mean([e["scaled"]["rmse"] for e in e2]),
                "scale": mean([e["scaled"]["scale"] for e in e2]),
                "noise": mean([e["noise"]["rmse"] for e in e2]),
                "mimg": e2[0]["mean"]["image"], "mref": mean([e["mean"]["reference"] for e in e2]),
                "r3": e3["rmse"] if e3 else None,
                "r3s": e3["scaled"]["rmse"] if e3 else None,
                "r3n": e3["noise"]["rmse"] if e3 else None,
            })
        if not rows:
            continue
        rows.sort(key=lambda r: mean(r["r2"]))
        t = T95[seeds - 1]
        noise = mean([r["noise"] for r in rows])
        lines += [f"## Light {l}, shading `{sh}`", "",
                  "| shadow | vs rung 1 | vs rung 2 | rung 2, noise removed | rung 2 at best "
                  "scale (scale) | mean image / rung 2 | vs the row above (95%) | vs rung 3 "
                  "(at best scale) |",
                  "|---|---|---|---|---|---|---|---|"]
        decided = 0
        quarter_failed = 0
        for i, r in enumerate(rows):
            half = t * sd(r["r2"]) / math.sqrt(seeds)
            cmp = ""
            if i > 0:
                d = [a - b for a, b in zip(r["r2"], rows[i - 1]["r2"])]
                dm, se = mean(d), sd(d) / math.sqrt(seeds)
                dh = t * se
                if dm - dh <= 0 and dm + dh >= 0:
                    cmp = f"undecided ({dm:+.5f} +- {dh:.5f}: the interval holds 0)"
                elif se > abs(dm) / 4:
                    cmp = (f"undecided ({dm:+.5f} +- {dh:.5f}: the noise {se:.5f} is over a "
                           "quarter of it)")
                    quarter_failed += 1
                else:
                    cmp = f"{dm:+.5f} [{dm - dh:.5f}, {dm + dh:.5f}], noise {se:.5f}"
                    decided += 1
            r3 = (f"{r['r3']:.4f} ({r['r3s']:.4f})" if r["r3"] is not None else "-")
            lines.append(f"| {r['shadow']} | {r['r1']:.4f} | {mean(r['r2']):.4f} +- {half:.4f} "
                         f"| {r['clean']:.4f} | {r['scaled']:.4f} ({r['scale']:.3f}) | "
                         f"{r['mimg']:.5f} / {r['mref']:.5f} | {cmp} | {r3} |")
        rho = spearman([r["r1"] for r in rows], [mean(r["r2"]) for r in rows])
        rhoScaled = spearman([r["r1"] for r in rows], [r["scaled"] for r in rows])
        rho3 = (spearman([mean(r["r2"]) for r in rows], [r["r3"] for r in rows])
                if all(r["r3"] is not None for r in rows) else float("nan"))
        r3noise = mean([r["r3n"] for r in rows if r["r3n"] is not None] or [float("nan")])
        lines += ["",
                  f"Adjacent pairs decided at 95% with the noise at most a quarter of the "
                  f"difference: {decided} of {len(rows) - 1} ({quarter_failed} more have an "
                  "interval that excludes 0 but too much noise). Rank correlation (Spearman) of "
                  f"the rung-1 and rung-2 orders: {rho:.3f} (of rung 1 and rung 2 at the best "
                  f"scale: {rhoScaled:.3f}; of rung 2 and rung 3: {rho3:.3f}). The reference's "
                  f"pixel noise (RMSE of one seed's reference against its converged self): "
                  f"rung 2 {noise:.5f}, rung 3 {r3noise:.5f}; it adds almost equally to every "
                  "technique's error, so a difference moves far less than it from seed to seed: "
                  "the difference's own noise over the seeds is what decides a pair.", ""]
        summary.append((l, sh, decided, len(rows) - 1, rho))
lines += ["## Summary", "", "| light | shading | pairs decided | Spearman rung 1 vs rung 2 |",
          "|---|---|---|---|"]
lines += [f"| {l} | `{sh}` | {d} of {n} | {rho:.3f} |" for l, sh, d, n, rho in summary]
open(out, "w").write("\n".join(lines) + "\n")
print("wrote", out)
PY
